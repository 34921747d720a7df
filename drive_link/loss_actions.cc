// RegisterProxy: LossSupervision. The front end reports its network lost; after c100 the c103 condition
// is checked and the c101 action carried out over the link until the network returns (seed 000 §3.2.3;
// docs/drive-link.md, "Loss actions").
#include "drive_link/drive_registers.h"
#include "drive_link/register_proxy.h"

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

void RegisterProxy::NetworkLost(LossCause cause, hal::Micros now) {
  if (loss_ != LossState::kNone) return;
  loss_ = LossState::kDelay;
  lost_at_ = now;
  if (cause == LossCause::kModbusIoScanning) c536_ = 1;
  if (cause == LossCause::kCarrierLost) c536_ = 3;
  UpdateStatusValues();
  wake_ = true;
}

void RegisterProxy::NetworkRestored(hal::Micros /*now*/) {
  const bool was_acting = loss_action_active();
  loss_ = LossState::kNone;
  stop_hold_valid_ = false;  // the drive command (or the scanner words) decide again
  c536_ = 0;
  UpdateStatusValues();
  if (was_acting) {
    // The action overwrote FA06: every word is written again, but only once its master sends words
    // again (unless it already did while the action was in force): the scanner words at the next
    // SetCommandWords*, the drive command (still taken) at the next SetDriveCommand. A fault-reset edge
    // from before the action is stale now.
    MarkCommandsUnknown();
    armed_ = static_cast<std::uint8_t>(armed_ & words_during_action_);
    fault_reset_edges_ = static_cast<std::uint8_t>(fault_reset_edges_ & words_during_action_);
  }
  wake_ = true;
}

// From the report until the network is restored, unless c101 = 1 (continue) or c103 did not allow the
// action: the command the drive gets is the loss supervision's. An explicit run or speed command taken
// now would be overwritten when c100 runs out, or never written at all while the action is in force.
bool RegisterProxy::CommandsHeldByLoss() const {
  switch (loss_) {
    case LossState::kDelay:
    case LossState::kChecking:
      return config().loss_action != kActionContinue;
    case LossState::kActive:
      return loss_action_ != kActionContinue;
    case LossState::kNone:
    case LossState::kNotApplied:
      break;
  }
  return false;
}

void RegisterProxy::HoldStopDuringLoss(std::uint16_t fa06) {
  if (!CommandsHeldByLoss() || !reg::IsStopCommand(fa06)) return;
  stop_hold_ = With(fa06, 0, command_bit::kFaultReset);
  stop_hold_valid_ = true;
  // In force: written as the next own transaction. During c100 the front end's own write carries it.
  stop_hold_written_ = false;
  if (loss_action_ != kActionErr8) loss_action_written_ = false;
  wake_ = true;
}

bool RegisterProxy::loss_action_active() const {
  return loss_ == LossState::kActive && loss_action_ != kActionContinue;
}

// c100 counts from the front end's report, with the configuration in force; no decision is taken while
// no configuration is loaded (start-up, reload).
hal::Micros RegisterProxy::LossDeadline() const { return lost_at_ + config().loss_delay_tenths * kTenth; }

void RegisterProxy::PollLoss(hal::Micros now) {
  if (loss_ != LossState::kDelay || !loaded_ || now < LossDeadline()) return;
  // c103 = 1/2 need cmod and fmod as they are now (the panel may have changed them since the load): read
  // them first. c103 = 0 acts at once.
  checked_cmod_ = config().cmod;
  checked_fmod_ = config().fmod;
  if (config().loss_condition == 0) {
    DecideLossAction();
  } else {
    loss_ = LossState::kChecking;
    loss_check_index_ = 0;
  }
}

bool RegisterProxy::LossJob(hal::Micros now, Job& job) {
  if (loss_ == LossState::kChecking) {
    job.kind = JobKind::kLossCheck;
    job.index = loss_check_index_;
    job.transaction = Transaction::Read(loss_check_index_ == 0 ? reg::kCmod : reg::kFmod);
    return true;
  }
  if (!loss_action_active()) return false;
  // Written once, then again every command_refresh_interval (an inverter reset would forget FA06); the
  // err8 request only until the inverter has taken it, then a stop held meanwhile (index 1), refreshed.
  const hal::Micros refresh = config_.command_refresh_interval;
  if (loss_action_ == kActionErr8) {
    if (!loss_action_written_) {
      job.kind = JobKind::kLossAction;
      job.index = 0;
      job.transaction = Transaction::WriteRam(reg::kFa30, reg::kErr8TripCode);
      return true;
    }
    if (!stop_hold_valid_ || (stop_hold_written_ && now - stop_hold_written_at_ < refresh)) return false;
    job.kind = JobKind::kLossAction;
    job.index = 1;
    job.transaction = Transaction::WriteRam(reg::kFa06, stop_hold_);
    return true;
  }
  if (loss_action_written_ && now - loss_action_written_at_ < refresh) return false;
  job.kind = JobKind::kLossAction;
  job.index = 0;
  job.transaction = Transaction::WriteRam(reg::kFa06, LossActionFa06());
  return true;
}

