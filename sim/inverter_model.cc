// Registers, writes and their side effects, trips, resets, power cycles, inputs. The drive state
// (command, ramps, monitors) is in drive_state.cc, the EEPROM image in inverter_eeprom.cc.
#include "sim/inverter_model.h"

#include <algorithm>
#include <cctype>
#include <cstdlib>

#include "sim/register_numbers.h"

namespace sim {
namespace {

bool Rising(std::uint16_t old_word, std::uint16_t new_word, std::uint16_t mask) {
  return (old_word & mask) == 0 && (new_word & mask) != 0;
}

bool EqualsIgnoringCase(std::string_view a, std::string_view b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
           return std::tolower(static_cast<unsigned char>(x)) == std::tolower(static_cast<unsigned char>(y));
         });
}

bool InList(std::int32_t value, std::initializer_list<std::int32_t> list) {
  return std::find(list.begin(), list.end(), value) != list.end();
}

}  // namespace

const char* WriteOutcomeName(WriteOutcome outcome) {
  switch (outcome) {
    case WriteOutcome::kOk:
      return "ok";
    case WriteOutcome::kNoSuchRegister:
      return "no such register";
    case WriteOutcome::kOutOfRange:
      return "out of range";
    case WriteOutcome::kNotWritableWhileRunning:
      return "not writable while running";
    case WriteOutcome::kReadOnly:
      return "read-only";
  }
  return "?";
}

InverterModel::InverterModel(Model model, const ModelTiming& timing)
    : model_(model), timing_(timing), table_(AllRegisters()) {
  ram_.resize(table_.size());
  eeprom_.resize(table_.size());
  eeprom_writes_.assign(table_.size(), 0);
  active_.resize(table_.size());
  held_.assign(table_.size(), 0);
  for (std::size_t i = 0; i < table_.size(); ++i) eeprom_[i] = table_[i].default_value(model_);
  Reinitialise(timing_.power_on);
}

std::size_t InverterModel::Index(const RegisterInfo& info) const {
  return static_cast<std::size_t>(&info - table_.data());
}

const RegisterInfo& InverterModel::Info(std::uint16_t number) const {
  const RegisterInfo* info = FindRegister(number);
  if (info == nullptr) std::abort();  // a register_numbers.h constant missing from registers.csv
  return *info;
}

std::int32_t InverterModel::Value(std::uint16_t number) const { return ram_[Index(Info(number))]; }

void InverterModel::SetRam(std::uint16_t number, std::int32_t value) { ram_[Index(Info(number))] = value; }

// ---- Reads and writes ------------------------------------------------------------------------------

base::Result<std::uint16_t> InverterModel::Read(std::uint16_t number) const {
  const RegisterInfo* info = FindRegister(number, model_);
  if (info == nullptr) return base::NotFound();
  std::int32_t value = ram_[Index(*info)];
  if (info->storage == StorageClass::kMonitor || info->storage == StorageClass::kTripHold) {
    value = MonitorValue(*info);
  }
  return info->ToWord(std::clamp(value, info->min(model_), info->max(model_)));
}

WriteOutcome InverterModel::CheckRunTimeLimits(std::uint16_t number, std::int32_t value) const {
  const std::int32_t fh = Value(reg::kFh);
  bool ok = true;
  if (number == reg::kFa01 || number == reg::kUl) {
    ok = value <= fh;  // FA01: 0..fh (seed 003 §8.4); ul: at most fh
  } else if (number == reg::kLl) {
    ok = value <= Value(reg::kUl);
  } else if ((number >= reg::kSr1 && number <= 0x0024) || (number >= reg::kF287 && number <= 0x0294)) {
    ok = value <= fh;  // preset speeds up to fh; ll..ul applies when they run
  } else if (number == reg::kFa23) {
    ok = (value & ~static_cast<std::int32_t>(command2_bit::kDefined)) == 0;  // reserved bits: write 0
  } else if (number == reg::kFa30) {
    ok = value == 0 || value == trip_code::kOptionCommunication;  // the card's contract: 27 or 0
  } else if (number == reg::kC523) {
    ok = value == 0 || value >= 5;  // 0.0 = disabled or 0.5-60 s (seed 000 §3.2.3)
  } else if (number >= reg::kC001 && number <= 0xC006) {
    ok = !InList(value, {4, 7, 9, 10, 11, 12});  // reserved menu entries (seed 000 §3.1)
  } else if (number >= reg::kC021 && number <= 0xC026) {
    ok = !InList(value, {15, 16, 17, 18, 24});
  }
  return ok ? WriteOutcome::kOk : WriteOutcome::kOutOfRange;
}

