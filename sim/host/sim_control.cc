#include "sim_control.h"

#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <system_error>

#include "register_names.h"
#include "sim/register_numbers.h"

namespace sim {
namespace {

// A delayed reply without a delay-ms: longer than the card's reply timeout (100 ms plus wire time,
// docs/drive-link.md), so the card sees a timeout and then the late reply as a stray frame.
constexpr std::uint32_t kDefaultDelayMs = 200;

struct NamedTrip {
  std::string_view name;
  std::uint8_t code;
};
constexpr std::array<NamedTrip, 4> kNamedTrips = {{
    {"E", trip_code::kEmergencyStop},
    {"err5", trip_code::kRs485Timeout},
    {"err8", trip_code::kOptionCommunication},
    {"e-23", trip_code::kOptionFault},
}};

// The usage of each command; nullptr for a verb that is not an inverter command.
const char* UsageOf(std::string_view verb) {
  if (verb == "get") return "get NAME|COMMNO";
  if (verb == "set") return "set NAME|COMMNO VALUE";
  if (verb == "terminal") return "terminal F|R|RES|S1|S2|S3|VIB|VIA|ST on|off";
  if (verb == "trip") return "trip CODE (1-255, or E, err5, err8, e-23)";
  if (verb == "inject") return "inject drop|delay|corrupt|silent [COUNT|until-cleared] [DELAY-MS], inject clear";
  if (verb == "status") return "status";
  return nullptr;
}

bool EqualsIgnoringCase(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (std::tolower(static_cast<unsigned char>(a[i])) != std::tolower(static_cast<unsigned char>(b[i]))) {
      return false;
    }
  }
  return true;
}

template <typename T>
bool ParseDecimal(std::string_view text, T& out) {
  const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), out);
  return ec == std::errc() && ptr == text.data() + text.size();
}

std::string Error(std::string_view reason) { return "error " + std::string(reason) + "\n"; }

void Get(std::string_view name, std::string& reply, SimulatedInverter& inverter) {
  std::string error;
  const RegisterInfo* info = ResolveRegister(name, inverter.model().model(), error);
  if (info == nullptr) {
    reply += Error(error);
    return;
  }
  const base::Result<std::uint16_t> word = inverter.model().Read(info->number);
  if (!word.ok()) {
    reply += Error(std::string(info->title) + ": no such register on this model");
    return;
  }
  reply += FormatRegisterValue(*info, *word) + "\nok\n";
}

// A panel write: RAM and EEPROM (W), refused where the model refuses a W.
void Set(std::string_view name, std::string_view value_text, std::string& reply, SimulatedInverter& inverter) {
  InverterModel& model = inverter.model();
  std::string error;
  const RegisterInfo* info = ResolveRegister(name, model.model(), error);
  if (info == nullptr) {
    reply += Error(error);
    return;
  }
  const std::string title = info->title;
  if (info->access == Access::kReadOnly) {
    reply += Error(title + " is read-only (" + StorageClassName(info->storage) + ")");
    return;
  }
  std::int32_t value = 0;
  if (!ParseRegisterValue(value_text, value)) {
    reply += Error("invalid value '" + std::string(value_text) + "' (a decimal or 0x-hex integer)");
    return;
  }
  error = StaticRangeError(*info, model.model(), value);
  if (!error.empty()) {
    reply += Error(title + ": " + std::to_string(value) + " " + error);
    return;
  }
  const WriteResult result = model.Write(info->number, info->ToWord(value), WriteTarget::kRamAndEeprom);
  switch (result.outcome) {
    case WriteOutcome::kOk:
      break;
    case WriteOutcome::kOutOfRange:
      reply += Error(title + ": " + std::to_string(value) + " refused by a run-time limit (data error)");
      return;
    case WriteOutcome::kNotWritableWhileRunning:
      reply += Error(title + ": not writable while the drive runs");
      return;
    default:
      reply += Error(title + ": " + WriteOutcomeName(result.outcome));
      return;
  }
  reply += FormatRegisterValue(*info, *model.Read(info->number)) + "\nok\n";
}

