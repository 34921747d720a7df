// RegisterProxy: the pass (Poll/NextDeadline), the scheduling of the link between the proxy's own
// transactions and on-demand accesses, link state changes and the configuration load. The cyclic
// exchange is in scanner_exchange.cc, on-demand accesses in proxy_access.cc, loss actions in
// loss_actions.cc (docs/drive-link.md, "Register proxy").
#include "drive_link/register_proxy.h"

#include <algorithm>

#include "drive_link/drive_registers.h"

namespace drive_link {
namespace {

// F875-F879, read after kConfigNumbers: the block read selections in force. FD01 is read last, so the
// drive's status is known the moment the load ends (a card reset resets the inverter too: the status
// from before is gone, and the drive profile must not see "unknown" between the load and the first cycle).
constexpr std::uint16_t kF875 = 0x0875;
constexpr std::size_t kLoadReadCount = kConfigLoadReads;
constexpr std::size_t kFd01LoadIndex = kLoadReadCount - 1;
// F875-F879 choices 0-10 (seed 003 §4).
constexpr std::uint16_t kMaxBlockReadSelection = 10;

std::uint16_t LoadNumber(std::size_t index) {
  if (index == kFd01LoadIndex) return reg::kFd01;
  return index < config::kConfigNumberCount ? config::kConfigNumbers[index]
                                    : static_cast<std::uint16_t>(kF875 + (index - config::kConfigNumberCount));
}

}  // namespace

RegisterProxy::RegisterProxy(hal::SerialPort& port, const LinkConfig& link_config, const ProxyConfig& config)
    : link_(port, link_config, this), config_(config) {}

base::Status RegisterProxy::Start(hal::Micros now) {
  if (started_) return base::FailedPrecondition();
  if (base::Status status = link_.Start(now); !status.ok()) return status;
  started_ = true;
  now_ = now;
  // Requests wait in the link until its start-up silence is over.
  BeginLoad(/*card_reset=*/true);
  Schedule(now);
  return base::OkStatus();
}

void RegisterProxy::Poll(hal::Micros now) {
  if (!started_) return;
  now_ = now;
  wake_ = false;
  PollLoss(now);
  Schedule(now);
  // Completions arrive in OnComplete, which schedules the next transaction at once, so the link sends it
  // in this same Poll.
  link_.Poll(now);
  DeliverAccesses();
  if (notify_loaded_) {
    notify_loaded_ = false;
    if (config_listener_ != nullptr) config_listener_->OnConfigLoaded(parsed_);
  }
  // What the listeners asked for goes to the link now; it sends it on the next pass (NextDeadline says
  // "at once").
  Schedule(now);
}

hal::Micros RegisterProxy::NextDeadline() const {
  if (!started_) return hal::kNever;
  // Something to deliver or to schedule since the last pass: at once.
  if (wake_ || notify_loaded_) return now_;
  hal::Micros deadline = link_.NextDeadline();
  if (loss_ == LossState::kDelay && loaded_) deadline = std::min(deadline, LossDeadline());
  // The own slot idles only between cycles (min_cycle_period) or with nothing to do: wake for the next
  // cycle, display sample and loss-action refresh.
  if (own_request_ == kNoRequestId && loaded_ && !loading_ && !reset_on_link_ &&
      link_.state() != LinkState::kFault) {
    if (!cycle_active_) deadline = std::min(deadline, next_cycle_at_);
    deadline = std::min(deadline, next_display_at_);
    if (loss_action_active() && loss_action_written_ && loss_action_ != 4) {
      deadline = std::min(deadline, loss_action_written_at_ + config_.command_refresh_interval);
    }
    if (loss_action_active() && loss_action_ == 4 && stop_hold_valid_ && stop_hold_written_) {
      deadline = std::min(deadline, stop_hold_written_at_ + config_.command_refresh_interval);
    }
  }
  return deadline;
}

// ---- Scheduling --------------------------------------------------------------------------------------

void RegisterProxy::Schedule(hal::Micros now) {
  if (!started_ || link_.state() == LinkState::kFault) return;
  // While an access that resets the inverter (f899, fault reset) is on the link, nothing of the proxy's
  // own follows it: the master's command words must not reach an inverter that has just been reset.
  if (own_request_ == kNoRequestId && !reset_on_link_) {
    Job job;
    if (NextJob(now, job)) {
      const base::Result<RequestId> id = link_.Submit(job.transaction);
      if (id.ok()) {
        own_job_ = job;
        own_request_ = *id;
      }
    }
  }
  if (!access_on_link_) SubmitAccess();
}

// The proxy's own transactions in priority order. The link carries one of them and at most one on-demand
// access at a time, so with both kinds waiting its FIFO alternates them.
bool RegisterProxy::NextJob(hal::Micros now, Job& job) {
  if (loading_) return NextConfigRead(job);
  if (!loaded_) return false;
  PollLoss(now);  // a c100 that ran out during the load, or just now
  if (LossJob(now, job)) return true;
  if (UrgentCommandWrite(job)) return true;
  return CycleJob(now, job);
}

void RegisterProxy::OnComplete(RequestId id, const Completion& completion) {
  if (id == own_request_) {
    const Job job = own_job_;
    own_request_ = kNoRequestId;
    own_job_ = Job{};
    OnOwnComplete(job, completion);
  } else {
    for (Access& access : accesses_) {
      if (access.state == Access::State::kOnLink && access.request == id) {
        access_on_link_ = false;
        OnAccessComplete(access, completion);
        break;
      }
    }
  }
  Schedule(now_);
}

void RegisterProxy::OnOwnComplete(const Job& job, const Completion& completion) {
  switch (job.kind) {
    case JobKind::kNone:
      break;
    case JobKind::kConfigRead:
      OnConfigRead(job.index, completion);
      break;
    case JobKind::kLossCheck:
      OnLossCheckRead(job.index, completion);
      break;
    case JobKind::kLossAction:
      OnLossActionWritten(job.index, completion, now_);
      break;
    case JobKind::kCommandWrite:
      OnCommandWritten(job, completion);
      break;
    case JobKind::kBlockRead:
    case JobKind::kMonitorRead:
      OnMonitorRead(job, completion);
      break;
    case JobKind::kOwnedWrite:
      OnOwnedWritten(job.index, completion);
      break;
  }
}

void RegisterProxy::OnLinkStateChanged(LinkState previous, LinkState current) {
  if (current == LinkState::kFault) {
    // e-23: the link refuses requests and completes the queued ones with kLinkDown. An interrupted load
    // starts again from the beginning when the link is back; so does the cycle.
    loading_ = false;
    cycle_active_ = false;
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
    MarkCommandsUnknown();
    for (OwnedValue& value : owned_) value.written_valid = false;
  }
}

// ---- Configuration load ------------------------------------------------------------------------------

void RegisterProxy::BeginLoad(bool card_reset) {
  if (card_reset) {
    // Start-up or f899: the card starts afresh. Command words wait for the master's next words (the
    // drive command is given back and waits for the next SetDriveCommand), no loss is known; what the
    // front ends report from now on counts. Whether the drive feedback is wanted stays: it writes nothing.
    held_ = ScannerWords{};
    drive_command_ = DriveCommandWords{};
    armed_ = 0;
    claimed_ = false;
    scanner_mask_ = kAllScannerWords;
    drive_taken_ = false;
    fault_reset_edges_ = 0;
    loss_ = LossState::kNone;
    stop_hold_valid_ = false;
    c536_ = 0;
  }
  loading_ = true;
  loaded_ = false;
  load_index_ = 0;
  cycle_active_ = false;
  // Accesses not yet sent cannot be checked against a configuration that is being replaced.
  FailWaitingAccesses(AccessError::kLinkDown);
}

bool RegisterProxy::NextConfigRead(Job& job) {
  if (load_index_ >= kLoadReadCount) return false;
  job.kind = JobKind::kConfigRead;
  job.index = load_index_;
  job.transaction = Transaction::Read(LoadNumber(load_index_));
  return true;
}

void RegisterProxy::OnConfigRead(std::uint8_t index, const Completion& completion) {
  if (!loading_ || index != load_index_) return;  // a load abandoned by e-23
  if (completion.outcome == Outcome::kLinkDown) return;
  AccessResult& read = load_reads_[index];
  read = AccessResult{};
  read.number = LoadNumber(index);
  if (completion.ok()) {
    read.value = completion.data;
  } else if (completion.outcome == Outcome::kErrorReply) {
    switch (completion.error) {
      case wire::ErrorCode::kCommunicationNumberError:
        read.error = AccessError::kNoSuchRegister;
        break;
      case wire::ErrorCode::kDataError:
        read.error = AccessError::kOutOfRange;
        break;
      case wire::ErrorCode::kChecksumError:
        read.error = AccessError::kTimeout;
        break;
      case wire::ErrorCode::kImpossibleToExecute:
      case wire::ErrorCode::kCommandError:
        read.error = AccessError::kRefused;
        break;
    }
  } else {
    read.error = AccessError::kTimeout;
  }
  ++load_index_;
  if (load_index_ == kLoadReadCount) FinishLoad();
}

void RegisterProxy::FinishLoad() {
  parsed_ = config::ParseCardConfig(std::span<const AccessResult, config::kConfigNumberCount>(load_reads_.data(), config::kConfigNumberCount));
  // F875-F879: a value the inverter cannot hold is reported like a configuration problem and not used.
  for (std::size_t i = 0; i < kBlockReadSelections; ++i) {
    const AccessResult& read = load_reads_[config::kConfigNumberCount + i];
    const bool valid = read.ok() && read.value <= kMaxBlockReadSelection;
    block_selections_[i] = valid ? read.value : 0;
    if (valid) continue;
    config::ConfigProblem problem{read.number, read.value,
                          read.ok() ? config::ConfigProblem::Kind::kOutOfRange : config::ConfigProblem::Kind::kUnreadable,
                          read.error};
    if (parsed_.problem_count < parsed_.problems.size()) parsed_.problems[parsed_.problem_count++] = problem;
    ++parsed_.problems_total;
  }
  loading_ = false;
  loaded_ = true;
  ++counters_.config_loads;
  // An action in force is carried out again (after a link recovery the inverter may have lost it).
  loss_action_written_ = false;
  stop_hold_written_ = false;
  ApplyConfig();
  if (const AccessResult& fd01 = load_reads_[kFd01LoadIndex]; fd01.ok()) SetFd01(fd01.value);
  next_cycle_at_ = now_;
  next_display_at_ = now_;
  notify_loaded_ = true;
}

}  // namespace drive_link
