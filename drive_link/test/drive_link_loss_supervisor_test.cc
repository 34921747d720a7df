// drive_link::LossSupervisor (drive_link/include/drive_link/loss_supervisor.h) on a configuration loaded
// through a ConfigLoader and a ScannerExchange holding the master's words: the c100 delay to the
// microsecond, c536, the c103 check with cmod/fmod read fresh, each c101 action's write and refresh, a
// stop held during the loss, and what NetworkRestored gives back.
#include "drive_link/loss_supervisor.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <map>
#include <utility>

#include "drive_link_part_fakes.h"

namespace drive_link::test {
namespace {

constexpr hal::Micros kMilli = hal::kMicrosPerMilli;
constexpr hal::Micros kLost = 100 * hal::kMicrosPerSecond;

class DriveLinkLossSupervisor : public ::testing::Test {
 protected:
  // c100 = 1.0 s; the master's scanner words FA06 = C400h, FA07 = 1770h.
  void Load(std::map<std::uint16_t, std::uint16_t> values) {
    values.emplace(0xC100, 10);
    RunLoad(loader_, FactoryReads(std::move(values)));
    exchange_.ApplyConfig(0);
    exchange_.SetCommandWordsMasked({0xC400, 0x1770, 0, 0, 0, 0}, kAllScannerWords);
  }