void TerminalCommand(std::string_view name, std::string_view state, std::string& reply, SimulatedInverter& inverter) {
  if (state != "on" && state != "off") {
    reply += Error(std::string("usage: ") + UsageOf("terminal"));
    return;
  }
  if (!inverter.model().SetTerminal(name, state == "on")) {
    reply += Error("unknown terminal '" + std::string(name) + "' (F R RES S1 S2 S3 VIB VIA ST)");
    return;
  }
  reply += "ok\n";
}

void Trip(std::string_view code_text, std::string& reply, SimulatedInverter& inverter) {
  int code = 0;
  for (const NamedTrip& trip : kNamedTrips) {
    if (EqualsIgnoringCase(code_text, trip.name)) code = trip.code;
  }
  if (code == 0 && (!ParseDecimal(code_text, code) || code < 1 || code > 255)) {
    reply += Error(std::string("usage: ") + UsageOf("trip"));
    return;
  }
  InverterModel& model = inverter.model();
  if (model.tripped()) {
    reply += Error("already tripped with code " + std::to_string(model.trip()) + " (the first trip holds)");
    return;
  }
  model.Trip(static_cast<std::uint8_t>(code));
  reply += "ok\n";
}

void Inject(std::span<const std::string_view> args, std::string& reply, SimulatedInverter& inverter) {
  const std::string usage = std::string("usage: ") + UsageOf("inject");
  if (args.size() == 1 && args[0] == "clear") {
    inverter.server().ClearFaults();
    reply += "ok\n";
    return;
  }
  Fault fault;
  bool known = false;
  for (Fault::Kind kind : {Fault::Kind::kDrop, Fault::Kind::kDelay, Fault::Kind::kCorrupt,
                                Fault::Kind::kSilent}) {
    if (!args.empty() && args[0] == FaultKindName(kind)) {
      fault.kind = kind;
      known = true;
    }
  }
  const bool delay = fault.kind == Fault::Kind::kDelay;
  if (!known || args.size() > (delay ? 3u : 2u)) {
    reply += Error(usage);
    return;
  }
  if (args.size() >= 2) {
    if (args[1] == "until-cleared") {
      fault.count = Fault::kUntilCleared;
    } else if (!ParseDecimal(args[1], fault.count) || fault.count == 0) {
      reply += Error("count must be 1 or more, or until-cleared; " + usage);
      return;
    }
  }
  std::uint32_t delay_ms = kDefaultDelayMs;
  if (args.size() == 3 && (!ParseDecimal(args[2], delay_ms) || delay_ms == 0 || delay_ms > 60000)) {
    reply += Error("delay must be 1-60000 ms");
    return;
  }
  if (delay) fault.delay_us = static_cast<hal::Micros>(delay_ms) * hal::kMicrosPerMilli;
  inverter.server().Inject(fault);
  reply += "ok\n";
}

// Signed 0.01 Hz as a JSON number with two decimals: -1234 -> -12.34.
std::string Hertz(std::int64_t centi_hz) {
  char text[24];
  const std::int64_t magnitude = centi_hz < 0 ? -centi_hz : centi_hz;
  std::snprintf(text, sizeof text, "%s%lld.%02lld", centi_hz < 0 ? "-" : "", static_cast<long long>(magnitude / 100),
                static_cast<long long>(magnitude % 100));
  return text;
}

std::string Hex(std::uint16_t word) {
  char text[8];
  std::snprintf(text, sizeof text, "0x%04X", static_cast<unsigned>(word));
  return text;
}

// Appends "name":value to a JSON object being built; `value` is JSON already (a number, or Quoted()).
void Field(std::string& json, std::string_view name, std::string_view value) {
  json += json.empty() ? "{\"" : ",\"";
  json += name;
  json += "\":";
  json += value;
}

// Our strings are names and hex words: nothing in them needs escaping.
std::string Quoted(std::string_view text) { return "\"" + std::string(text) + "\""; }

