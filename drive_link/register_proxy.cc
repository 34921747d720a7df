// RegisterProxy: the composition of the proxy's parts. The pass (Poll/NextDeadline), the facades handed
// on to the part that owns each concern, the own slot's priorities, link state changes and the
// configuration load's start and end (docs/drive-link.md, "Register proxy").
#include "drive_link/register_proxy.h"

#include <algorithm>

#include "drive_link/drive_registers.h"

namespace drive_link {

RegisterProxy::RegisterProxy(hal::SerialPort& port, const LinkConfig& link_config, const ProxyConfig& config)
    : config_(config),
      write_back_(config_, counters_),
      exchange_(loader_, write_back_, config_, counters_,
                config.use_block_reads && link_config.mode == wire::Mode::kBinary),
      loss_(loader_, exchange_, write_back_, config_, counters_),
      accesses_(*this, counters_),
      scheduler_(port, link_config, accesses_, *this) {}

base::Status RegisterProxy::Start(hal::Micros now) {
  if (base::Status status = scheduler_.Start(now); !status.ok()) return status;
  now_ = now;
  // Requests wait in the link until its start-up silence is over.
  BeginLoad(/*card_reset=*/true);
  scheduler_.Schedule(now);
  return base::OkStatus();
}

void RegisterProxy::Poll(hal::Micros now) {
  if (!scheduler_.started()) return;
  now_ = now;
  wake_ = false;
  loss_.Poll(now);
  scheduler_.Schedule(now);
  scheduler_.Poll(now);
  accesses_.Deliver();
  if (notify_loaded_) {
    notify_loaded_ = false;
    if (config_listener_ != nullptr) config_listener_->OnConfigLoaded(loader_.parsed());
  }
  // What the listeners asked for goes to the link now; it sends it on the next pass (NextDeadline says
  // "at once").
  scheduler_.Schedule(now);
}

hal::Micros RegisterProxy::NextDeadline() const {
  if (!scheduler_.started()) return hal::kNever;
  // Something to deliver or to schedule since the last pass: at once.
  if (wake_ || notify_loaded_) return now_;
  hal::Micros deadline = std::min(scheduler_.NextDeadline(), loss_.Deadline());
  // The own slot idles only between cycles (min_cycle_period) or with nothing to do: wake for the next
  // cycle, display sample and loss-action refresh.
  if (scheduler_.own_slot_free() && loader_.loaded() && !loader_.loading() && !accesses_.reset_on_link() &&
      !scheduler_.link_fault()) {
    deadline = std::min({deadline, exchange_.NextCycleAt(), write_back_.next_display_at(), loss_.RefreshDeadline()});
  }
  return deadline;
}

// ---- Facades -----------------------------------------------------------------------------------------

base::Result<AccessToken> RegisterProxy::Read(std::uint16_t number, AccessListener& listener) {
  if (!scheduler_.started() || scheduler_.link_fault()) return base::FailedPrecondition();
  base::Result<AccessToken> token = accesses_.Read(number, listener);
  if (token.ok()) wake_ = true;
  return token;
}

base::Result<AccessToken> RegisterProxy::Write(std::uint16_t number, std::uint16_t value, WriteMode mode,
                                               AccessListener& listener) {
  if (!scheduler_.started() || scheduler_.link_fault()) return base::FailedPrecondition();
  base::Result<AccessToken> token = accesses_.Write(number, value, mode, listener);
  if (token.ok()) wake_ = true;
  return token;
}

void RegisterProxy::SetCommandWordsMasked(const ScannerWords& words, std::uint8_t mask) {
  exchange_.SetCommandWordsMasked(words, mask);
  wake_ = true;
}

void RegisterProxy::SetDriveCommand(const DriveCommandWords& words) {
  exchange_.SetDriveCommand(words);
  wake_ = true;
}

void RegisterProxy::ReleaseDriveCommand() {
  if (exchange_.ReleaseDriveCommand()) wake_ = true;
}

void RegisterProxy::SetFeedbackWanted(bool wanted) {
  if (exchange_.SetFeedbackWanted(wanted)) wake_ = true;
}

void RegisterProxy::HoldStopDuringLoss(std::uint16_t fa06) {
  if (loss_.HoldStopDuringLoss(fa06)) wake_ = true;
}

void RegisterProxy::NetworkLost(LossCause cause, hal::Micros now) {
  if (loss_.NetworkLost(cause, now)) wake_ = true;
}

void RegisterProxy::NetworkRestored(hal::Micros /*now*/) {
  loss_.NetworkRestored();
  wake_ = true;
}

void RegisterProxy::SetCardStatus(const config::CardStatus& status) {
  write_back_.SetCardStatus(status);
  wake_ = true;
}

// ---- What a completed access means to the rest -----------------------------------------------------

void RegisterProxy::OnWriteAccepted(std::uint16_t number, std::uint16_t value) {
  if (number == reg::kFa06) HoldStopDuringLoss(value);
}

void RegisterProxy::OnInverterReset(bool card_reset) {
  if (card_reset) {
    BeginLoad(/*card_reset=*/true);
  } else {
    exchange_.MarkCommandsUnknown();
  }
}

// ---- The own slot ------------------------------------------------------------------------------------

// The proxy's own transactions in priority order: the load, then the loss supervision, then a changed
// command word, then the cycle (with the write-backs between cycles).
bool RegisterProxy::NextOwnJob(hal::Micros now, OwnJob& job) {
  if (loader_.loading()) return loader_.NextRead(job);
  if (!loader_.loaded()) return false;
  loss_.Poll(now);  // a c100 that ran out during the load, or just now
  if (loss_.NextJob(now, job)) return true;
  if (exchange_.UrgentCommandWrite(now, job)) return true;
  return exchange_.CycleJob(now, job);
}

void RegisterProxy::OnOwnComplete(const OwnJob& job, const Completion& completion, hal::Micros now) {
  switch (job.kind) {
    case OwnJobKind::kNone:
      break;
    case OwnJobKind::kConfigRead:
      if (loader_.OnRead(job.index, completion)) FinishLoad(now);
      break;
    case OwnJobKind::kLossCheck:
      loss_.OnCheckRead(job.index, completion);
      break;
    case OwnJobKind::kLossAction:
      loss_.OnActionWritten(job.index, completion, now);
      break;
    case OwnJobKind::kCommandWrite:
      exchange_.OnCommandWritten(job, completion);
      break;
    case OwnJobKind::kBlockRead:
    case OwnJobKind::kMonitorRead:
      exchange_.OnMonitorRead(job, completion);
      break;
    case OwnJobKind::kOwnedWrite:
      write_back_.OnWritten(job.index, completion);
      break;
  }
}

void RegisterProxy::OnLinkStateChanged(LinkState previous, LinkState current) {
  if (current == LinkState::kFault) {
    // e-23: the link refuses requests and completes the queued ones with kLinkDown. An interrupted load
    // starts again from the beginning when the link is back; so does the cycle.
    loader_.Abandon();
    exchange_.AbandonCycle();
    FailWaitingAccesses(AccessError::kLinkDown);
    return;
  }
  if (current != LinkState::kUp) return;
  if (previous == LinkState::kFault) {
    // The inverter answers again after e-23. It may have been power-cycled meanwhile (parameters changed,
    // RAM values lost): read the configuration again and write everything back.
    BeginLoad(/*card_reset=*/false);
  } else if (previous == LinkState::kDegraded) {
    // A silence too short for e-23 may still have been an inverter reset (panel or terminal RES): the
    // inverter would have forgotten FA06/FA07. Write the command words and owned values again.
    exchange_.MarkCommandsUnknown();
    write_back_.MarkAllUnknown();
  }
}

// ---- Configuration load ------------------------------------------------------------------------------

void RegisterProxy::BeginLoad(bool card_reset) {
  if (card_reset) {
    // Start-up or f899: the card starts afresh. Command words wait for the master's next words (the
    // drive command is given back and waits for the next SetDriveCommand), no loss is known; what the
    // front ends report from now on counts. Whether the drive feedback is wanted stays: it writes nothing.
    exchange_.CardReset();
    loss_.CardReset();
  }
  loader_.Begin();
  exchange_.AbandonCycle();
  // Accesses not yet sent cannot be checked against a configuration that is being replaced.
  FailWaitingAccesses(AccessError::kLinkDown);
}

void RegisterProxy::FinishLoad(hal::Micros now) {
  ++counters_.config_loads;
  // An action in force is carried out again (after a link recovery the inverter may have lost it).
  loss_.OnConfigLoaded();
  exchange_.ApplyConfig(now);
  notify_loaded_ = true;
}

void RegisterProxy::FailWaitingAccesses(AccessError error) {
  accesses_.FailWaiting(error);
  wake_ = true;
}

}  // namespace drive_link
