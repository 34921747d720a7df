#include "inverter_options.h"

#include <cctype>
#include <optional>

#include "register_names.h"

namespace sim {
namespace {

// NAME=VALUE with NAME a panel title or a communication number (letters and digits, at most 8) and
// VALUE a decimal or 0x-hex integer; what they mean is checked once the model is known (CheckPreset).
bool ParseParam(const std::string& text, InverterOptions& options) {
  const std::size_t eq = text.find('=');
  if (eq == std::string::npos || eq == 0 || eq > 8) return false;
  for (std::size_t i = 0; i < eq; ++i) {
    if (std::isalnum(static_cast<unsigned char>(text[i])) == 0) return false;
  }
  ParamPreset preset;
  preset.text = text;
  if (!ParseRegisterValue(std::string_view(text).substr(eq + 1), preset.value)) return false;
  options.params.push_back(preset);
  return true;
}

// A preset goes into the EEPROM of a new inverter, so it must name an EEPROM parameter hosts may write
// and lie within its static limits. Run-time limits (ul <= fh...) are the model's, when it is applied.
bool CheckPreset(ParamPreset& preset, Model model, std::string& reason) {
  const std::string name = preset.text.substr(0, preset.text.find('='));
  const RegisterInfo* info = ResolveRegister(name, model, reason);
  if (info == nullptr) return false;
  if (info->storage != StorageClass::kEeprom || !info->HostWritable()) {
    reason = std::string(info->title) + " is not a parameter hosts keep in the EEPROM (" +
             StorageClassName(info->storage) + (info->HostWritable() ? "" : ", not host-writable") + ")";
    return false;
  }
  reason = StaticRangeError(*info, model, preset.value);
  if (!reason.empty()) return false;
  preset.number = info->number;
  return true;
}

bool ParseMilliseconds(const std::string& text, int& out) {
  if (text.empty() || text.size() > 4) return false;
  for (char c : text) {
    if (std::isdigit(static_cast<unsigned char>(c)) == 0) return false;
  }
  out = std::stoi(text);
  return out <= 2000;
}

}  // namespace

const char kInverterOptionsUsage[] =
    "  --model vf-mb1|vf-s15              inverter model (default vf-mb1); each model has its own file\n"
    "  --param NAME|COMMNO=VALUE          preset a parameter (acc=50, 0009=50, c500=1; value in the\n"
    "                                     register's unit step); repeatable; presets for a new inverter:\n"
    "                                     applied only while DIR has no usable file for the model\n"
    "  --rs485-profile                    19200 baud 8E1 with the manual's 20 ms processing time\n"
    "  --sim-processing-ms N              the inverter's processing time, 0-2000 ms (default 2,\n"
    "                                     20 with --rs485-profile)\n";

bool TakeInverterSwitch(std::string_view flag, InverterOptions& options) {
  if (flag != "--rs485-profile") return false;
  options.rs485_profile = true;
  return true;
}

FlagOutcome TakeInverterFlag(std::string_view flag, const std::string& value, InverterOptions& options) {
  bool ok = true;
  if (flag == "--param") {
    ok = ParseParam(value, options);
  } else if (flag == "--model") {
    const std::optional<Model> model = ModelFromName(value);
    ok = model.has_value();
    if (ok) options.model = *model;
  } else if (flag == "--sim-processing-ms") {
    ok = ParseMilliseconds(value, options.sim_processing_ms);
  } else {
    return FlagOutcome::kNotOurs;
  }
  return ok ? FlagOutcome::kTaken : FlagOutcome::kInvalid;
}

bool CheckPresets(InverterOptions& options, std::string& error) {
  for (ParamPreset& preset : options.params) {
    std::string reason;
    if (!CheckPreset(preset, options.model, reason)) {
      error = "invalid value for --param: '" + preset.text + "' (" + reason + ")";
      return false;
    }
  }
  return true;
}

ServerConfig ServerConfigFromOptions(const InverterOptions& options) {
  ServerConfig config = options.rs485_profile ? Rs485Profile() : ServerConfig{};
  if (options.sim_processing_ms >= 0) {
    config.processing_delay = static_cast<hal::Micros>(options.sim_processing_ms) * hal::kMicrosPerMilli;
  }
  return config;
}

}  // namespace sim