// Which command word's priority bit is set: FA06 (the option) wins over FA00 (RS485), as in the model.
const char* Priority(std::uint16_t fa06, std::uint16_t fa00, std::uint16_t bit) {
  if ((fa06 & bit) != 0) return "fa06";
  if ((fa00 & bit) != 0) return "fa00";
  return "none";
}

// A trip outranks the reset silence (a trip during the power-on second is still a trip); a fault
// reset clears the trip first, so it shows as "resetting".
const char* StateName(SimulatedInverter& inverter) {
  const InverterModel& model = inverter.model();
  if (model.tripped()) return "tripped";
  if (model.in_reset(inverter.clock().NowMicros())) return "resetting";
  if (model.running()) return "running";
  return "stopped";
}

}  // namespace

const char kSimControlHelp[] =
    "get NAME|COMMNO        an inverter register: get acc, get 0009 -> acc = 100 (0x0064)\n"
    "set NAME|COMMNO VALUE  write it as the panel does (RAM and EEPROM; decimal or 0x-hex)\n"
    "terminal NAME on|off   an input terminal: F R RES S1 S2 S3 VIB VIA ST\n"
    "trip CODE              trip the inverter: 1-255 or E, err5, err8, e-23\n"
    "inject KIND [COUNT|until-cleared] [DELAY-MS]\n"
    "                       damage the inverter's serial replies: KIND drop, delay (default\n"
    "                       200 ms), corrupt, silent; COUNT replies (default 1)\n"
    "inject clear           end every injected fault\n"
    "status                 the inverter's state as one JSON line\n";

std::string InverterStatusJson(SimulatedInverter& inverter) {
  const InverterModel& model = inverter.model();
  const DriveCommand cmd = model.command();
  const std::uint16_t fa06 = *model.Read(reg::kFa06);
  const std::uint16_t fa00 = *model.Read(reg::kFa00);
  std::uint64_t eeprom_writes = 0;
  for (const RegisterInfo& info : AllRegisters()) eeprom_writes += model.EepromWriteCount(info.number);

  std::string json;
  Field(json, "state", Quoted(StateName(inverter)));
  Field(json, "model", Quoted(ModelName(model.model())));
  Field(json, "output_hz", Hertz(std::llround(model.output_frequency_signed())));
  Field(json, "target_hz", Hertz(model.target_frequency()));
  Field(json, "command_source", Quoted(CommandSourceName(cmd.command_source)));
  Field(json, "frequency_source", Quoted(FrequencySourceName(cmd.frequency_source)));
  Field(json, "command_priority", Quoted(Priority(fa06, fa00, command_bit::kCommandPriority)));
  Field(json, "frequency_priority", Quoted(Priority(fa06, fa00, command_bit::kFrequencyPriority)));
  Field(json, "fa06", Quoted(Hex(fa06)));
  Field(json, "fa07", std::to_string(*model.Read(reg::kFa07)));
  Field(json, "fd01", Quoted(Hex(*model.Read(reg::kFd01))));
  Field(json, "trip", std::to_string(model.trip()));
  Field(json, "eeprom_writes", std::to_string(eeprom_writes));
  return json + "}";
}

bool HandleSimCommand(std::span<const std::string_view> words, std::string& reply, SimulatedInverter& inverter) {
  if (words.empty()) return false;
  const std::string_view verb = words[0];
  const std::size_t count = words.size();
  const char* usage = UsageOf(verb);
  if (usage == nullptr) return false;
  inverter.AdvanceToNow();  // answers and writes happen at the clock's now
  if (verb == "get" && count == 2) {
    Get(words[1], reply, inverter);
  } else if (verb == "set" && count == 3) {
    Set(words[1], words[2], reply, inverter);
  } else if (verb == "terminal" && count == 3) {
    TerminalCommand(words[1], words[2], reply, inverter);
  } else if (verb == "trip" && count == 2) {
    Trip(words[1], reply, inverter);
  } else if (verb == "inject") {
    Inject(words.subspan(1), reply, inverter);
  } else if (verb == "status" && count == 1) {
    reply += InverterStatusJson(inverter) + "\nok\n";
  } else {
    reply += Error(std::string("usage: ") + usage);
  }
  return true;
}

}  // namespace sim
