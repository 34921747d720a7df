// The drive objects' memory of the drive-link accesses a CIP request started (docs/drive-objects.md
// "The access journal and deferred replies"), which is what lets an explicit request wait for the inverter (docs/ethernetip.md
// "Deferred replies").
//
// A handler that needs a register does not own a buffer for the answer: the request is executed again
// from the start once its accesses have completed, and every pass makes the same calls in the same
// order. So the journal keeps, per requester, the list of accesses in call order and answers the n-th
// call of a pass from the n-th entry:
//
//   entry done             kDone with the drive's result (which may carry an AccessError)
//   entry on its way       kPending, context.pending = true
//   no entry yet           the access is started: kPending, context.pending = true; or, when it cannot
//                          start, kRefused (see below), recorded so that every later pass answers the
//                          same way and the calls after it keep their positions
//   entry of another kind, number, value or mode: kRefused/kInternal. A handler's calls depend only on the
//                          request bytes and on results it already got, so this is a bug, never the
//                          drive's doing; the object answers it as an error rather than starting an
//                          access nobody will collect (0x1F, RefusalStatus).
//
// Refusals (the object answers a CIP error at once, docs/drive-objects.md "Access errors"):
//   kResourceExhausted     the proxy's pool is full, the journal has no room for another requester, or
//                          the request made more than kMaxJournalEntries accesses: 0x02 resource
//                          unavailable (the originator may try again)
//   kFailedPrecondition    the drive link is down (e-23, configuration not loaded): the same answer as
//                          AccessError::kLinkDown, so a Get never waits on a link that cannot answer
//   kInternal              a mismatch as above
//
// Calls after one that pended still start their accesses: the proxy runs accesses in the order they
// were accepted, so several reads of one service (or of a packet, where the router goes on) cost one
// wait instead of several, and a read after a write of the same register still sees the written value.
// One exception: when the proxy's pool is full while accesses of this request are on their way, the
// call is deferred (kPending, nothing started or recorded) and so is every later call of the pass; the
// retry, once this request's accesses are done, starts it. A request may thus need more accesses than
// the pool holds. A pool full of other front ends' accesses is refused (kResourceExhausted), since no
// completion of this request would tell when to try again.
//
// Lifecycle (cip::RequestLifecycle, called by the encapsulation server): OnRequestStarted rewinds the
// requester's call position before every pass; OnRequestFinished forgets its entries. Accesses still on
// their way then run to their end in the proxy (a write on the wire cannot be taken back) and their
// completions are ignored, since no entry holds their token any more. ReadyToRetry: the requester has
// entries and none is on its way. Every request that touched the journal must be finished (also one
// answered at once with a refusal), or its entries stay and the requester's next request mismatches.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "base/pool_stats.h"
#include "base/status.h"
#include "cip/encapsulation_server.h"
#include "cip/explicit_messaging.h"
#include "drive_link/register_access.h"

namespace cip::drive {

// Requesters with a request in progress at a time: every TCP connection of the encapsulation server
// (one request each) plus requester 0 (no connection: tests, internal callers).
inline constexpr std::size_t kMaxJournalRequesters = kMaxTcpConnections + 1;
// Accesses one request may make (a Multiple Service Packet of Gets, a service reading several
// parameters). Beyond, each further access is refused with kResourceExhausted. With the requesters:
// 3,352 bytes in all on the card (10 requesters).
inline constexpr std::size_t kMaxJournalEntries = 16;

enum class JournalState : std::uint8_t { kDone, kPending, kRefused };

struct JournalAnswer {
  JournalState state = JournalState::kPending;
  drive_link::AccessResult result;                      // kDone: the drive's answer
  base::StatusCode refusal = base::StatusCode::kOk;      // kRefused: why (see above)
};

class DriveAccessJournal final : public drive_link::AccessListener, public RequestLifecycle {
 public:
  explicit DriveAccessJournal(drive_link::DriveRegisters& registers) : registers_(registers) {}
  ~DriveAccessJournal() override { registers_.Cancel(*this); }
  DriveAccessJournal(const DriveAccessJournal&) = delete;
  DriveAccessJournal& operator=(const DriveAccessJournal&) = delete;

  // The next access of context.requester's current pass (see the table above).
  JournalAnswer Read(RequestContext& context, std::uint16_t number);
  JournalAnswer Write(RequestContext& context, std::uint16_t number, std::uint16_t value,
                      drive_link::WriteMode mode);

  // cip::RequestLifecycle
  void OnRequestStarted(std::uint32_t requester) override;
  void OnRequestFinished(std::uint32_t requester) override;
  bool ReadyToRetry(std::uint32_t requester) const override;

  // drive_link::AccessListener
  void OnAccessDone(drive_link::AccessToken token, const drive_link::AccessResult& result) override;

  // Statistics: accesses started, completions recorded, completions that arrived after their request
  // was finished (ignored).
  std::uint32_t accesses_started() const { return started_; }
  std::uint32_t completions() const { return completions_; }
  std::uint32_t completions_ignored() const { return ignored_; }
  // Requesters that currently hold entries.
  std::size_t active_requesters() const;
  // The requester pool (docs/robustness.md "Exhaustion"); refused: a request answered 0x02 because no
  // requester slot was free.
  base::PoolStats requester_pool() const { return requester_marks_.Stats(active_requesters(), kMaxJournalRequesters); }

 private:
  enum class Kind : std::uint8_t { kRead, kWrite };
  enum class EntryState : std::uint8_t { kOnItsWay, kDone, kRefused };

  struct Entry {
    Kind kind = Kind::kRead;
    EntryState state = EntryState::kOnItsWay;
    drive_link::WriteMode mode = drive_link::WriteMode::kRamOnly;
    base::StatusCode refusal = base::StatusCode::kOk;
    std::uint16_t number = 0;
    std::uint16_t value = 0;  // write: the value asked for
    drive_link::AccessToken token = drive_link::kNoAccess;
    drive_link::AccessResult result;
  };

  struct RequesterJournal {
    bool in_use = false;
    std::uint32_t requester = 0;
    std::uint8_t count = 0;     // entries recorded
    std::uint8_t position = 0;  // calls made in the current pass
    bool deferred = false;      // the pool was full in this pass: later calls start nothing
    std::array<Entry, kMaxJournalEntries> entries{};
  };

  JournalAnswer Access(RequestContext& context, Kind kind, std::uint16_t number, std::uint16_t value,
                       drive_link::WriteMode mode);
  RequesterJournal* Find(std::uint32_t requester);
  const RequesterJournal* Find(std::uint32_t requester) const;
  RequesterJournal* FindOrClaim(std::uint32_t requester);
  static bool HasOnItsWay(const RequesterJournal& journal);

  drive_link::DriveRegisters& registers_;
  std::array<RequesterJournal, kMaxJournalRequesters> journals_{};
  std::uint32_t started_ = 0;
  std::uint32_t completions_ = 0;
  std::uint32_t ignored_ = 0;
  base::PoolWatermark requester_marks_;
};

}  // namespace cip::drive
