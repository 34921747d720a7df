// drive_link::AccessQueue (drive_link/include/drive_link/access_queue.h): the one check of a register
// access (every local refusal and its order), the pool, one access on the link at a time in acceptance
// order, the mapping of the link's outcomes, delivery, cancel, and what a completed write tells the proxy.
#include "drive_link/access_queue.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <utility>
#include <vector>

#include "drive_link_part_fakes.h"

namespace drive_link::test {
namespace {

class Recorder final : public AccessListener {
 public:
  void OnAccessDone(AccessToken token, const AccessResult& result) override { done.emplace_back(token, result); }
  std::vector<std::pair<AccessToken, AccessResult>> done;
};

class DriveLinkAccessQueue : public ::testing::Test {
 protected:
  FakeAccessRules rules_;
  ProxyCounters counters_;
  AccessQueue queue_{rules_, counters_};
  Recorder listener_;

  // Sends the next access as `request` and completes it with `completion`.
  void SendAndComplete(RequestId request, const Completion& completion) {
    ASSERT_NE(queue_.NextToSend(), nullptr);
    queue_.Sent(request);
    EXPECT_TRUE(queue_.OnComplete(request, completion));
  }
};

TEST_F(DriveLinkAccessQueue, CheckWriteRefusesInItsOrder) {
  EXPECT_EQ(queue_.CheckWrite(0x000A, 1), AccessError::kNoSuchRegister);  // ends A-F
  EXPECT_EQ(queue_.CheckWrite(0xFD01, 1), AccessError::kReadOnly);        // a monitor
  EXPECT_EQ(queue_.CheckWrite(0xC536, 1), AccessError::kReadOnly);        // owned by the card
  EXPECT_EQ(queue_.CheckWrite(0xFA30, 27), AccessError::kReadOnly);       // the card's fault line
  EXPECT_EQ(queue_.CheckWrite(0x0009, 50), AccessError::kNone);
  rules_.scanner_target = 0xFA07;
  EXPECT_EQ(queue_.CheckWrite(0xFA07, 0x1770), AccessError::kReservedForScanner);
  rules_.held_by_loss = true;
  EXPECT_EQ(queue_.CheckWrite(0xFA06, 0xC400), AccessError::kNetworkLost);  // runs the drive
  EXPECT_EQ(queue_.CheckWrite(0xFA06, 0xC000), AccessError::kNone);         // a stop is never refused
  EXPECT_EQ(queue_.CheckWrite(0xFA07, 0x1770), AccessError::kReservedForScanner);
  rules_.scanner_target = 0;
  EXPECT_EQ(queue_.CheckWrite(0xFA07, 0x1770), AccessError::kNetworkLost);
  rules_.loaded = false;
  EXPECT_EQ(queue_.CheckWrite(0xFA07, 0x1770), AccessError::kLinkDown);
  EXPECT_EQ(queue_.CheckWrite(0xFD00, 0), AccessError::kReadOnly);  // read-only before "not loaded"
  EXPECT_EQ(queue_.CheckRead(0xFD00), AccessError::kLinkDown);
  rules_.loaded = true;
  EXPECT_EQ(queue_.CheckRead(0xFD00), AccessError::kNone);
  EXPECT_EQ(queue_.CheckRead(0xFD0F), AccessError::kNoSuchRegister);
}

TEST_F(DriveLinkAccessQueue, ALocalRefusalIsDeliveredOnlyByDeliver) {
  const base::Result<AccessToken> token = queue_.Write(0xFD01, 1, WriteMode::kRamOnly, listener_);
  ASSERT_TRUE(token.ok());
  EXPECT_EQ(*token, 1U);
  EXPECT_TRUE(listener_.done.empty());
  EXPECT_EQ(queue_.NextToSend(), nullptr);  // nothing goes to the link
  queue_.Deliver();
  ASSERT_EQ(listener_.done.size(), 1U);
  EXPECT_EQ(listener_.done[0].first, 1U);
  EXPECT_EQ(listener_.done[0].second.error, AccessError::kReadOnly);
  EXPECT_EQ(listener_.done[0].second.number, 0xFD01);
  EXPECT_EQ(counters_.access_errors[static_cast<std::size_t>(AccessError::kReadOnly)], 1U);
}

TEST_F(DriveLinkAccessQueue, OneOnTheLinkAtATimeInAcceptanceOrder) {
  ASSERT_TRUE(queue_.Read(0xFD00, listener_).ok());
  ASSERT_TRUE(queue_.Write(0x0009, 50, WriteMode::kRamAndEeprom, listener_).ok());
  const Transaction* first = queue_.NextToSend();
  ASSERT_NE(first, nullptr);
  EXPECT_EQ(first->kind, TransactionKind::kRead);
  EXPECT_EQ(first->comm_number, 0xFD00);
  queue_.Sent(7);
  EXPECT_TRUE(queue_.on_link());
  EXPECT_EQ(queue_.NextToSend(), nullptr);
  EXPECT_FALSE(queue_.OnComplete(8, OkCompletion(1)));  // not an access's request
  EXPECT_TRUE(queue_.OnComplete(7, OkCompletion(0x1770)));
  const Transaction* second = queue_.NextToSend();
  ASSERT_NE(second, nullptr);
  EXPECT_EQ(second->kind, TransactionKind::kWrite);
  EXPECT_EQ(second->comm_number, 0x0009);
  EXPECT_EQ(second->data, 50);
  queue_.Sent(9);
  EXPECT_TRUE(queue_.OnComplete(9, OkCompletion(50)));
  queue_.Deliver();
  ASSERT_EQ(listener_.done.size(), 2U);
  EXPECT_EQ(listener_.done[0].first, 1U);
  EXPECT_EQ(listener_.done[0].second.value, 0x1770);
  EXPECT_EQ(listener_.done[1].first, 2U);
  EXPECT_EQ(listener_.done[1].second.value, 50);
  EXPECT_EQ(counters_.accesses, 2U);
  EXPECT_EQ(counters_.accesses_ok, 2U);
  ASSERT_EQ(rules_.accepted.size(), 1U);
  EXPECT_EQ(rules_.accepted[0], std::make_pair(std::uint16_t{0x0009}, std::uint16_t{50}));
}

TEST_F(DriveLinkAccessQueue, ThePoolHoldsEightAccesses) {
  for (int i = 0; i < 8; ++i) ASSERT_TRUE(queue_.Read(0xFD00, listener_).ok());
  const base::Result<AccessToken> ninth = queue_.Read(0xFD00, listener_);
  ASSERT_FALSE(ninth.ok());
  EXPECT_EQ(ninth.status().code(), base::StatusCode::kResourceExhausted);
  EXPECT_EQ(counters_.pool_full, 1U);
  EXPECT_EQ(queue_.pool().capacity, 8U);
  EXPECT_EQ(queue_.pool().used, 8U);
}

TEST_F(DriveLinkAccessQueue, ErrorRepliesAreMapped) {
  ASSERT_TRUE(queue_.Write(0x0009, 50, WriteMode::kRamOnly, listener_).ok());
  SendAndComplete(1, ErrorCompletion(wire::ErrorCode::kImpossibleToExecute));
  rules_.running = true;
  ASSERT_TRUE(queue_.Write(0x0009, 50, WriteMode::kRamOnly, listener_).ok());
  SendAndComplete(2, ErrorCompletion(wire::ErrorCode::kImpossibleToExecute));
  ASSERT_TRUE(queue_.Write(0xFA07, 50, WriteMode::kRamOnly, listener_).ok());  // not a parameter
  SendAndComplete(3, ErrorCompletion(wire::ErrorCode::kImpossibleToExecute));
  ASSERT_TRUE(queue_.Read(0x0009, listener_).ok());
  SendAndComplete(4, ErrorCompletion(wire::ErrorCode::kDataError));
  ASSERT_TRUE(queue_.Read(0x0009, listener_).ok());
  SendAndComplete(5, ErrorCompletion(wire::ErrorCode::kCommunicationNumberError));
  ASSERT_TRUE(queue_.Read(0x0009, listener_).ok());
  SendAndComplete(6, ErrorCompletion(wire::ErrorCode::kChecksumError));
  ASSERT_TRUE(queue_.Read(0x0009, listener_).ok());
  SendAndComplete(7, OutcomeCompletion(Outcome::kNoReply));
  queue_.Deliver();
  ASSERT_EQ(listener_.done.size(), 7U);
  EXPECT_EQ(listener_.done[0].second.error, AccessError::kRefused);
  EXPECT_EQ(listener_.done[1].second.error, AccessError::kNotWritableWhileRunning);
  EXPECT_EQ(listener_.done[2].second.error, AccessError::kRefused);
  EXPECT_EQ(listener_.done[3].second.error, AccessError::kOutOfRange);
  EXPECT_EQ(listener_.done[4].second.error, AccessError::kNoSuchRegister);
  EXPECT_EQ(listener_.done[5].second.error, AccessError::kTimeout);
  EXPECT_EQ(listener_.done[6].second.error, AccessError::kTimeout);
  EXPECT_TRUE(rules_.accepted.empty());
}

TEST_F(DriveLinkAccessQueue, AResetWriteIsSentOnceAndTellsTheProxy) {
  ASSERT_TRUE(queue_.Write(0x0899, 1, WriteMode::kRamAndEeprom, listener_).ok());
  const Transaction* f899 = queue_.NextToSend();
  ASSERT_NE(f899, nullptr);
  EXPECT_TRUE(f899->expect_no_reply);
  queue_.Sent(1);
  EXPECT_TRUE(queue_.reset_on_link());
  EXPECT_TRUE(queue_.OnComplete(1, OutcomeCompletion(Outcome::kNoReply)));
  EXPECT_FALSE(queue_.reset_on_link());
  ASSERT_TRUE(queue_.Write(0xFA06, 0x2000, WriteMode::kRamOnly, listener_).ok());
  SendAndComplete(2, OutcomeCompletion(Outcome::kNoReply));
  queue_.Deliver();
  ASSERT_EQ(listener_.done.size(), 2U);
  EXPECT_TRUE(listener_.done[0].second.ok());
  EXPECT_EQ(listener_.done[0].second.value, 1);  // the value sent: no echo came
  EXPECT_TRUE(listener_.done[1].second.ok());
  EXPECT_EQ(listener_.done[1].second.value, 0x2000);
  EXPECT_EQ(rules_.resets, (std::vector<bool>{true, false}));
  ASSERT_EQ(rules_.accepted.size(), 2U);
  EXPECT_EQ(rules_.accepted[1], std::make_pair(std::uint16_t{0xFA06}, std::uint16_t{0x2000}));
}

TEST_F(DriveLinkAccessQueue, CancelForgetsTheListenerAndFailWaitingEndsTheRest) {
  Recorder other;
  ASSERT_TRUE(queue_.Read(0xFD00, listener_).ok());
  ASSERT_TRUE(queue_.Read(0xFD01, listener_).ok());
  ASSERT_TRUE(queue_.Read(0xFD03, other).ok());
  queue_.Sent(1);             // FD00 is on the link
  queue_.Cancel(listener_);   // FD01 is dropped; FD00 runs to its end silently
  EXPECT_EQ(queue_.pool().used, 2U);
  queue_.FailWaiting(AccessError::kLinkDown);
  EXPECT_TRUE(queue_.OnComplete(1, OkCompletion(5)));
  EXPECT_EQ(queue_.pool().used, 1U);
  queue_.Deliver();
  EXPECT_TRUE(listener_.done.empty());
  ASSERT_EQ(other.done.size(), 1U);
  EXPECT_EQ(other.done[0].first, 3U);
  EXPECT_EQ(other.done[0].second.error, AccessError::kLinkDown);
  EXPECT_EQ(queue_.pool().used, 0U);
}

TEST_F(DriveLinkAccessQueue, ALinkThatRefusesTheAccessEndsIt) {
  ASSERT_TRUE(queue_.Read(0xFD00, listener_).ok());
  ASSERT_TRUE(queue_.Read(0xFD01, listener_).ok());
  queue_.SendRefused(base::StatusCode::kResourceExhausted);  // waits
  queue_.SendRefused(base::StatusCode::kFailedPrecondition);
  queue_.SendRefused(base::StatusCode::kInvalidArgument);
  queue_.Deliver();
  ASSERT_EQ(listener_.done.size(), 2U);
  EXPECT_EQ(listener_.done[0].second.error, AccessError::kLinkDown);
  EXPECT_EQ(listener_.done[1].second.error, AccessError::kRefused);
}

}  // namespace
}  // namespace drive_link::test