WriteResult InverterModel::Write(std::uint16_t number, std::uint16_t word, WriteTarget target) {
  WriteResult result;
  const RegisterInfo* info = FindRegister(number, model_);
  if (info == nullptr) {
    result.outcome = WriteOutcome::kNoSuchRegister;
    return result;
  }
  if (info->access == Access::kReadOnly) {
    result.outcome = WriteOutcome::kReadOnly;
    return result;
  }
  const std::int32_t value = info->FromWord(word);
  if (!info->InRange(model_, value)) {
    result.outcome = WriteOutcome::kOutOfRange;
    return result;
  }
  result.outcome = CheckRunTimeLimits(number, value);
  if (!result.ok()) return result;
  if (!info->write_during_run && running()) {
    result.outcome = WriteOutcome::kNotWritableWhileRunning;
    return result;
  }

  const std::size_t i = Index(*info);
  const std::int32_t old_value = ram_[i];
  ram_[i] = value;
  if (info->storage == StorageClass::kEeprom && target == WriteTarget::kRamAndEeprom) {
    eeprom_[i] = value;
    ++eeprom_writes_[i];
    ++eeprom_generation_;
  }

  if (number == reg::kFa06 || number == reg::kFa00) {
    AfterCommandWrite(static_cast<std::uint16_t>(old_value), word, result);
  } else if (number == reg::kTyp) {
    ExecuteTyp(value);
    SetRam(reg::kTyp, 0);  // "reads 0 after execution"
  } else if (number == reg::kFa30) {
    // The option's fault line: 27 trips err8 as Trip(27) does; the register always reads 0 again.
    if (value == trip_code::kOptionCommunication) Trip(trip_code::kOptionCommunication);
    SetRam(reg::kFa30, 0);
  } else if (number == reg::kF899 && value == 1) {
    Reinitialise(timing_.reset);  // resets the option and the drive; f899 reads 0 again
  }
  ApplyImmediateEffects();
  return result;
}

void InverterModel::AfterCommandWrite(std::uint16_t old_word, std::uint16_t new_word, WriteResult& result) {
  // Fault reset acts on the 0 -> 1 edge only and gets no reply (seed 000 §3.2.4.2, §5.1.6 (5)); it works
  // without command priority (§5.1.6 example (5) writes 0x2000).
  if (Rising(old_word, new_word, command_bit::kFaultReset)) {
    result.no_reply = true;
    FaultReset();
  }
  // Emergency stop is always effective, whatever the priorities: "E" trip.
  if ((new_word & command_bit::kEmergencyStop) != 0) Trip(trip_code::kEmergencyStop);
}

void InverterModel::ExecuteTyp(std::int32_t choice) {
  auto set = [this](std::uint16_t number, std::int32_t value) {
    const std::size_t i = Index(Info(number));
    ram_[i] = value;
    if (eeprom_[i] != value) {
      eeprom_[i] = value;
      ++eeprom_writes_[i];
      ++eeprom_generation_;
    }
  };
  if (choice == 1 || choice == 2) {
    // 50 / 60 Hz default setting: the base and upper-limit frequencies (assumed list).
    const std::int32_t hz = choice == 1 ? 5000 : 6000;
    for (std::uint16_t number : {reg::kUl, reg::kVl, reg::kF170, reg::kF219, reg::kF814}) set(number, hz);
  } else if (choice == 3) {
    // Default setting 1 (initialisation): every parameter hosts may write back to its default.
    for (const RegisterInfo& r : table_) {
      if (r.storage == StorageClass::kEeprom && r.access == Access::kReadWrite) {
        set(r.number, r.default_value(model_));
      }
    }
  } else {
    return;  // other choices are not modelled
  }
  ResetRamOnlyHostRegisters();  // RAM-only command registers return to 0 with typ (seed 003 §13.9)
}

// ---- Trips and resets ------------------------------------------------------------------------------

void InverterModel::Trip(std::uint8_t code) {
  if (tripped() || code == trip_code::kNone) return;
  // Trip-hold registers keep the values from just before the trip (seed 003 §9 "*5").
  for (const RegisterInfo& r : table_) {
    if (r.storage == StorageClass::kTripHold) held_[Index(r)] = LiveTripHoldValue(r.number);
  }
  for (std::size_t i = trip_history_.size() - 1; i > 0; --i) trip_history_[i] = trip_history_[i - 1];
  trip_history_[0] = code;
  ++eeprom_generation_;
  trip_ = code;
  output_ = 0.0;  // the output is cut: the motor coasts
}

void InverterModel::ClearTrip() { trip_ = trip_code::kNone; }

bool InverterModel::FaultReset() {
  if (!tripped()) return false;
  // err8 and e-23 need a power cycle or f899 = 1 (seed 004 §5 for err8; e-23 assumed alike).
  if (trip_ == trip_code::kOptionCommunication || trip_ == trip_code::kOptionFault) return false;
  ClearTrip();
  ResetRamOnlyHostRegisters();  // FA00/FA06/FA07... back to 0: priorities must be re-asserted
  StartSilence(timing_.reset);
  return true;
}

