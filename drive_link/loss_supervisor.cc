// LossSupervisor: the loss supervision. The front end reports its network lost; after c100 the c103 condition
// is checked and the c101 action carried out over the link until the network returns (seed 000 §3.2.3;
// docs/drive-link.md, "Loss actions").
#include "drive_link/drive_registers.h"
#include "drive_link/loss_supervisor.h"

namespace drive_link {
namespace {

namespace command_bit = reg::command_bit;

constexpr std::uint16_t kActionStop = 0;      // stop, cmod/fmod decide
constexpr std::uint16_t kActionContinue = 1;  // operation continues
constexpr std::uint16_t kActionDecelerate = 2;
constexpr std::uint16_t kActionCoast = 3;
constexpr std::uint16_t kActionErr8 = 4;      // network error stop: err8 trip
constexpr std::uint16_t kActionPreset = 5;    // preset speed c102

constexpr hal::Micros kTenth = 100 * hal::kMicrosPerMilli;

// c103 = 1: "both cmod and fmod are set to CANopen or communication option" (seed 000 §3.1).
bool NetworkModes(std::uint16_t cmod, std::uint16_t fmod) {
  return (cmod == 3 || cmod == 4) && (fmod == 6 || fmod == 7);
}

std::uint16_t With(std::uint16_t word, std::uint16_t set, std::uint16_t clear = 0) {
  return static_cast<std::uint16_t>((word & ~clear) | set);
}

}  // namespace

bool LossSupervisor::NetworkLost(LossCause cause, hal::Micros now) {
  if (state_ != State::kNone) return false;
  state_ = State::kDelay;
  lost_at_ = now;
  if (cause == LossCause::kModbusIoScanning) write_back_.SetEthernetError(1);
  if (cause == LossCause::kCarrierLost) write_back_.SetEthernetError(3);
  return true;
}

void LossSupervisor::NetworkRestored() {
  const bool was_acting = action_active();
  state_ = State::kNone;
  stop_hold_valid_ = false;  // the drive command (or the scanner words) decide again
  write_back_.SetEthernetError(0);
  // The action overwrote FA06: the command words are written again once their masters send.
  if (was_acting) exchange_.ResumeCommandWrites();
}

void LossSupervisor::CardReset() {
  state_ = State::kNone;
  stop_hold_valid_ = false;
  write_back_.SetEthernetError(0);
}

void LossSupervisor::OnConfigLoaded() {
  action_written_ = false;
  stop_hold_written_ = false;
}

// From the report until the network is restored, unless c101 = 1 (continue) or c103 did not allow the
// action: the command the drive gets is the loss supervision's. An explicit run or speed command taken
// now would be overwritten when c100 runs out, or never written at all while the action is in force.
bool LossSupervisor::CommandsHeldByLoss() const {
  switch (state_) {
    case State::kDelay:
    case State::kChecking:
      return loader_.config().loss_action != kActionContinue;
    case State::kActive:
      return action_ != kActionContinue;
    case State::kNone:
    case State::kNotApplied:
      break;
  }
  return false;
}

bool LossSupervisor::HoldStopDuringLoss(std::uint16_t fa06) {
  if (!CommandsHeldByLoss() || !reg::IsStopCommand(fa06)) return false;
  stop_hold_ = With(fa06, 0, command_bit::kFaultReset);
  stop_hold_valid_ = true;
  // In force: written as the next own transaction. During c100 the front end's own write carries it.
  stop_hold_written_ = false;
  if (action_ != kActionErr8) action_written_ = false;
  return true;
}

// c100 counts from the front end's report, with the configuration in force; no decision is taken while
// no configuration is loaded (start-up, reload).
hal::Micros LossSupervisor::LossDeadline() const { return lost_at_ + loader_.config().loss_delay_tenths * kTenth; }

hal::Micros LossSupervisor::Deadline() const {
  return state_ == State::kDelay && loader_.loaded() ? LossDeadline() : hal::kNever;
}

hal::Micros LossSupervisor::RefreshDeadline() const {
  if (!action_active()) return hal::kNever;
  const hal::Micros refresh = config_.command_refresh_interval;
  if (action_ != kActionErr8) return action_written_ ? action_written_at_ + refresh : hal::kNever;
  return stop_hold_valid_ && stop_hold_written_ ? stop_hold_written_at_ + refresh : hal::kNever;
}

void LossSupervisor::Poll(hal::Micros now) {
  if (state_ != State::kDelay || !loader_.loaded() || now < LossDeadline()) return;
  // c103 = 1/2 need cmod and fmod as they are now (the panel may have changed them since the load): read
  // them first. c103 = 0 acts at once.
  checked_cmod_ = loader_.config().cmod;
  checked_fmod_ = loader_.config().fmod;
  if (loader_.config().loss_condition == 0) {
    Decide();
  } else {
    state_ = State::kChecking;
    check_index_ = 0;
  }
}

bool LossSupervisor::NextJob(hal::Micros now, OwnJob& job) {
  if (state_ == State::kChecking) {
    job.kind = OwnJobKind::kLossCheck;
    job.index = check_index_;
    job.transaction = Transaction::Read(check_index_ == 0 ? reg::kCmod : reg::kFmod);
    return true;
  }
  if (!action_active()) return false;
  // Written once, then again every command_refresh_interval (an inverter reset would forget FA06); the
  // err8 request only until the inverter has taken it, then a stop held meanwhile (index 1), refreshed.
  const hal::Micros refresh = config_.command_refresh_interval;
  if (action_ == kActionErr8) {
    if (!action_written_) {
      job.kind = OwnJobKind::kLossAction;
      job.index = 0;
      job.transaction = Transaction::WriteRam(reg::kFa30, reg::kErr8TripCode);
      return true;
    }
    if (!stop_hold_valid_ || (stop_hold_written_ && now - stop_hold_written_at_ < refresh)) return false;
    job.kind = OwnJobKind::kLossAction;
    job.index = 1;
    job.transaction = Transaction::WriteRam(reg::kFa06, stop_hold_);
    return true;
  }
  if (action_written_ && now - action_written_at_ < refresh) return false;
  job.kind = OwnJobKind::kLossAction;
  job.index = 0;
  job.transaction = Transaction::WriteRam(reg::kFa06, ActionFa06());
  return true;
}

void LossSupervisor::OnCheckRead(std::uint8_t index, const Completion& completion) {
  if (state_ != State::kChecking || index != check_index_) return;
  // A failed read leaves the value read at the configuration load.
  if (completion.ok()) {
    if (index == 0) checked_cmod_ = completion.data;
    if (index == 1) checked_fmod_ = completion.data;
  }
  ++check_index_;
  if (check_index_ == 2) Decide();
}

// c103: 0 always; 1 only when cmod and fmod both select a network; 2 = 1 and the drive runs (FD01 bit 10
// of the newest cycle). Evaluated once, when c100 has run out.
void LossSupervisor::Decide() {
  const std::uint16_t condition = loader_.config().loss_condition;
  const bool running = exchange_.drive_running();
  const bool network = NetworkModes(checked_cmod_, checked_fmod_);
  const bool applies = condition == 0 || (network && (condition == 1 || running));
  if (!applies) {
    state_ = State::kNotApplied;
    return;
  }
  state_ = State::kActive;
  action_ = loader_.config().loss_action;
  action_written_ = false;
  // Every c101 but "continue" owns FA06: the master's command words are not written meanwhile.
  if (action_ != kActionContinue) exchange_.SuspendCommandWrites();
  ++counters_.loss_actions;
}

// FA06 for c101 = 0, 2, 3, 5, from the master's FA06 word as held when the action runs
// (ScannerExchange::HeldFa06: the drive command's while taken, else the first scanner word in use on
// FA06 that the master has sent, else the drive command's last FA06 if it was released since, the
// connection that held it having closed before c100 ran out).
std::uint16_t LossSupervisor::ActionFa06() const {
  // An explicit stop taken during the loss wins over the action (c101 = 5 would run the drive again).
  if (stop_hold_valid_) return stop_hold_;
  const std::uint16_t held = With(exchange_.HeldFa06(), 0, command_bit::kFaultReset);
  switch (action_) {
    case kActionStop:
      return 0;  // priorities released: cmod/fmod decide (and with cmod = 4 the option's run is off)
    case kActionDecelerate:
      return With(held, command_bit::kCommandPriority, command_bit::kRun | command_bit::kJog);
    case kActionCoast:
      return command_bit::kCommandPriority | command_bit::kCoastStop;
    case kActionPreset: {
      const std::uint16_t preset = loader_.config().loss_preset_speed;
      if (preset == 0) return With(held, command_bit::kCommandPriority | command_bit::kRun);
      return static_cast<std::uint16_t>(command_bit::kCommandPriority | command_bit::kRun |
                                        (preset & command_bit::kPresetMask));
    }
    default:
      break;
  }
  return held;
}

void LossSupervisor::OnActionWritten(std::uint8_t index, const Completion& completion, hal::Micros now) {
  ++counters_.loss_action_writes;
  if (!completion.ok()) ++counters_.loss_action_errors;
  if (!action_active()) return;  // restored meanwhile
  // Taken or refused: done until the refresh (a refusal would not change on repetition). Unanswered: again.
  const bool done = completion.ok() || completion.outcome == Outcome::kErrorReply;
  if (index == 1) {
    stop_hold_written_ = done;
    stop_hold_written_at_ = now;
    return;
  }
  action_written_ = done;
  action_written_at_ = now;
}

}  // namespace drive_link
