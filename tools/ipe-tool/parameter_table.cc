#include "parameter_table.h"

#include <cctype>

#include "sim/register_table.h"
#include "text.h"

namespace ipe {
namespace {

sim::Model ToSim(Model model) { return model == Model::kVfS15 ? sim::Model::kVfS15 : sim::Model::kVfMb1; }

const char* UnitText(sim::Unit unit) {
  switch (unit) {
    case sim::Unit::kHertz: return "Hz";
    case sim::Unit::kSecond: return "s";
    case sim::Unit::kPercent: return "%";
    case sim::Unit::kVolt: return "V";
    case sim::Unit::kAmpere: return "A";
    case sim::Unit::kKilowatt: return "kW";
    case sim::Unit::kKilowattHour: return "kWh";
    case sim::Unit::kHour: return "h";
    case sim::Unit::kDegreeCelsius: return "degC";
    case sim::Unit::kPulsesPerSecond: return "pps";
    case sim::Unit::kRpm: return "rpm";
    case sim::Unit::kNone:
    case sim::Unit::kBits:
    case sim::Unit::kAscii: return "";
  }
  return "";
}

ParameterInfo FromRegister(const sim::RegisterInfo& r, Model model) {
  const sim::Model m = ToSim(model);
  ParameterInfo info;
  info.number = r.number;
  info.title = r.title;
  info.function = r.function;
  info.unit = UnitText(r.scale.unit);
  info.bits = r.scale.unit == sim::Unit::kBits;
  info.decimals = r.scale.decimals;
  info.min = r.min(m);
  info.max = r.max(m);
  info.default_value = r.default_value(m);
  info.host_writable = r.HostWritable();
  info.setting = r.HostWritable() && r.storage == sim::StorageClass::kEeprom;
  info.monitor = r.storage == sim::StorageClass::kMonitor || r.storage == sim::StorageClass::kTripHold;
  info.write_during_run = r.write_during_run;
  info.effective_after_reset = r.effective_after_reset;
  info.is_signed = r.is_signed();
  return info;
}

}  // namespace

const char* ModelName(Model model) { return model == Model::kVfS15 ? "VF-S15" : "VF-MB1"; }

std::optional<Model> ModelFromName(std::string_view name) {
  if (EqualsIgnoringCase(name, "VF-MB1")) return Model::kVfMb1;
  if (EqualsIgnoringCase(name, "VF-S15")) return Model::kVfS15;
  return std::nullopt;
}

std::optional<ParameterInfo> FindParameter(std::string_view title, Model model) {
  const sim::RegisterInfo* r = sim::FindRegisterByTitle(title);
  if (r == nullptr || !r->AppliesTo(ToSim(model))) return std::nullopt;
  return FromRegister(*r, model);
}

std::vector<ParameterInfo> BackupParameters(Model model) {
  std::vector<ParameterInfo> out;
  for (const sim::RegisterInfo& r : sim::AllRegisters()) {
    if (!r.AppliesTo(ToSim(model))) continue;
    ParameterInfo info = FromRegister(r, model);
    if (info.setting) out.push_back(std::move(info));
  }
  return out;
}

}  // namespace ipe
