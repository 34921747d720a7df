// AccessQueue: the on-demand accesses of the front ends (docs/drive-link.md, "Register proxy"): local
// refusals, the pool, one access on the link at a time, error mapping, delivery from Poll.
#include "drive_link/access_queue.h"

#include <algorithm>

#include "drive_link/card_write_back.h"
#include "drive_link/drive_registers.h"

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

AccessError AccessQueue::CheckRead(std::uint16_t number) const {
  if (!reg::HasDecimalLastDigit(number)) return AccessError::kNoSuchRegister;  // xxxA-xxxF (seed 000 §8.9 (5))
  if (!rules_.ConfigLoaded()) return AccessError::kLinkDown;  // start-up, f899, after e-23
  return AccessError::kNone;
}

AccessError CheckRegisterWrite(std::uint16_t number, std::uint16_t value, const AccessRules& rules) {
  if (!reg::HasDecimalLastDigit(number)) return AccessError::kNoSuchRegister;
  if (reg::IsMonitorNumber(number) || CardWriteBack::IsOwnedNumber(number) || number == reg::kFa30) {
    return AccessError::kReadOnly;  // FA30 is the card's own fault line (c101 = 4)
  }
  if (!rules.ConfigLoaded()) return AccessError::kLinkDown;
  if (rules.IsScannerTarget(number)) return AccessError::kReservedForScanner;  // IO scanning (seed 000 §9.1)
  if (RunOrSpeedCommand(number, value) && rules.CommandsHeldByLoss()) {
    return AccessError::kNetworkLost;  // the loss action owns FA06: a success would be a lie
  }
  return AccessError::kNone;
}

base::Result<AccessToken> AccessQueue::Read(std::uint16_t number, AccessListener& listener) {
  return Accept(Transaction::Read(number), listener, CheckRead(number));
}

base::Result<AccessToken> AccessQueue::Write(std::uint16_t number, std::uint16_t value, WriteMode mode,
                                             AccessListener& listener) {
  Transaction transaction = mode == WriteMode::kRamAndEeprom ? Transaction::Write(number, value)
                                                             : Transaction::WriteRam(number, value);
  // f899 = 1 resets the option and the drive: it is sent once and its reply is not waited for (the link
  // sets the same for FA06/FA00 fault resets itself).
  if (number == reg::kF899 && value == 1) transaction.expect_no_reply = true;
  return Accept(transaction, listener, CheckWrite(number, value));
}

void AccessQueue::Cancel(AccessListener& listener) {
  for (Access& access : accesses_) {
    if (access.state == Access::State::kFree || access.listener != &listener) continue;
    if (access.state == Access::State::kOnLink) {
      access.listener = nullptr;  // runs to its end; the slot is freed then, silently
    } else {
      access = Access{};
    }
  }
}

base::Result<AccessToken> AccessQueue::Accept(const Transaction& transaction, AccessListener& listener,
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
    marks_.NoteRefused();
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
  marks_.NoteTaken(InUse());
  // A local refusal is delivered on the next Poll like any result, never from inside Read/Write.
  if (local_refusal != AccessError::kNone) Finish(*slot, local_refusal, 0);
  return slot->token;
}

std::size_t AccessQueue::InUse() const {
  return static_cast<std::size_t>(std::count_if(accesses_.begin(), accesses_.end(),
                                                [](const Access& a) { return a.state != Access::State::kFree; }));
}

void AccessQueue::Finish(Access& access, AccessError error, std::uint16_t value) {
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
AccessQueue::Access* AccessQueue::OldestWaiting() {
  Access* next = nullptr;
  for (Access& access : accesses_) {
    if (access.state != Access::State::kWaiting) continue;
    if (next == nullptr || Before(access.order, next->order)) next = &access;
  }
  return next;
}

const Transaction* AccessQueue::NextToSend() {
  if (on_link_) return nullptr;
  const Access* next = OldestWaiting();
  return next == nullptr ? nullptr : &next->transaction;
}

void AccessQueue::Sent(RequestId request) {
  Access* next = OldestWaiting();
  if (next == nullptr) return;
  next->state = Access::State::kOnLink;
  next->request = request;
  on_link_ = true;
  reset_on_link_ = ResetsInverter(next->transaction);
}

void AccessQueue::SendRefused(base::StatusCode code) {
  Access* next = OldestWaiting();
  if (next == nullptr || code == base::StatusCode::kResourceExhausted) return;
  Finish(*next, code == base::StatusCode::kFailedPrecondition ? AccessError::kLinkDown : AccessError::kRefused, 0);
}

bool AccessQueue::OnComplete(RequestId request, const Completion& completion) {
  for (Access& access : accesses_) {
    if (access.state != Access::State::kOnLink || access.request != request) continue;
    on_link_ = false;
    Complete(access, completion);
    return true;
  }
  return false;
}

void AccessQueue::Complete(Access& access, const Completion& completion) {
  reset_on_link_ = false;
  const Transaction transaction = access.transaction;
  const AccessError error = MapError(access, completion);
  std::uint16_t value = completion.data;
  if (IsWrite(transaction) && completion.outcome == Outcome::kNoReply) value = transaction.data;
  if (access.listener == nullptr) {
    access = Access{};  // cancelled: nobody to tell
  } else {
    Finish(access, error, value);
  }
  if (error != AccessError::kNone || !IsWrite(transaction)) return;
  // A stop written to FA06 while the loss holds it must not be undone by the action's next write.
  rules_.OnWriteAccepted(transaction.comm_number, transaction.data);
  // f899 = 1 reset the option's configuration too: it is read again once the inverter is back (the link
  // holds the reads until its reset silence is over), and the card's state starts afresh. A fault reset
  // cleared FA06/FA07 in the inverter.
  if (ResetsInverter(transaction)) rules_.OnInverterReset(/*card_reset=*/transaction.comm_number == reg::kF899);
}

AccessError AccessQueue::MapError(const Access& access, const Completion& completion) const {
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
      const bool running = rules_.DriveRunning();
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

void AccessQueue::FailWaiting(AccessError error) {
  for (Access& access : accesses_) {
    if (access.state == Access::State::kWaiting) Finish(access, error, 0);
  }
}

// Completed accesses in acceptance order. The slot is freed before the listener runs, so it may start a
// new access; one finished during this delivery waits for the next Poll.
void AccessQueue::Deliver() {
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
