// drive_link::CardWriteBack (drive_link/include/drive_link/card_write_back.h): the values the card owns,
// written back in their order after a load, only when changed, c555 from FD01, c536, the display sample
// and what a refused or unanswered write-back leaves.
#include "drive_link/card_write_back.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "drive_link_part_fakes.h"

namespace drive_link::test {
namespace {

constexpr hal::Micros kSecond = hal::kMicrosPerSecond;

class DriveLinkCardWriteBack : public ::testing::Test {
 protected:
  // Every write-back due at `now` (each completed with `completion`), as number/value pairs.
  std::vector<std::pair<std::uint16_t, std::uint16_t>> Drain(hal::Micros now, const Completion& completion) {
    std::vector<std::pair<std::uint16_t, std::uint16_t>> writes;
    OwnJob job;
    while (write_back_.NextWrite(now, commands_, monitors_, job)) {
      EXPECT_EQ(job.kind, OwnJobKind::kOwnedWrite);
      EXPECT_EQ(job.transaction.kind, TransactionKind::kWriteRam);
      writes.emplace_back(job.transaction.comm_number, job.transaction.data);
      write_back_.OnWritten(job.index, completion);
    }
    return writes;
  }

  ProxyConfig config_;
  ProxyCounters counters_;
  CardWriteBack write_back_{config_, counters_};
  ScannerWords commands_{};
  ScannerWords monitors_{};
};

TEST_F(DriveLinkCardWriteBack, EverythingIsWrittenAfterALoadThenOnlyChanges) {
  config::CardStatus status;
  status.port_rates = {3, 0};
  status.mac = {0x00, 0x0E, 0x8C, 0x01, 0x02, 0x03};
  status.ip = {192, 168, 1, 10};
  status.netmask = {255, 255, 255, 0};
  status.gateway = {192, 168, 1, 1};
  write_back_.SetCardStatus(status);
  write_back_.Reload(10 * kSecond);
  write_back_.SetDriveStatus(0x0400);  // running
  commands_ = {0xC400, 0x1770, 0, 0, 0, 0};
  monitors_ = {0x6400, 0x1770, 0, 0, 0, 0};
  const auto writes = Drain(10 * kSecond, OkCompletion(0));
  ASSERT_EQ(writes.size(), 34U);
  EXPECT_EQ(writes[0], std::make_pair(std::uint16_t{0xC502}, std::uint16_t{3}));
  EXPECT_EQ(writes[3], std::make_pair(std::uint16_t{0xC518}, std::uint16_t{0x0E}));
  EXPECT_EQ(writes[8], std::make_pair(std::uint16_t{0xC524}, std::uint16_t{192}));
  EXPECT_EQ(writes[20], std::make_pair(std::uint16_t{0xC536}, std::uint16_t{0}));
  EXPECT_EQ(writes[21], std::make_pair(std::uint16_t{0xC555}, std::uint16_t{4}));
  EXPECT_EQ(writes[22], std::make_pair(std::uint16_t{0xC041}, std::uint16_t{0xC400}));
  EXPECT_EQ(writes[29], std::make_pair(std::uint16_t{0xC062}, std::uint16_t{0x1770}));
  EXPECT_EQ(counters_.owned_writes, 34U);
  EXPECT_TRUE(Drain(10 * kSecond, OkCompletion(0)).empty());

  write_back_.SetDriveStatus(0x0002);  // tripped
  write_back_.SetEthernetError(3);
  monitors_[0] = 0x6401;  // sampled only at the next display interval
  EXPECT_EQ(write_back_.next_display_at(), 11 * kSecond);
  const auto changes = Drain(10 * kSecond, OkCompletion(0));
  ASSERT_EQ(changes.size(), 2U);
  EXPECT_EQ(changes[0], std::make_pair(std::uint16_t{0xC536}, std::uint16_t{3}));
  EXPECT_EQ(changes[1], std::make_pair(std::uint16_t{0xC555}, std::uint16_t{23}));
  EXPECT_EQ(write_back_.ethernet_error(), 3);
  const auto sampled = Drain(11 * kSecond, OkCompletion(0));
  ASSERT_EQ(sampled.size(), 1U);
  EXPECT_EQ(sampled[0], std::make_pair(std::uint16_t{0xC061}, std::uint16_t{0x6401}));
  EXPECT_EQ(write_back_.next_display_at(), 12 * kSecond);
}

TEST_F(DriveLinkCardWriteBack, ARefusalIsNotRepeatedAnUnansweredWriteIs) {
  write_back_.Reload(0);
  // c555 waits for FD01: 33 values.
  EXPECT_EQ(Drain(0, ErrorCompletion(wire::ErrorCode::kDataError)).size(), 33U);
  EXPECT_EQ(counters_.owned_errors, 33U);
  EXPECT_TRUE(Drain(0, OkCompletion(0)).empty());
  write_back_.MarkAllUnknown();  // a short silence: the inverter may have been reset
  OwnJob job;
  ASSERT_TRUE(write_back_.NextWrite(0, commands_, monitors_, job));
  EXPECT_EQ(job.transaction.comm_number, 0xC502);
  write_back_.OnWritten(job.index, OutcomeCompletion(Outcome::kTimeout));
  ASSERT_TRUE(write_back_.NextWrite(0, commands_, monitors_, job));
  EXPECT_EQ(job.transaction.comm_number, 0xC502);  // again at once
}

TEST_F(DriveLinkCardWriteBack, TheOwnedNumbers) {
  EXPECT_TRUE(CardWriteBack::IsOwnedNumber(0xC502));
  EXPECT_TRUE(CardWriteBack::IsOwnedNumber(0xC536));
  EXPECT_TRUE(CardWriteBack::IsOwnedNumber(0xC555));
  EXPECT_TRUE(CardWriteBack::IsOwnedNumber(0xC066));
  EXPECT_FALSE(CardWriteBack::IsOwnedNumber(0xC523));
  EXPECT_FALSE(CardWriteBack::IsOwnedNumber(0xC504));
  EXPECT_FALSE(CardWriteBack::IsOwnedNumber(0xC001));
}

}  // namespace
}  // namespace drive_link::test
