// The drive objects' access journal (cip/drive/drive_access_journal.h): call-order matching across
// execution passes, one access per call ever, refusals, deferral when the proxy's pool is full, limits,
// and the request lifecycle (started / finished / ready to retry).
#include <gtest/gtest.h>

#include <cstdint>

#include "cip/drive/drive_access_journal.h"
#include "drive_registers_fake.h"

namespace cip::drive {
namespace {

using drive_link::AccessError;
using drive_link::AccessResult;
using drive_link::WriteMode;
using drive_link::test::ScriptedDriveRegisters;
using Access = ScriptedDriveRegisters::Access;

class DriveJournalTest : public ::testing::Test {
 protected:
  // One execution pass of `requester`'s request: the server's OnRequestStarted, then a fresh context.
  RequestContext Pass(std::uint32_t requester = 1) {
    journal_.OnRequestStarted(requester);
    RequestContext context;
    context.requester = requester;
    return context;
  }
  static AccessResult Value(std::uint16_t value) { return AccessResult{AccessError::kNone, 0, value}; }

  ScriptedDriveRegisters drive_;
  DriveAccessJournal journal_{drive_};
};

TEST_F(DriveJournalTest, FirstCallStartsOneAccessAndPends) {
  RequestContext context = Pass();
  const JournalAnswer answer = journal_.Read(context, 0x0009);
  EXPECT_EQ(answer.state, JournalState::kPending);
  EXPECT_TRUE(context.pending);
  ASSERT_EQ(drive_.log.size(), 1u);
  EXPECT_EQ(drive_.log[0], (Access{false, 0x0009, 0, WriteMode::kRamOnly}));
  EXPECT_FALSE(journal_.ReadyToRetry(1));
  EXPECT_EQ(journal_.accesses_started(), 1u);
}

TEST_F(DriveJournalTest, RetryBeforeCompletionPendsWithoutASecondAccess) {
  RequestContext first = Pass();
  (void)journal_.Read(first, 0x0009);
  RequestContext again = Pass();
  EXPECT_EQ(journal_.Read(again, 0x0009).state, JournalState::kPending);
  EXPECT_TRUE(again.pending);
  EXPECT_EQ(drive_.log.size(), 1u);
}

TEST_F(DriveJournalTest, RetryAfterCompletionAnswersTheResult) {
  RequestContext first = Pass();
  (void)journal_.Read(first, 0x0009);
  ASSERT_TRUE(drive_.CompleteWith(Value(50)));
  EXPECT_TRUE(journal_.ReadyToRetry(1));
  EXPECT_EQ(journal_.completions(), 1u);

  RequestContext retry = Pass();
  const JournalAnswer answer = journal_.Read(retry, 0x0009);
  EXPECT_EQ(answer.state, JournalState::kDone);
  EXPECT_EQ(answer.result.error, AccessError::kNone);
  EXPECT_EQ(answer.result.number, 0x0009);
  EXPECT_EQ(answer.result.value, 50);
  EXPECT_FALSE(retry.pending);
  EXPECT_EQ(drive_.log.size(), 1u);
  // The same pass again (a second retry before the reply is produced) answers the same.
  RequestContext once_more = Pass();
  EXPECT_EQ(journal_.Read(once_more, 0x0009).result.value, 50);
  EXPECT_EQ(drive_.log.size(), 1u);
}

TEST_F(DriveJournalTest, AnAccessErrorIsADoneAnswer) {
  RequestContext first = Pass();
  (void)journal_.Write(first, 0x0009, 7000, WriteMode::kRamAndEeprom);
  ASSERT_TRUE(drive_.CompleteWith(AccessResult{AccessError::kOutOfRange, 0, 0}));
  RequestContext retry = Pass();
  const JournalAnswer answer = journal_.Write(retry, 0x0009, 7000, WriteMode::kRamAndEeprom);
  EXPECT_EQ(answer.state, JournalState::kDone);
  EXPECT_EQ(answer.result.error, AccessError::kOutOfRange);
  EXPECT_EQ(drive_.log, (std::vector<Access>{{true, 0x0009, 7000, WriteMode::kRamAndEeprom}}));
}

TEST_F(DriveJournalTest, CallsAreMatchedInOrderAndLaterCallsStartTheirAccesses) {
  RequestContext first = Pass();
  EXPECT_EQ(journal_.Read(first, 0x0003).state, JournalState::kPending);
  EXPECT_EQ(journal_.Read(first, 0x0004).state, JournalState::kPending);
  EXPECT_EQ(journal_.Write(first, 0xFA07, 6000, WriteMode::kRamOnly).state, JournalState::kPending);
  EXPECT_EQ(drive_.log.size(), 3u);

  ASSERT_TRUE(drive_.CompleteWith(Value(4)));
  EXPECT_FALSE(journal_.ReadyToRetry(1));  // two still on their way
  ASSERT_TRUE(drive_.CompleteWith(Value(7)));
  ASSERT_TRUE(drive_.CompleteWith(Value(6000)));
  EXPECT_TRUE(journal_.ReadyToRetry(1));

  RequestContext retry = Pass();
  EXPECT_EQ(journal_.Read(retry, 0x0003).result.value, 4);
  EXPECT_EQ(journal_.Read(retry, 0x0004).result.value, 7);
  EXPECT_EQ(journal_.Write(retry, 0xFA07, 6000, WriteMode::kRamOnly).result.value, 6000);
  EXPECT_FALSE(retry.pending);
  EXPECT_EQ(drive_.log.size(), 3u);
}

TEST_F(DriveJournalTest, AResultDecidesTheNextCall) {
  // A handler that reads, then writes what it read: the write is a new call of the retry.
  RequestContext first = Pass();
  (void)journal_.Read(first, 0x0856);
  ASSERT_TRUE(drive_.CompleteWith(Value(2)));
  RequestContext second = Pass();
  EXPECT_EQ(journal_.Read(second, 0x0856).result.value, 2);
  EXPECT_EQ(journal_.Write(second, 0x0009, 2, WriteMode::kRamAndEeprom).state, JournalState::kPending);
  EXPECT_TRUE(second.pending);
  EXPECT_EQ(drive_.log.size(), 2u);
}

TEST_F(DriveJournalTest, AMismatchIsRefusedAsInternal) {
  RequestContext first = Pass();
  (void)journal_.Read(first, 0x0003);
  (void)journal_.Write(first, 0x0009, 50, WriteMode::kRamAndEeprom);
  drive_.CompleteAll();

  RequestContext kind = Pass();
  const JournalAnswer other_kind = journal_.Write(kind, 0x0003, 0, WriteMode::kRamOnly);
  EXPECT_EQ(other_kind.state, JournalState::kRefused);
  EXPECT_EQ(other_kind.refusal, base::StatusCode::kInternal);

  RequestContext number = Pass();
  EXPECT_EQ(journal_.Read(number, 0x0004).refusal, base::StatusCode::kInternal);

  RequestContext value = Pass();
  EXPECT_EQ(journal_.Read(value, 0x0003).state, JournalState::kDone);
  EXPECT_EQ(journal_.Write(value, 0x0009, 51, WriteMode::kRamAndEeprom).refusal, base::StatusCode::kInternal);

  RequestContext mode = Pass();
  EXPECT_EQ(journal_.Read(mode, 0x0003).state, JournalState::kDone);
  EXPECT_EQ(journal_.Write(mode, 0x0009, 50, WriteMode::kRamOnly).refusal, base::StatusCode::kInternal);
  EXPECT_EQ(drive_.log.size(), 2u);  // nothing started for a mismatch
}

TEST_F(DriveJournalTest, LinkDownIsRefusedAtOnceAndTheSameOnEveryPass) {
  drive_.link_down = true;
  RequestContext first = Pass();
  const JournalAnswer answer = journal_.Read(first, 0xFD00);
  EXPECT_EQ(answer.state, JournalState::kRefused);
  EXPECT_EQ(answer.refusal, base::StatusCode::kFailedPrecondition);
  EXPECT_FALSE(first.pending);
  EXPECT_TRUE(drive_.log.empty());
  // The refusal holds the call's position: a later call of the same request still matches its entry.
  EXPECT_EQ(journal_.Read(first, 0xFD01).refusal, base::StatusCode::kFailedPrecondition);
  drive_.link_down = false;
  RequestContext second = Pass();
  EXPECT_EQ(journal_.Read(second, 0xFD00).refusal, base::StatusCode::kFailedPrecondition);
  EXPECT_EQ(journal_.Read(second, 0xFD01).refusal, base::StatusCode::kFailedPrecondition);
  EXPECT_TRUE(drive_.log.empty());
  journal_.OnRequestFinished(1);
  // The next request asks again.
  RequestContext next = Pass();
  EXPECT_EQ(journal_.Read(next, 0xFD00).state, JournalState::kPending);
}

TEST_F(DriveJournalTest, PoolFullWithNothingOfOursOnItsWayIsRefused) {
  drive_.busy_next = 1;
  RequestContext first = Pass();
  const JournalAnswer answer = journal_.Read(first, 0x0003);
  EXPECT_EQ(answer.state, JournalState::kRefused);
  EXPECT_EQ(answer.refusal, base::StatusCode::kResourceExhausted);
  EXPECT_FALSE(first.pending);
}

TEST_F(DriveJournalTest, PoolFullBehindOurOwnAccessDefersTheRestOfThePass) {
  RequestContext first = Pass();
  EXPECT_EQ(journal_.Read(first, 0x0003).state, JournalState::kPending);
  drive_.busy_next = 1;
  EXPECT_EQ(journal_.Read(first, 0x0004).state, JournalState::kPending);  // deferred, not refused
  EXPECT_EQ(journal_.Read(first, 0x0005).state, JournalState::kPending);  // nothing more this pass
  EXPECT_EQ(drive_.log.size(), 1u);
  EXPECT_EQ(drive_.busy_next, 0);
  EXPECT_FALSE(journal_.ReadyToRetry(1));

  ASSERT_TRUE(drive_.CompleteWith(Value(4)));
  EXPECT_TRUE(journal_.ReadyToRetry(1));
  RequestContext retry = Pass();
  EXPECT_EQ(journal_.Read(retry, 0x0003).result.value, 4);
  EXPECT_EQ(journal_.Read(retry, 0x0004).state, JournalState::kPending);
  EXPECT_EQ(journal_.Read(retry, 0x0005).state, JournalState::kPending);
  EXPECT_EQ(drive_.log, (std::vector<Access>{{false, 0x0003, 0, WriteMode::kRamOnly},
                                              {false, 0x0004, 0, WriteMode::kRamOnly},
                                              {false, 0x0005, 0, WriteMode::kRamOnly}}));
}

TEST_F(DriveJournalTest, MoreThanTheEntryLimitIsRefused) {
  RequestContext first = Pass();
  for (std::size_t i = 0; i < kMaxJournalEntries; ++i) {
    EXPECT_EQ(journal_.Read(first, static_cast<std::uint16_t>(i)).state, JournalState::kPending);
  }
  const JournalAnswer beyond = journal_.Read(first, 0x0100);
  EXPECT_EQ(beyond.state, JournalState::kRefused);
  EXPECT_EQ(beyond.refusal, base::StatusCode::kResourceExhausted);
  EXPECT_EQ(drive_.log.size(), kMaxJournalEntries);
  drive_.CompleteAll();
  RequestContext retry = Pass();
  for (std::size_t i = 0; i < kMaxJournalEntries; ++i) {
    EXPECT_EQ(journal_.Read(retry, static_cast<std::uint16_t>(i)).state, JournalState::kDone);
  }
  EXPECT_EQ(journal_.Read(retry, 0x0100).refusal, base::StatusCode::kResourceExhausted);
}

TEST_F(DriveJournalTest, RequestersAreIndependentUpToTheLimit) {
  for (std::uint32_t requester = 0; requester < kMaxJournalRequesters; ++requester) {
    RequestContext context = Pass(requester);
    EXPECT_EQ(journal_.Read(context, 0x0003).state, JournalState::kPending) << requester;
  }
  EXPECT_EQ(journal_.active_requesters(), kMaxJournalRequesters);
  RequestContext one_too_many = Pass(100);
  const JournalAnswer refused = journal_.Read(one_too_many, 0x0003);
  EXPECT_EQ(refused.state, JournalState::kRefused);
  EXPECT_EQ(refused.refusal, base::StatusCode::kResourceExhausted);
  EXPECT_EQ(journal_.requester_pool(),
            (base::PoolStats{kMaxJournalRequesters, kMaxJournalRequesters, kMaxJournalRequesters, 1}));

  // Completions reach the right requester.
  ASSERT_TRUE(drive_.CompleteWith(Value(10)));  // requester 0's
  EXPECT_TRUE(journal_.ReadyToRetry(0));
  EXPECT_FALSE(journal_.ReadyToRetry(1));
  journal_.OnRequestFinished(0);
  EXPECT_EQ(journal_.requester_pool().used, kMaxJournalRequesters - 1);
  RequestContext now_room = Pass(100);
  EXPECT_EQ(journal_.Read(now_room, 0x0003).state, JournalState::kPending);
  EXPECT_EQ(journal_.requester_pool().used, kMaxJournalRequesters);
}

TEST_F(DriveJournalTest, FinishedForgetsAndIgnoresLateCompletions) {
  RequestContext first = Pass();
  (void)journal_.Read(first, 0x0003);
  journal_.OnRequestFinished(1);
  EXPECT_EQ(journal_.active_requesters(), 0u);
  EXPECT_FALSE(journal_.ReadyToRetry(1));
  ASSERT_TRUE(drive_.CompleteWith(Value(4)));  // the proxy still delivers it
  EXPECT_EQ(journal_.completions(), 0u);
  EXPECT_EQ(journal_.completions_ignored(), 1u);
  EXPECT_FALSE(journal_.ReadyToRetry(1));

  // The requester's next request starts from nothing.
  RequestContext next = Pass();
  EXPECT_EQ(journal_.Read(next, 0x0003).state, JournalState::kPending);
  EXPECT_EQ(drive_.log.size(), 2u);
}

TEST_F(DriveJournalTest, LifecycleCallsForUnknownRequestersDoNothing) {
  journal_.OnRequestStarted(7);
  journal_.OnRequestFinished(7);
  EXPECT_FALSE(journal_.ReadyToRetry(7));
  EXPECT_EQ(journal_.active_requesters(), 0u);
  journal_.OnAccessDone(12345, Value(1));
  EXPECT_EQ(journal_.completions_ignored(), 1u);
}

TEST(DriveJournalLifetimeTest, DestructionCancelsItsCompletions) {
  ScriptedDriveRegisters drive;
  {
    DriveAccessJournal journal(drive);
    RequestContext context;
    (void)journal.Read(context, 0x0003);
    EXPECT_EQ(drive.pending(), 1u);
  }
  EXPECT_EQ(drive.cancels, 1);
  EXPECT_EQ(drive.pending(), 0u);
}

}  // namespace
}  // namespace cip::drive