void RegisterProxy::OnLossCheckRead(std::uint8_t index, const Completion& completion) {
  if (loss_ != LossState::kChecking || index != loss_check_index_) return;
  // A failed read leaves the value read at the configuration load.
  if (completion.ok()) {
    if (index == 0) checked_cmod_ = completion.data;
    if (index == 1) checked_fmod_ = completion.data;
  }
  ++loss_check_index_;
  if (loss_check_index_ == 2) DecideLossAction();
}

// c103: 0 always; 1 only when cmod and fmod both select a network; 2 = 1 and the drive runs (FD01 bit 10
// of the newest cycle). Evaluated once, when c100 has run out.
void RegisterProxy::DecideLossAction() {
  const std::uint16_t condition = config().loss_condition;
  const bool running = fd01_known_ && (fd01_ & reg::status_bit::kRunning) != 0;
  const bool network = NetworkModes(checked_cmod_, checked_fmod_);
  const bool applies = condition == 0 || (network && (condition == 1 || running));
  if (!applies) {
    loss_ = LossState::kNotApplied;
    return;
  }
  loss_ = LossState::kActive;
  loss_action_ = config().loss_action;
  loss_action_written_ = false;
  words_during_action_ = 0;
  ++counters_.loss_actions;
}

// FA06 for c101 = 0, 2, 3, 5, from the master's FA06 word as held when the action runs: the drive
// command's while it is taken (a scanner word on FA06 is not written then), else the first scanner word
// in use on FA06 that the master has sent, else the drive command's last FA06 if it was released since (the connection that
// held it closed before c100 ran out).
std::uint16_t RegisterProxy::LossActionFa06() const {
  // An explicit stop taken during the loss wins over the action (c101 = 5 would run the drive again).
  if (stop_hold_valid_) return stop_hold_;
  std::uint16_t held = drive_taken_ ? drive_command_.fa06 : released_fa06_valid_ ? released_fa06_ : 0;
  for (std::size_t w = 0; w < kScannerWordCount && !drive_taken_; ++w) {
    // Only a word the master has sent: one never sent wrote nothing to FA06.
    if (commands_[w].target == reg::kFa06 && CommandWordInUse(w) && (armed_ & (1U << w)) != 0) {
      held = held_[w];
      break;
    }
  }
  held = With(held, 0, command_bit::kFaultReset);
  switch (loss_action_) {
    case kActionStop:
      return 0;  // priorities released: cmod/fmod decide (and with cmod = 4 the option's run is off)
    case kActionDecelerate:
      return With(held, command_bit::kCommandPriority, command_bit::kRun | command_bit::kJog);
    case kActionCoast:
      return command_bit::kCommandPriority | command_bit::kCoastStop;
    case kActionPreset: {
      const std::uint16_t preset = config().loss_preset_speed;
      if (preset == 0) return With(held, command_bit::kCommandPriority | command_bit::kRun);
      return static_cast<std::uint16_t>(command_bit::kCommandPriority | command_bit::kRun |
                                        (preset & command_bit::kPresetMask));
    }
    default:
      break;
  }
  return held;
}

void RegisterProxy::OnLossActionWritten(std::uint8_t index, const Completion& completion, hal::Micros now) {
  ++counters_.loss_action_writes;
  if (!completion.ok()) ++counters_.loss_action_errors;
  if (!loss_action_active()) return;  // restored meanwhile
  // Taken or refused: done until the refresh (a refusal would not change on repetition). Unanswered: again.
  const bool done = completion.ok() || completion.outcome == Outcome::kErrorReply;
  if (index == 1) {
    stop_hold_written_ = done;
    stop_hold_written_at_ = now;
    return;
  }
  loss_action_written_ = done;
  loss_action_written_at_ = now;
}

}  // namespace drive_link
