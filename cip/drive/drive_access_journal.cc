#include "cip/drive/drive_access_journal.h"

namespace cip::drive {

JournalAnswer DriveAccessJournal::Read(RequestContext& context, std::uint16_t number) {
  return Access(context, Kind::kRead, number, 0, drive_link::WriteMode::kRamOnly);
}

JournalAnswer DriveAccessJournal::Write(RequestContext& context, std::uint16_t number, std::uint16_t value,
                                        drive_link::WriteMode mode) {
  return Access(context, Kind::kWrite, number, value, mode);
}

JournalAnswer DriveAccessJournal::Access(RequestContext& context, Kind kind, std::uint16_t number,
                                         std::uint16_t value, drive_link::WriteMode mode) {
  JournalAnswer answer;
  RequesterJournal* journal = FindOrClaim(context.requester);
  if (journal == nullptr) {
    answer.state = JournalState::kRefused;
    answer.refusal = base::StatusCode::kResourceExhausted;
    return answer;
  }
  const std::size_t position = journal->position;
  if (position >= kMaxJournalEntries) {
    // Not recorded, but every pass reaches this position with the same calls: refused every time.
    answer.state = JournalState::kRefused;
    answer.refusal = base::StatusCode::kResourceExhausted;
    return answer;
  }
  journal->position = static_cast<std::uint8_t>(position + 1);

  if (position < journal->count) {
    const Entry& entry = journal->entries[position];
    const bool same = entry.kind == kind && entry.number == number &&
                      (kind == Kind::kRead || (entry.value == value && entry.mode == mode));
    if (!same) {
      answer.state = JournalState::kRefused;
      answer.refusal = base::StatusCode::kInternal;
      return answer;
    }
    switch (entry.state) {
      case EntryState::kDone:
        answer.state = JournalState::kDone;
        answer.result = entry.result;
        return answer;
      case EntryState::kRefused:
        answer.state = JournalState::kRefused;
        answer.refusal = entry.refusal;
        return answer;
      case EntryState::kOnItsWay:
        context.pending = true;
        answer.state = JournalState::kPending;
        return answer;
    }
  }

  // A new access. After a deferral (below) nothing more is started or recorded in this pass, so that
  // entry `position` is always entries[count]: every earlier pass recorded each position it reached.
  if (journal->deferred) {
    context.pending = true;
    answer.state = JournalState::kPending;
    return answer;
  }
  const base::Result<drive_link::AccessToken> token = kind == Kind::kRead
                                                          ? registers_.Read(number, *this)
                                                          : registers_.Write(number, value, mode, *this);
  if (!token.ok() && token.status().code() == base::StatusCode::kResourceExhausted && HasOnItsWay(*journal)) {
    // The pool is full, partly with this request's own accesses: wait for them and start this one on
    // the retry, instead of failing a request that only needs more room than the pool has at once.
    journal->deferred = true;
    context.pending = true;
    answer.state = JournalState::kPending;
    return answer;
  }
  Entry& entry = journal->entries[journal->count++];
  entry = Entry{};
  entry.kind = kind;
  entry.number = number;
  entry.value = value;
  entry.mode = mode;
  if (!token.ok()) {
    entry.state = EntryState::kRefused;
    // The facade names only these two; anything else is the facade's bug and is answered as one.
    const base::StatusCode code = token.status().code();
    entry.refusal = code == base::StatusCode::kResourceExhausted || code == base::StatusCode::kFailedPrecondition
                        ? code
                        : base::StatusCode::kInternal;
    answer.state = JournalState::kRefused;
    answer.refusal = entry.refusal;
    return answer;
  }
  ++started_;
  entry.state = EntryState::kOnItsWay;
  entry.token = token.value();
  context.pending = true;
  answer.state = JournalState::kPending;
  return answer;
}

void DriveAccessJournal::OnRequestStarted(std::uint32_t requester) {
  if (RequesterJournal* journal = Find(requester)) {
    journal->position = 0;
    journal->deferred = false;
  }
}

void DriveAccessJournal::OnRequestFinished(std::uint32_t requester) {
  // Entries on their way are dropped with the rest: their completions find no token and are ignored.
  if (RequesterJournal* journal = Find(requester)) *journal = RequesterJournal{};
}

bool DriveAccessJournal::ReadyToRetry(std::uint32_t requester) const {
  const RequesterJournal* journal = Find(requester);
  return journal != nullptr && journal->count > 0 && !HasOnItsWay(*journal);
}

bool DriveAccessJournal::HasOnItsWay(const RequesterJournal& journal) {
  for (std::size_t i = 0; i < journal.count; ++i) {
    if (journal.entries[i].state == EntryState::kOnItsWay) return true;
  }
  return false;
}

void DriveAccessJournal::OnAccessDone(drive_link::AccessToken token, const drive_link::AccessResult& result) {
  // The proxy numbers accesses from a running counter, so a token names at most one access on its way.
  for (RequesterJournal& journal : journals_) {
    if (!journal.in_use) continue;
    for (std::size_t i = 0; i < journal.count; ++i) {
      Entry& entry = journal.entries[i];
      if (entry.state != EntryState::kOnItsWay || entry.token != token) continue;
      entry.state = EntryState::kDone;
      entry.result = result;
      ++completions_;
      return;
    }
  }
  ++ignored_;
}

std::size_t DriveAccessJournal::active_requesters() const {
  std::size_t count = 0;
  for (const RequesterJournal& journal : journals_) count += journal.in_use ? 1 : 0;
  return count;
}

DriveAccessJournal::RequesterJournal* DriveAccessJournal::Find(std::uint32_t requester) {
  for (RequesterJournal& journal : journals_) {
    if (journal.in_use && journal.requester == requester) return &journal;
  }
  return nullptr;
}

const DriveAccessJournal::RequesterJournal* DriveAccessJournal::Find(std::uint32_t requester) const {
  for (const RequesterJournal& journal : journals_) {
    if (journal.in_use && journal.requester == requester) return &journal;
  }
  return nullptr;
}

DriveAccessJournal::RequesterJournal* DriveAccessJournal::FindOrClaim(std::uint32_t requester) {
  if (RequesterJournal* journal = Find(requester)) return journal;
  for (RequesterJournal& journal : journals_) {
    if (journal.in_use) continue;
    journal = RequesterJournal{};
    journal.in_use = true;
    journal.requester = requester;
    requester_marks_.NoteTaken(active_requesters());
    return &journal;
  }
  requester_marks_.NoteRefused();
  return nullptr;
}

}  // namespace cip::drive
