// RegisterProxy: DriveRegisters, the on-demand accesses of the front ends (docs/drive-link.md, "Register
// proxy"): local refusals, the pool, one access on the link at a time, error mapping, delivery from Poll.
#include <algorithm>

#include "drive_link/drive_registers.h"
#include "drive_link/register_proxy.h"

namespace drive_link {
namespace {

bool IsWrite(const Transaction& transaction) {
  return transaction.kind == TransactionKind::kWrite || transaction.kind == TransactionKind::kWriteRam;
}

// A write the inverter answers by resetting: f899 = 1, or the fault-reset bit of FA06/FA00.
bool ResetsInverter(const Transaction& transaction) {
  if (!IsWrite(transaction)) return false;
  if (transaction.comm_number == reg::kF899) return transaction.data == 1;
  return (transaction.comm_number == reg::kFa06 || transaction.comm_number == reg::kFa00) &&
         (transaction.data & reg::command_bit::kFaultReset) != 0;
}

// FA07 (the speed) or an FA06 that runs the drive; a stop on FA06 is never refused for a loss.
bool RunOrSpeedCommand(std::uint16_t number, std::uint16_t value) {
  return number == reg::kFa07 || (number == reg::kFa06 && !reg::IsStopCommand(value));
}

// Wrap-safe "a was accepted before b".
bool Before(std::uint32_t a, std::uint32_t b) { return static_cast<std::int32_t>(a - b) < 0; }

}  // namespace

base::Result<AccessToken> RegisterProxy::Read(std::uint16_t number, AccessListener& listener) {
  if (!started_ || link_.state() == LinkState::kFault) return base::FailedPrecondition();
  AccessError refusal = AccessError::kNone;
  if (!reg::HasDecimalLastDigit(number)) {
    refusal = AccessError::kNoSuchRegister;  // xxxA-xxxF do not exist (seed 000 §8.9 (5))
  } else if (!loaded_) {
    refusal = AccessError::kLinkDown;  // configuration not loaded yet (start-up, f899, after e-23)
  }
  return Accept(Transaction::Read(number), listener, refusal);
}

base::Result<AccessToken> RegisterProxy::Write(std::uint16_t number, std::uint16_t value, WriteMode mode,
                                               AccessListener& listener) {
  if (!started_ || link_.state() == LinkState::kFault) return base::FailedPrecondition();
  Transaction transaction = mode == WriteMode::kRamAndEeprom ? Transaction::Write(number, value)
                                                             : Transaction::WriteRam(number, value);
  // f899 = 1 resets the option and the drive: it is sent once and its reply is not waited for (the link
  // sets the same for FA06/FA00 fault resets itself).
  if (number == reg::kF899 && value == 1) transaction.expect_no_reply = true;
  AccessError refusal = AccessError::kNone;
  if (!reg::HasDecimalLastDigit(number)) {
    refusal = AccessError::kNoSuchRegister;
  } else if (reg::IsMonitorNumber(number) || IsOwnedNumber(number) || number == reg::kFa30) {
    refusal = AccessError::kReadOnly;  // FA30 is the card's own fault line (c101 = 4)
  } else if (!loaded_) {
    refusal = AccessError::kLinkDown;
  } else if (IsScannerTarget(number)) {
    refusal = AccessError::kReservedForScanner;  // IO scanning owns it (seed 000 §9.1)
  } else if (RunOrSpeedCommand(number, value) && CommandsHeldByLoss()) {
    refusal = AccessError::kNetworkLost;  // the loss action owns FA06: a success would be a lie
  }
  return Accept(transaction, listener, refusal);
}

void RegisterProxy::Cancel(AccessListener& listener) {
  for (Access& access : accesses_) {
    if (access.state == Access::State::kFree || access.listener != &listener) continue;
    if (access.state == Access::State::kOnLink) {
      access.listener = nullptr;  // runs to its end; the slot is freed then, silently
    } else {
      access = Access{};
    }
  }
}

base::Result<AccessToken> RegisterProxy::Accept(const Transaction& transaction, AccessListener& listener,
                                                AccessError local_refusal) {
  Access* slot = nullptr;
  for (Access& access : accesses_) {
    if (access.state == Access::State::kFree) {
      slot = &access;
      break;
    }
  }
  if (slot == nullptr) {
    ++counters_.pool_full;
    access_marks_.NoteRefused();
    return base::ResourceExhausted();
  }
  *slot = Access{};
  slot->state = Access::State::kWaiting;
  slot->token = next_token_;
  next_token_ = next_token_ == UINT32_MAX ? 1 : next_token_ + 1;
  slot->listener = &listener;
  slot->order = next_order_++;
  slot->transaction = transaction;
  slot->result.number = transaction.comm_number;
  ++counters_.accesses;
  access_marks_.NoteTaken(AccessesInUse());
  // A local refusal is delivered on the next Poll like any result, never from inside Read/Write.
  if (local_refusal != AccessError::kNone) FinishAccess(*slot, local_refusal, 0);
  wake_ = true;
  return slot->token;
}

std::size_t RegisterProxy::AccessesInUse() const {
  return static_cast<std::size_t>(std::count_if(accesses_.begin(), accesses_.end(),
                                                [](const Access& a) { return a.state != Access::State::kFree; }));
}

void RegisterProxy::FinishAccess(Access& access, AccessError error, std::uint16_t value) {
  access.state = Access::State::kDone;
  access.result.error = error;
  access.result.value = error == AccessError::kNone ? value : 0;
  if (error == AccessError::kNone) {
    ++counters_.accesses_ok;
  } else {
    ++counters_.access_errors[static_cast<std::size_t>(error)];
  }
}

// The oldest waiting access goes to the link; the next one follows when it has completed.
void RegisterProxy::SubmitAccess() {
  Access* next = nullptr;
  for (Access& access : accesses_) {
    if (access.state != Access::State::kWaiting) continue;
    if (next == nullptr || Before(access.order, next->order)) next = &access;
  }
  if (next == nullptr) return;
  const base::Result<RequestId> id = link_.Submit(next->transaction);
  if (id.ok()) {
    next->state = Access::State::kOnLink;
    next->request = *id;
    access_on_link_ = true;
    reset_on_link_ = ResetsInverter(next->transaction);
  } else if (id.status().code() != base::StatusCode::kResourceExhausted) {
    FinishAccess(*next, id.status().code() == base::StatusCode::kFailedPrecondition ? AccessError::kLinkDown
                                                                                    : AccessError::kRefused,
                 0);
  }
}

void RegisterProxy::OnAccessComplete(Access& access, const Completion& completion) {
  reset_on_link_ = false;
  const Transaction transaction = access.transaction;
  const AccessError error = MapError(access, completion);
  std::uint16_t value = completion.data;
  if (IsWrite(transaction) && completion.outcome == Outcome::kNoReply) value = transaction.data;
  // A stop written to FA06 while the loss holds it must not be undone by the action's next write.
  if (error == AccessError::kNone && IsWrite(transaction) && transaction.comm_number == reg::kFa06) {
    HoldStopDuringLoss(transaction.data);
  }
  if (access.listener == nullptr) {
    access = Access{};  // cancelled: nobody to tell
  } else {
    FinishAccess(access, error, value);
  }
  if (error != AccessError::kNone || !ResetsInverter(transaction)) return;
  if (transaction.comm_number == reg::kF899) {
    // f899 = 1 reset the option's configuration too: read it again once the inverter is back (the link
    // holds the reads until its reset silence is over), and start the card's state afresh.
    BeginLoad(/*card_reset=*/true);
  } else {
    MarkCommandsUnknown();  // a fault reset cleared FA06/FA07 in the inverter
  }
}

AccessError RegisterProxy::MapError(const Access& access, const Completion& completion) const {
  switch (completion.outcome) {
    case Outcome::kOk:
      return AccessError::kNone;
    case Outcome::kNoReply:
      // Expected for a reset (f899, fault reset); any other request lost in a quiet period timed out.
      return ResetsInverter(access.transaction) ? AccessError::kNone : AccessError::kTimeout;
    case Outcome::kTimeout:
      return AccessError::kTimeout;
    case Outcome::kLinkDown:
      return AccessError::kLinkDown;
    case Outcome::kErrorReply:
      break;
  }
  switch (completion.error) {
    case wire::ErrorCode::kCommunicationNumberError:
      return AccessError::kNoSuchRegister;
    case wire::ErrorCode::kDataError:
      return AccessError::kOutOfRange;
    case wire::ErrorCode::kImpossibleToExecute: {
      // 0000 on a parameter write while the drive runs: "cannot be changed during operation" (seed 003
      // §3.4); otherwise the inverter refused for a reason the card cannot name.
      const bool parameter = access.transaction.comm_number < reg::kFa00;
      const bool running = fd01_known_ && (fd01_ & reg::status_bit::kRunning) != 0;
      return IsWrite(access.transaction) && parameter && running ? AccessError::kNotWritableWhileRunning
                                                                 : AccessError::kRefused;
    }
    case wire::ErrorCode::kCommandError:
      return AccessError::kRefused;
    case wire::ErrorCode::kChecksumError:
      return AccessError::kTimeout;  // every attempt arrived damaged: the request never got through
  }
  return AccessError::kRefused;
}

void RegisterProxy::FailWaitingAccesses(AccessError error) {
  for (Access& access : accesses_) {
    if (access.state == Access::State::kWaiting) FinishAccess(access, error, 0);
  }
  wake_ = true;
}

// Completed accesses in acceptance order. The slot is freed before the listener runs, so it may start a
// new access; one finished during this delivery waits for the next Poll.
void RegisterProxy::DeliverAccesses() {
  std::array<AccessToken, kMaxPendingAccesses> due{};
  std::size_t count = 0;
  for (;;) {
    const Access* next = nullptr;
    for (const Access& access : accesses_) {
      if (access.state != Access::State::kDone) continue;
      bool taken = false;
      for (std::size_t i = 0; i < count; ++i) taken = taken || due[i] == access.token;
      if (taken) continue;
      if (next == nullptr || Before(access.order, next->order)) next = &access;
    }
    if (next == nullptr) break;
    due[count++] = next->token;
  }
  for (std::size_t i = 0; i < count; ++i) {
    for (Access& access : accesses_) {
      if (access.state != Access::State::kDone || access.token != due[i]) continue;
      AccessListener* listener = access.listener;
      const AccessToken token = access.token;
      const AccessResult result = access.result;
      access = Access{};
      if (listener != nullptr) listener->OnAccessDone(token, result);
      break;
    }
  }
}

}  // namespace drive_link
