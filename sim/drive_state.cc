// The simulated inverter's drive state: the command in force, ramps and time, and every computed
// monitor (FD01 and the rest). Part of InverterModel (inverter_model.h).
#include <algorithm>
#include <cmath>
#include <cstddef>

#include "sim/inverter_model.h"
#include "sim/register_numbers.h"

namespace sim {
namespace {

constexpr double kAmbientC = 25.0;
constexpr double kIgbtRiseAtRatedC = 30.0;        // IGBT rise over ambient at drive rated current
constexpr double kIgbtTimeConstantS = 60.0;       // first-order thermal lag
constexpr std::int32_t kDcBusPercent = 12780;     // FD04: 127.80 % (seed 004 §9 example)
constexpr double kMaxDecelerationSeconds = 0.1;   // FA23 bit 7: fh -> 0 in the shortest dec time

std::int32_t Round(double x) { return static_cast<std::int32_t>(std::lround(x)); }

std::int32_t Percent(double value, double rated, double scale) {
  return rated > 0.0 ? Round(value / rated * scale) : 0;
}

}  // namespace

// ---- Command ---------------------------------------------------------------------------------------

CommandInputs InverterModel::Inputs() const {
  CommandInputs in;
  in.fa06 = static_cast<std::uint16_t>(Value(reg::kFa06));
  in.fa07 = static_cast<std::uint16_t>(Value(reg::kFa07));
  in.fa23 = static_cast<std::uint16_t>(Value(reg::kFa23));
  in.fa00 = static_cast<std::uint16_t>(Value(reg::kFa00));
  in.fa01 = static_cast<std::uint16_t>(Value(reg::kFa01));
  in.cmod = Value(reg::kCmod);
  in.fmod = Value(reg::kFmod);
  in.f207 = Value(reg::kF207);
  in.f109 = Value(reg::kF109);
  for (std::size_t i = 0; i < in.terminal_functions.size(); ++i) {
    in.terminal_functions[i] = Value(static_cast<std::uint16_t>(reg::kF111 + i));
  }
  in.terminals = static_cast<std::uint8_t>(terminals_ & 0xFF);
  in.st_input = terminal(Terminal::kSt);
  in.panel_run = panel_run_;
  in.panel_reverse = panel_reverse_;
  in.panel_frequency = panel_frequency_;
  in.analog = analog_;
  in.fh = Value(reg::kFh);
  in.f268 = Value(reg::kF268);
  for (int n = 1; n <= 15; ++n) in.preset_speeds[static_cast<std::size_t>(n - 1)] = Value(reg::PresetSpeed(n));
  in.ignore_option = loss_ == Loss::kActive && loss_action_ == 0;
  return in;
}

DriveCommand InverterModel::command() const {
  DriveCommand cmd = ResolveCommand(Inputs());
  if (loss_ == Loss::kActive) {
    // c101 while the option's network is lost (seed 000 §3.1/§3.2.3); 0 is handled by ignore_option.
    const std::int32_t c102 = Value(reg::kC102);
    if (loss_action_ == 2) cmd.run = false;        // deceleration stop
    if (loss_action_ == 3) cmd.standby = false;    // coast stop
    if (loss_action_ == 5 && c102 != 0) {          // preset speed c102
      cmd.preset = c102;
      cmd.frequency = Value(reg::PresetSpeed(c102));
    }
  }
  return cmd;
}

bool InverterModel::RunEffective(const DriveCommand& cmd) const {
  return !tripped() && cmd.run && cmd.standby && !cmd.dc_braking && !cmd.max_deceleration_stop;
}

bool InverterModel::running() const { return RunEffective(command()) || output_ != 0.0; }

double InverterModel::TargetFrequency(const DriveCommand& cmd) const {
  if (!RunEffective(cmd)) return 0.0;
  const std::int32_t upper = std::min(Value(reg::kUl), Value(reg::kFh));
  const std::int32_t lower = std::min(Value(reg::kLl), upper);
  const std::int32_t f = cmd.jog ? std::min(cmd.frequency, upper) : std::clamp(cmd.frequency, lower, upper);
  return cmd.reverse ? -f : f;
}

std::int32_t InverterModel::target_frequency() const { return Round(TargetFrequency(command())); }

RampRates InverterModel::Rates(const DriveCommand& cmd) const {
  std::uint16_t acc = reg::kAcc;
  std::uint16_t dec = reg::kDec;
  if (cmd.pattern == AccDecPattern::kAd2) {
    acc = reg::kF500;
    dec = reg::kF501;
  } else if (cmd.pattern == AccDecPattern::kAd3) {
    acc = reg::kF510;
    dec = reg::kF511;
  }
  const double step_s = Value(reg::kF519) == 1 ? 0.01 : 0.1;  // f519 = 1: 0.01 s unit
  const double fh = Value(reg::kFh);
  RampRates rates;
  rates.acceleration = fh / (Value(acc) * step_s);
  rates.deceleration = fh / ((cmd.max_deceleration_stop ? kMaxDecelerationSeconds / step_s : Value(dec)) * step_s);
  return rates;
}

MotorParameters InverterModel::Motor(const DriveCommand& cmd) const {
  MotorParameters p;
  p.base_frequency_hz = Value(cmd.thr2 ? reg::kF170 : reg::kVl) / 100.0;
  p.base_voltage_v = Value(cmd.thr2 ? reg::kF171 : reg::kVlv) / 10.0;
  p.torque_boost = Value(cmd.thr2 ? reg::kF172 : reg::kVb) / 1000.0;
  p.rated_power_kw = Value(reg::kF405) / 100.0;
  p.rated_current_a = Value(reg::kF415) / 10.0;
  p.rated_speed_rpm = Value(reg::kF417);
  p.pole_pairs = Value(reg::kF856);
  p.drive_rated_current_a = Value(reg::kFe70) / 10.0;
  p.drive_rated_voltage_v = Value(reg::kFe71) / 10.0;
  return p;
}

Electrical InverterModel::electrical() const {
  if (tripped()) return {};
  const DriveCommand cmd = command();
  const RampRates rates = Rates(cmd);
  const int direction = RampDirection(output_, TargetFrequency(cmd));
  const double acceleration =
      direction > 0 ? rates.acceleration / 100.0 : (direction < 0 ? -rates.deceleration / 100.0 : 0.0);
  const bool dc_braking = cmd.dc_braking && cmd.standby;
  return ComputeElectrical(Motor(cmd), std::fabs(output_) / 100.0, acceleration, load_percent_ / 100.0,
                           dc_braking);
}

std::int32_t InverterModel::output_frequency() const { return Round(std::fabs(output_)); }

std::int32_t InverterModel::motor_speed_rpm() const {
  const int pole_pairs = Value(reg::kF856);
  return Round(electrical().speed_hz * 60.0 / pole_pairs);
}

void InverterModel::ApplyImmediateEffects() {
  // A trip, a coast stop (ST off) and DC braking cut the frequency output at once.
  const DriveCommand cmd = command();
  if (tripped() || !cmd.standby || cmd.dc_braking) output_ = 0.0;
}

// ---- Time ------------------------------------------------------------------------------------------

void InverterModel::Advance(hal::Micros now) {
  if (!time_known_) {
    time_known_ = true;
    now_ = now;
    if (pending_silence_ != 0) reset_until_ = now + pending_silence_;
    pending_silence_ = 0;
    if (loss_ == Loss::kPending) {
      loss_deadline_ += now;
      if (loss_deadline_ <= now) ApplyLossAction();
    }
    return;
  }
  if (now <= now_) return;
  if (loss_ == Loss::kPending && loss_deadline_ <= now) {
    AdvanceTo(std::max(loss_deadline_, now_));
    ApplyLossAction();
  }
  AdvanceTo(now);
}

void InverterModel::AdvanceTo(hal::Micros now) {
  if (now <= now_) return;
  const hal::Micros dt = now - now_;
  const double seconds = static_cast<double>(dt) / static_cast<double>(hal::kMicrosPerSecond);
  const DriveCommand cmd = command();
  const bool run = RunEffective(cmd);
  const Electrical before = electrical();

  const RampStep step = Ramp(output_, TargetFrequency(cmd), Rates(cmd), seconds);
  output_ = step.output;
  const Electrical after = electrical();

  power_on_us_ += dt;
  operation_us_ += run ? dt : std::min(dt, static_cast<hal::Micros>(std::llround(step.seconds_moving * 1e6)));
  if (cmd.energy_reset) {
    input_kwh_ = 0.0;  // FA23 bit 1 holds FE76/FE77 at 0
    output_kwh_ = 0.0;
  } else {
    input_kwh_ += (before.input_power_kw + after.input_power_kw) / 2.0 * seconds / 3600.0;
    output_kwh_ += std::max(0.0, before.output_power_kw + after.output_power_kw) / 2.0 * seconds / 3600.0;
  }
  const double load = after.current_a / (Value(reg::kFe70) / 10.0);
  const double settled = kAmbientC + kIgbtRiseAtRatedC * load * load;
  igbt_temperature_c_ = settled + (igbt_temperature_c_ - settled) * std::exp(-seconds / kIgbtTimeConstantS);
  now_ = now;
}

// ---- Monitors --------------------------------------------------------------------------------------

std::uint16_t InverterModel::StatusWord() const {
  const DriveCommand cmd = command();
  std::uint16_t w = 0;
  auto set = [&w](bool on, std::uint16_t bit) {
    if (on) w = static_cast<std::uint16_t>(w | bit);
  };
  set(AlarmWord() != 0, status_bit::kAlarm);
  set(cmd.thr2, status_bit::kThr2);
  set(cmd.pid_off, status_bit::kPidOff);
  set(cmd.pattern == AccDecPattern::kAd2, status_bit::kAd2);
  if (tripped()) {
    set(true, status_bit::kFailureFl);
    set(true, status_bit::kTripped);
    set(trip_ == trip_code::kEmergencyStop, status_bit::kEmergencyStopped);
    return w;
  }
  const bool run = RunEffective(cmd);
  set(cmd.dc_braking && cmd.standby, status_bit::kDcBraking);
  set(cmd.jog && run, status_bit::kJog);
  set(output_ < 0.0 || (output_ == 0.0 && run && cmd.reverse), status_bit::kReverse);
  set(run || output_ != 0.0, status_bit::kRunning);
  set(!cmd.standby, status_bit::kStOff);
  set(run, status_bit::kReadyStRun);  // ready, ST = ON and RUN = ON
  set(true, status_bit::kReady);      // initialised, no failure stop, no alarm stop
  return w;
}

std::uint16_t InverterModel::AlarmWord() const {
  std::uint16_t w = external_alarms_;
  if (loss_ != Loss::kNone) w = static_cast<std::uint16_t>(w | (1u << kAlarmBitOptionCommunication));
  return w;
}

std::uint16_t InverterModel::InputTerminalWord() const {
  // Bits 0-5 F..S3; VIB/VIA (6, 7) only as logic inputs (f109).
  const std::uint16_t mask = Value(reg::kF109) != 0 ? 0xFF : 0x3F;
  return static_cast<std::uint16_t>(terminals_ & mask);
}

std::uint16_t InverterModel::OutputTerminalWord() const {
  const DriveCommand cmd = command();
  const double target = TargetFrequency(cmd);
  const std::int32_t fa50 = Value(reg::kFa50);
  std::uint16_t w = 0;
  const std::uint16_t functions[3] = {reg::kF130, reg::kF131, reg::kF132};
  for (unsigned i = 0; i < 3; ++i) {
    const std::int32_t f = Value(functions[i]);
    bool on = false;
    switch (f & ~1) {
      case 4:  // LOW: low-speed signal (output above 0 Hz)
        on = output_ != 0.0;
        break;
      case 6:  // RCH: acceleration/deceleration complete
        on = RunEffective(cmd) && std::fabs(output_ - target) < 0.5;
        break;
      case 10:  // FL: failure
        on = tripped();
        break;
      case 92:  // specified data output 1 (FA50 bit 0)
        on = (fa50 & 1) != 0;
        break;
      case 94:  // specified data output 2 (FA50 bit 1)
        on = (fa50 & 2) != 0;
        break;
      default:
        continue;  // functions the simulator does not model stay off
    }
    if ((f & 1) != 0) on = !on;  // odd function numbers: inverted logic
    if (on) w = static_cast<std::uint16_t>(w | (1u << i));
  }
  return w;
}

std::int32_t InverterModel::EnergyRaw(double kwh) const {
  const double unit = 0.1 * std::pow(10.0, Value(reg::kF749));  // 0.1 kWh x 10^f749
  return static_cast<std::int32_t>(std::min(65535.0, std::floor(kwh / unit)));
}

std::int32_t InverterModel::LiveTripHoldValue(std::uint16_t number) const {
  switch (number) {
    case reg::kFe02: {
      const DriveCommand cmd = command();
      return std::min(cmd.frequency, std::min(Value(reg::kUl), Value(reg::kFh)));
    }
    case reg::kFe15:
      return MonitorValue(Info(reg::kFd00));
    case reg::kFe21:
      return Percent(electrical().excitation_current_a, Value(reg::kF415) / 10.0, 10000.0);
    default:
      break;
  }
  if (number >= reg::kFe10 && number <= reg::kFe13) return trip_history_[number - reg::kFe10];
  // FExx holds the FDxx of the same low byte (FE00 <- FD00, FE30 <- FD30).
  const RegisterInfo* live = FindRegister(static_cast<std::uint16_t>(0xFD00 | (number & 0xFF)));
  return live != nullptr ? MonitorValue(*live) : 0;
}

std::int32_t InverterModel::MonitorValue(const RegisterInfo& info) const {
  const std::uint16_t n = info.number;
  if (info.storage == StorageClass::kTripHold) {
    if (n >= reg::kFe10 && n <= reg::kFe13) return trip_history_[n - reg::kFe10];
    return tripped() ? held_[Index(info)] : LiveTripHoldValue(n);
  }
  switch (n) {
    case reg::kFc90:
      return trip_;
    case reg::kFc91:
      return AlarmWord();
    case reg::kFd00:
      return output_frequency();
    case reg::kFd01:
      return StatusWord();
    case reg::kFd04:
    case reg::kFe04:
      return kDcBusPercent;
    case reg::kFd06:
      return InputTerminalWord();
    case reg::kFd07:
      return OutputTerminalWord();
    case reg::kFd22:  // PID feedback: no PID control in the simulator
    case reg::kFd23:  // overload factors: no electronic-thermal model
    case reg::kFd24:
    case reg::kFd25:
    case reg::kFe56:  // no pulse train input
      return 0;
    case reg::kFd83:
      return Round(igbt_temperature_c_);
    case reg::kFe14:
      return static_cast<std::int32_t>(std::min<std::uint64_t>(operation_us_ / (3600 * hal::kMicrosPerSecond), 65535));
    case reg::kFe80:
      return static_cast<std::int32_t>(std::min<std::uint64_t>(power_on_us_ / (3600 * hal::kMicrosPerSecond), 65535));
    case reg::kFe35:
    case reg::kFe35 + 1:
    case reg::kFe35 + 2:
      return analog_[static_cast<std::size_t>(n - reg::kFe35)];
    case reg::kFe40: {
      const std::int32_t fmsl = Value(reg::kFmsl);
      if (fmsl == 18) return Value(reg::kFa51) * 10;  // communication data output (FA51 0-1000)
      if (fmsl == 0) return Percent(output_frequency(), Value(reg::kFh), 10000.0);  // output frequency
      return 0;
    }
    case reg::kFe76:
      return EnergyRaw(input_kwh_);
    case reg::kFe77:
      return EnergyRaw(output_kwh_);
    default:
      break;
  }
  const Electrical e = electrical();
  const double drive_current = Value(reg::kFe70) / 10.0;
  const double motor_current = Value(reg::kF415) / 10.0;
  switch (n) {
    case reg::kFd03:
      return Percent(e.current_a, drive_current, 10000.0);
    case reg::kFd05:
      return Percent(e.voltage_v, Value(reg::kFe71) / 10.0, 10000.0);
    case reg::kFd16:
      return Round(e.speed_hz * 100.0);
    case reg::kFd18:
    case reg::kFe18:
      return Round(e.torque_percent * 100.0);
    case reg::kFd20:
      return Percent(e.torque_current_a, motor_current, 10000.0);
    case reg::kFd26:
      return Percent(e.current_a, motor_current, 100.0);
    case reg::kFd27:
      return Percent(e.current_a, drive_current, 100.0);
    case reg::kFd29:
    case reg::kFe29:
      return Round(e.input_power_kw * 100.0);
    case reg::kFd30:
      return Round(std::max(0.0, e.output_power_kw) * 100.0);
    default:
      return ram_[Index(info)];  // stored values: FB05, FE08, FE70, FE71, FD67 (written by the option)
  }
}

}  // namespace sim
