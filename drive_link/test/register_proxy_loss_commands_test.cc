// The register proxy's answer to explicit drive commands while a network loss holds the drive
// (docs/drive-control.md): FA06 run words and FA07 refused with kNetworkLost from the report until the
// network is restored (c101 != 1); a stop taken, written at once and kept by the action in place of its
// own FA06 (HoldStopDuringLoss). Runs against the simulated inverter (register_proxy_fixture.h).
#include <gtest/gtest.h>

#include "drive_link/register_proxy.h"
#include "register_proxy_fixture.h"

namespace drive_link::test {
namespace {

constexpr std::uint16_t kFa06 = 0xFA06;
constexpr std::uint16_t kFa07 = 0xFA07;
constexpr std::uint16_t kFd00 = 0xFD00;
constexpr std::uint16_t kSr2 = 0x0019;

class ProxyLossCommandTest : public RegisterProxyFixture {
 protected:
  // EtherNet/IP (c500 = 1: no IO scanning reservation), cmod 4 / fmod 7 (the option), acc = dec = 1 s.
  // The drive profile runs the drive at 60 Hz, gives the command back (Forward_Close) and the loss is
  // reported: c100 = 0.5 s.
  void RunReleaseLose(int c101, int c102 = 0) {
    SetEeprom({{0xC500, 1}, {0xC100, 5}, {0xC101, static_cast<std::uint16_t>(c101)},
               {0xC102, static_cast<std::uint16_t>(c102)}, {0x0003, 4}, {0x0004, 7}, {0x0009, 10},
               {0x0010, 10}, {kSr2, 2000}});
    StartLoaded();
    proxy_->SetDriveCommand({0xC400, 0x1770});
    RunFor(1500 * kMilli);
    ASSERT_EQ(Reg(kFd00), 0x1770);
    proxy_->ReleaseDriveCommand();
    lost_at_ = Now();
    proxy_->NetworkLost(LossCause::kCipConnection, lost_at_);
  }
  void RunPastDelay() { RunUntil(lost_at_ + 500 * kMilli + 2 * kExchange); }

  Micros lost_at_ = 0;
};

TEST_F(ProxyLossCommandTest, RunAndSpeedAreRefusedDuringTheDelayAndNothingIsWritten) {
  RunReleaseLose(2);
  EXPECT_TRUE(proxy_->CommandsHeldByLoss());
  EXPECT_FALSE(proxy_->loss_action_active());
  EXPECT_EQ(WriteNow(kFa06, 0xC400).error, AccessError::kNetworkLost);
  EXPECT_EQ(WriteNow(kFa07, 0x0BB8).error, AccessError::kNetworkLost);
  EXPECT_EQ(WriteNow(kFa06, 0xC100).error, AccessError::kNetworkLost);  // jog runs too
  EXPECT_EQ(Reg(kFa07), 0x1770);                                       // nothing reached the drive
  EXPECT_EQ(proxy_->counters().access_errors[static_cast<std::size_t>(AccessError::kNetworkLost)], 3U);
}

TEST_F(ProxyLossCommandTest, RunIsRefusedWhileTheActionIsInForce) {
  RunReleaseLose(2);
  RunPastDelay();
  ASSERT_TRUE(proxy_->loss_action_active());
  EXPECT_EQ(Reg(kFa06), 0xC000);
  EXPECT_EQ(WriteNow(kFa06, 0xC400).error, AccessError::kNetworkLost);
  RunFor(kSecond);
  EXPECT_EQ(Reg(kFa06), 0xC000);
  EXPECT_EQ(Reg(kFd00), 0);
}

TEST_F(ProxyLossCommandTest, AStopReplacesThePresetSpeedActionAndStays) {
  RunReleaseLose(5, 2);
  RunPastDelay();
  ASSERT_EQ(Reg(kFa06), 0x8402);  // priority, run, preset 2
  RunFor(kSecond);
  ASSERT_EQ(Reg(kFd00), 2000);
  const AccessResult stop = WriteNow(kFa06, 0xA000);  // priority + fault-reset bit, no run
  EXPECT_EQ(stop.error, AccessError::kNone);
  EXPECT_EQ(stop.value, 0xA000);
  RunFor(2 * kSecond);  // four refreshes of the action: each writes the stop, not 8402h
  EXPECT_EQ(Reg(kFa06), 0x8000);  // the held stop, fault-reset bit cleared
  EXPECT_EQ(Reg(kFd00), 0);
  EXPECT_TRUE(proxy_->loss_action_active());
  EXPECT_EQ(WriteNow(kFa06, 0xC400).error, AccessError::kNetworkLost);  // still lost

  proxy_->NetworkRestored(Now());
  EXPECT_FALSE(proxy_->CommandsHeldByLoss());
  EXPECT_EQ(WriteNow(kFa06, 0xC400).error, AccessError::kNone);  // restored: taken
  RunFor(100 * kMilli);
  EXPECT_EQ(Reg(kFa06), 0xC400);
}

TEST_F(ProxyLossCommandTest, AHeldStopIsWrittenToFa06AfterTheErr8Request) {
  RunReleaseLose(4);
  RunPastDelay();
  ASSERT_EQ(model_.trip(), 27);
  const std::uint32_t writes = proxy_->counters().loss_action_writes;
  proxy_->HoldStopDuringLoss(0x8800);  // coast, e.g. the drive profile's Run1 = 0
  RunFor(2 * kExchange);
  EXPECT_EQ(Reg(kFa06), 0x8800);
  EXPECT_EQ(proxy_->counters().loss_action_writes, writes + 1);
  RunFor(1100 * kMilli);
  EXPECT_EQ(proxy_->counters().loss_action_writes, writes + 3);  // refreshed every 500 ms; FA30 not again
  EXPECT_EQ(model_.trip(), 27);
}

TEST_F(ProxyLossCommandTest, RunWordsAreNotHeldAsStops) {
  RunReleaseLose(3);
  RunPastDelay();
  ASSERT_EQ(Reg(kFa06), 0x8800);
  proxy_->HoldStopDuringLoss(0xC400);
  RunFor(kSecond);
  EXPECT_EQ(Reg(kFa06), 0x8800);
}

TEST_F(ProxyLossCommandTest, ContinueHoldsNothing) {
  RunReleaseLose(1);
  EXPECT_FALSE(proxy_->CommandsHeldByLoss());
  RunPastDelay();
  EXPECT_FALSE(proxy_->CommandsHeldByLoss());
  EXPECT_EQ(WriteNow(kFa07, 0x0BB8).error, AccessError::kNone);
  EXPECT_EQ(Reg(kFa07), 0x0BB8);
}

TEST_F(ProxyLossCommandTest, NothingIsHeldWithoutALoss) {
  SetEeprom({{0xC500, 1}, {0xC101, 2}});
  StartLoaded();
  EXPECT_FALSE(proxy_->CommandsHeldByLoss());
  EXPECT_EQ(WriteNow(kFa06, 0xC400).error, AccessError::kNone);
  EXPECT_EQ(Reg(kFa06), 0xC400);
}

}  // namespace
}  // namespace drive_link::test