  ProxyConfig config_;
  ProxyCounters counters_;
  ConfigLoader loader_;
  CardWriteBack write_back_{config_, counters_};
  ScannerExchange exchange_{loader_, write_back_, config_, counters_, /*block_reads=*/true};
  LossSupervisor loss_{loader_, exchange_, write_back_, config_, counters_};
};

TEST_F(DriveLinkLossSupervisor, DecelerateAfterC100ThenRefreshUntilRestored) {
  Load({{0xC101, 2}});
  EXPECT_TRUE(loss_.NetworkLost(LossCause::kModbusIoScanning, kLost));
  EXPECT_FALSE(loss_.NetworkLost(LossCause::kCarrierLost, kLost + kMilli));  // already lost
  EXPECT_EQ(write_back_.ethernet_error(), 1);
  EXPECT_TRUE(loss_.CommandsHeldByLoss());
  EXPECT_EQ(loss_.Deadline(), kLost + 1000 * kMilli);
  OwnJob job;
  loss_.Poll(kLost + 999 * kMilli);
  EXPECT_FALSE(loss_.NextJob(kLost + 999 * kMilli, job));
  EXPECT_FALSE(loss_.action_active());
  loss_.Poll(kLost + 1000 * kMilli);
  EXPECT_TRUE(loss_.action_active());
  EXPECT_EQ(loss_.Deadline(), hal::kNever);
  EXPECT_FALSE(exchange_.UrgentCommandWrite(kLost + 1000 * kMilli, job));  // the master's words wait
  ASSERT_TRUE(loss_.NextJob(kLost + 1000 * kMilli, job));
  EXPECT_EQ(job.kind, OwnJobKind::kLossAction);
  EXPECT_EQ(job.transaction.kind, TransactionKind::kWriteRam);
  EXPECT_EQ(job.transaction.comm_number, 0xFA06);
  EXPECT_EQ(job.transaction.data, 0xC000);  // held C400h without run, with priority
  loss_.OnActionWritten(job.index, OkCompletion(0xC000), kLost + 1006 * kMilli);
  EXPECT_EQ(loss_.RefreshDeadline(), kLost + 1506 * kMilli);
  EXPECT_FALSE(loss_.NextJob(kLost + 1505 * kMilli, job));
  EXPECT_TRUE(loss_.NextJob(kLost + 1506 * kMilli, job));
  EXPECT_EQ(counters_.loss_actions, 1U);
  EXPECT_EQ(counters_.loss_action_writes, 1U);

  loss_.NetworkRestored();
  EXPECT_FALSE(loss_.action_active());
  EXPECT_FALSE(loss_.CommandsHeldByLoss());
  EXPECT_EQ(write_back_.ethernet_error(), 0);
  EXPECT_FALSE(loss_.NextJob(kLost + 2 * hal::kMicrosPerSecond, job));
  exchange_.SetCommandWordsMasked({0xC400, 0x1770, 0, 0, 0, 0}, kAllScannerWords);
  ASSERT_TRUE(exchange_.UrgentCommandWrite(kLost + 2 * hal::kMicrosPerSecond, job));
  EXPECT_EQ(job.transaction.comm_number, 0xFA06);
  EXPECT_EQ(job.transaction.data, 0xC400);
}

TEST_F(DriveLinkLossSupervisor, C103ReadsCmodAndFmodFresh) {
  Load({{0xC101, 3}, {0xC103, 1}, {0x0003, 4}, {0x0004, 7}});
  loss_.NetworkLost(LossCause::kCipConnection, kLost);
  EXPECT_EQ(write_back_.ethernet_error(), 0);  // no code for a CIP timeout
  loss_.Poll(kLost + 1000 * kMilli);
  OwnJob job;
  ASSERT_TRUE(loss_.NextJob(kLost + 1000 * kMilli, job));
  EXPECT_EQ(job.kind, OwnJobKind::kLossCheck);
  EXPECT_EQ(job.transaction.comm_number, 0x0003);
  loss_.OnCheckRead(job.index, OkCompletion(4));
  ASSERT_TRUE(loss_.NextJob(kLost + 1006 * kMilli, job));
  EXPECT_EQ(job.transaction.comm_number, 0x0004);
  loss_.OnCheckRead(job.index, OkCompletion(0));  // the panel set fmod = 0 since the load
  EXPECT_FALSE(loss_.action_active());
  EXPECT_FALSE(loss_.CommandsHeldByLoss());  // c103 did not allow it
  EXPECT_FALSE(loss_.NextJob(kLost + 1012 * kMilli, job));
  EXPECT_EQ(counters_.loss_actions, 0U);
}

TEST_F(DriveLinkLossSupervisor, Err8ThenAStopHeldDuringTheLoss) {
  Load({{0xC101, 4}});
  loss_.NetworkLost(LossCause::kCarrierLost, kLost);
  EXPECT_EQ(write_back_.ethernet_error(), 3);
  EXPECT_FALSE(loss_.HoldStopDuringLoss(0xC400));  // runs the drive: not a stop
  EXPECT_TRUE(loss_.HoldStopDuringLoss(0x2000));   // a stop, fault-reset bit dropped
  loss_.Poll(kLost + 1000 * kMilli);
  OwnJob job;
  ASSERT_TRUE(loss_.NextJob(kLost + 1000 * kMilli, job));
  EXPECT_EQ(job.transaction.comm_number, 0xFA30);
  EXPECT_EQ(job.transaction.data, 27);
  loss_.OnActionWritten(job.index, OkCompletion(27), kLost + 1006 * kMilli);
  ASSERT_TRUE(loss_.NextJob(kLost + 1006 * kMilli, job));
  EXPECT_EQ(job.index, 1);
  EXPECT_EQ(job.transaction.comm_number, 0xFA06);
  EXPECT_EQ(job.transaction.data, 0x0000);
  loss_.OnActionWritten(job.index, OkCompletion(0), kLost + 1012 * kMilli);
  EXPECT_EQ(loss_.RefreshDeadline(), kLost + 1512 * kMilli);
}

TEST_F(DriveLinkLossSupervisor, PresetSpeedAndContinue) {
  Load({{0xC101, 5}, {0xC102, 3}});
  loss_.NetworkLost(LossCause::kModbusConnection, kLost);
  loss_.Poll(kLost + 1000 * kMilli);
  OwnJob job;
  ASSERT_TRUE(loss_.NextJob(kLost + 1000 * kMilli, job));
  EXPECT_EQ(job.transaction.data, 0x8403);  // priority, run, preset 3
  loss_.CardReset();  // the proxy resets both at f899
  exchange_.CardReset();
  EXPECT_FALSE(loss_.action_active());

  Load({{0xC101, 1}});
  loss_.NetworkLost(LossCause::kModbusConnection, kLost);
  EXPECT_FALSE(loss_.CommandsHeldByLoss());  // continue: the explicit paths keep the drive
  loss_.Poll(kLost + 1000 * kMilli);
  EXPECT_FALSE(loss_.action_active());
  EXPECT_FALSE(loss_.NextJob(kLost + 1000 * kMilli, job));
  EXPECT_TRUE(exchange_.UrgentCommandWrite(kLost + 1000 * kMilli, job));  // the words go on
}

}  // namespace
}  // namespace drive_link::test