void InverterModel::ResetRamOnlyHostRegisters() {
  for (const RegisterInfo& r : table_) {
    if (r.storage == StorageClass::kRamOnly && r.access == Access::kReadWrite) {
      ram_[Index(r)] = r.default_value(model_);
    }
  }
}

void InverterModel::Reinitialise(hal::Micros silence) {
  for (std::size_t i = 0; i < table_.size(); ++i) {
    const RegisterInfo& r = table_[i];
    ram_[i] = r.storage == StorageClass::kEeprom ? eeprom_[i] : r.default_value(model_);
    active_[i] = ram_[i];
  }
  ClearTrip();
  output_ = 0.0;
  panel_run_ = false;
  panel_reverse_ = false;
  loss_ = Loss::kNone;
  StartSilence(silence);
}

void InverterModel::PowerCycle() { Reinitialise(timing_.power_on); }

void InverterModel::StartSilence(hal::Micros duration) {
  if (time_known_) {
    reset_until_ = std::max(reset_until_, now_ + duration);
  } else {
    pending_silence_ = std::max(pending_silence_, duration);
  }
}

// ---- Inputs ----------------------------------------------------------------------------------------

void InverterModel::SetTerminal(Terminal t, bool on) {
  const bool reset_before = InputFunctionActive(Inputs(), input_function::kReset);
  const auto bit = static_cast<std::uint16_t>(1u << static_cast<unsigned>(t));
  terminals_ = static_cast<std::uint16_t>(on ? (terminals_ | bit) : (terminals_ & ~bit));
  if (!reset_before && InputFunctionActive(Inputs(), input_function::kReset)) FaultReset();
  ApplyImmediateEffects();
}

bool InverterModel::SetTerminal(std::string_view name, bool on) {
  static constexpr std::array<std::string_view, 9> kNames = {"F",  "R",  "RES", "S1", "S2",
                                                             "S3", "VIB", "VIA", "ST"};
  for (std::size_t i = 0; i < kNames.size(); ++i) {
    if (EqualsIgnoringCase(name, kNames[i])) {
      SetTerminal(static_cast<Terminal>(i), on);
      return true;
    }
  }
  return false;
}

bool InverterModel::terminal(Terminal t) const { return (terminals_ & (1u << static_cast<unsigned>(t))) != 0; }

void InverterModel::SetPanelFrequency(std::int32_t centi_hz) { panel_frequency_ = std::clamp(centi_hz, 0, 50000); }

void InverterModel::SetPanelRun(bool run, bool reverse) {
  panel_run_ = run;
  panel_reverse_ = reverse;
  ApplyImmediateEffects();
}

void InverterModel::SetAnalogInput(AnalogInput input, std::int32_t centi_percent) {
  const std::int32_t low = input == AnalogInput::kVib ? -10000 : 0;
  analog_[static_cast<std::size_t>(input)] = std::clamp(centi_percent, low, 10000);
}

void InverterModel::SetLoadTorque(std::int32_t centi_percent) { load_percent_ = std::clamp(centi_percent, 0, 20000); }

void InverterModel::SetAlarm(int bit, bool on) {
  if (bit < 0 || bit > 15) return;
  const auto mask = static_cast<std::uint16_t>(1u << bit);
  external_alarms_ = static_cast<std::uint16_t>(on ? (external_alarms_ | mask) : (external_alarms_ & ~mask));
}

// ---- Communication loss (seed 000 §3.2.3) ----------------------------------------------------------

void InverterModel::OptionCommunicationLost() {
  if (loss_ != Loss::kNone) return;
  loss_ = Loss::kPending;
  // c100: the error must last this long before c101 acts.
  loss_deadline_ = static_cast<hal::Micros>(Value(reg::kC100)) * 100 * hal::kMicrosPerMilli;
  if (time_known_) {
    loss_deadline_ += now_;
    if (loss_deadline_ <= now_) ApplyLossAction();
  }
}

void InverterModel::OptionCommunicationRestored() {
  loss_ = Loss::kNone;  // an err8 trip stays until a power cycle or f899 = 1
  ApplyImmediateEffects();
}

void InverterModel::ApplyLossAction() {
  // c103: 0 always; 1 only when cmod and fmod both select CANopen or the option; 2 = 1 and running.
  const std::int32_t c103 = Value(reg::kC103);
  const bool network_modes =
      InList(Value(reg::kCmod), {3, 4}) && InList(Value(reg::kFmod), {6, 7});
  const bool applies = c103 == 0 || (network_modes && (c103 == 1 || running()));
  loss_ = Loss::kActive;
  loss_action_ = applies ? Value(reg::kC101) : 1;  // 1 = operation continues
  if (loss_action_ == 4) Trip(trip_code::kOptionCommunication);  // network error stop: err8
  ApplyImmediateEffects();
}

}  // namespace sim
