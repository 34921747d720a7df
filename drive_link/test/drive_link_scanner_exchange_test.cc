// drive_link::ScannerExchange (drive_link/include/drive_link/scanner_exchange.h) on a configuration
// loaded through a ConfigLoader: the command words written (changes at once, RAM only, nothing before
// the master sends), the cycle's reads and the monitor words, write-backs between cycles, the targets
// reserved, the drive command taking FA06/FA07, the suspension by a loss action and the held FA06.
#include "drive_link/scanner_exchange.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <map>
#include <utility>

#include "drive_link_part_fakes.h"

namespace drive_link::test {
namespace {

constexpr hal::Micros kT0 = 5 * hal::kMicrosPerSecond;

class DriveLinkScannerExchange : public ::testing::Test {
 protected:
  // Factory menus: c001 = 1 (FA06), c002 = 3 (FA07), c021 = 1 (FD01), c022 = 2 (FD00).
  void Load(std::map<std::uint16_t, std::uint16_t> values = {}) {
    RunLoad(loader_, FactoryReads(std::move(values)));
    exchange_.ApplyConfig(kT0);
  }

  // The next own transaction as the proxy asks for it: a changed word first, then the cycle.
  OwnJob Next(hal::Micros now = kT0) {
    OwnJob job;
    if (exchange_.UrgentCommandWrite(now, job)) return job;
    if (exchange_.CycleJob(now, job)) return job;
    return OwnJob{};
  }

  // The next job that is not a write-back (those are completed on the way).
  OwnJob NextExchangeJob(hal::Micros now = kT0) {
    OwnJob job = Next(now);
    while (job.kind == OwnJobKind::kOwnedWrite) {
      write_back_.OnWritten(job.index, OkCompletion(0));
      job = Next(now);
    }
    return job;
  }

  // Completes the next exchange job with `completion`.
  OwnJob Complete(const Completion& completion, hal::Micros now = kT0) {
    const OwnJob job = NextExchangeJob(now);
    if (job.kind == OwnJobKind::kCommandWrite) exchange_.OnCommandWritten(job, completion);
    if (job.kind == OwnJobKind::kMonitorRead || job.kind == OwnJobKind::kBlockRead) {
      exchange_.OnMonitorRead(job, completion);
    }
    return job;
  }

  ProxyConfig config_;
  ProxyCounters counters_;
  ConfigLoader loader_;
  CardWriteBack write_back_{config_, counters_};
  ScannerExchange exchange_{loader_, write_back_, config_, counters_, /*block_reads=*/true};
};

TEST_F(DriveLinkScannerExchange, NothingIsWrittenBeforeTheMasterSendsThenChangesGoAtOnce) {
  Load({{0xFD01, 0x0000}});
  OwnJob job = Complete(OkCompletion(0x6400));
  EXPECT_EQ(job.kind, OwnJobKind::kMonitorRead);  // no command word: the cycle reads FD01
  EXPECT_EQ(job.transaction.comm_number, 0xFD01);
  job = Complete(OkCompletion(0x1770));
  EXPECT_EQ(job.transaction.comm_number, 0xFD00);
  EXPECT_EQ(exchange_.MonitorWords(), (ScannerWords{0x6400, 0x1770, 0, 0, 0, 0}));
  EXPECT_EQ(exchange_.drive_status(), 0x6400);
  EXPECT_TRUE(exchange_.drive_running());
  EXPECT_EQ(counters_.cycles, 0U);  // the cycle ends when the next one is asked for

  exchange_.SetCommandWordsMasked({0xC400, 0x1770, 0, 0, 0, 0}, kAllScannerWords);
  job = Next();
  EXPECT_EQ(job.kind, OwnJobKind::kCommandWrite);
  EXPECT_EQ(job.transaction.kind, TransactionKind::kWriteRam);
  EXPECT_EQ(job.transaction.comm_number, 0xFA06);
  EXPECT_EQ(job.transaction.data, 0xC400);
  exchange_.OnCommandWritten(job, OkCompletion(0xC400));
  job = Next();
  EXPECT_EQ(job.transaction.comm_number, 0xFA07);
  EXPECT_EQ(job.transaction.data, 0x1770);
  exchange_.OnCommandWritten(job, OkCompletion(0x1770));
  EXPECT_EQ(counters_.command_writes, 2U);
  EXPECT_EQ(exchange_.CommandWords(), (ScannerWords{0xC400, 0x1770, 0, 0, 0, 0}));
}

TEST_F(DriveLinkScannerExchange, TargetsAreReservedFromTheMastersFirstWordsOrWithIoScanning) {
  Load();
  EXPECT_FALSE(exchange_.IsScannerTarget(0xFA06));
  exchange_.SetCommandWordsMasked({0, 0, 0, 0, 0, 0}, kAllScannerWords);
  EXPECT_TRUE(exchange_.IsScannerTarget(0xFA06));
  EXPECT_TRUE(exchange_.IsScannerTarget(0xFA07));
  EXPECT_FALSE(exchange_.IsScannerTarget(0x0009));
  exchange_.SetCommandWordsMasked({0, 0, 0, 0, 0, 0}, 0x01);  // word 2 (FA07) left out
  EXPECT_FALSE(exchange_.IsScannerTarget(0xFA07));
  exchange_.CardReset();
  EXPECT_FALSE(exchange_.IsScannerTarget(0xFA06));
  Load({{0xC604, 1}});  // Modbus with IO scanning: reserved before the scanner sends
  EXPECT_TRUE(exchange_.IsScannerTarget(0xFA06));
}

TEST_F(DriveLinkScannerExchange, TheDriveCommandTakesFa06AndFa07) {
  Load();
  exchange_.SetCommandWordsMasked({0xC400, 0x1770, 0, 0, 0, 0}, kAllScannerWords);
  exchange_.SetDriveCommand({0x8400, 0x0BB8});
  EXPECT_TRUE(exchange_.drive_command_taken());
  OwnJob job = Next();
  EXPECT_EQ(job.index, kDriveFa06Word);  // the scanner words on FA06/FA07 are displaced
  EXPECT_EQ(job.transaction.comm_number, 0xFA06);
  EXPECT_EQ(job.transaction.data, 0x8400);
  job = Next();
  EXPECT_EQ(job.index, kDriveFa07Word);
  EXPECT_EQ(job.transaction.data, 0x0BB8);
  EXPECT_EQ(exchange_.HeldFa06(), 0x8400);
  EXPECT_TRUE(exchange_.ReleaseDriveCommand());
  EXPECT_FALSE(exchange_.ReleaseDriveCommand());
  EXPECT_EQ(exchange_.HeldFa06(), 0xC400);  // the scanner word is FA06's again
  job = Next();
  EXPECT_EQ(job.index, 0);
  EXPECT_EQ(job.transaction.data, 0xC400);  // written at once on release
}

TEST_F(DriveLinkScannerExchange, ASuspensionStopsTheCommandWordsUntilTheMasterSendsAgain) {
  Load();
  exchange_.SetCommandWordsMasked({0xC400, 0x1770, 0, 0, 0, 0}, kAllScannerWords);
  exchange_.SuspendCommandWrites();
  EXPECT_EQ(Next().kind, OwnJobKind::kOwnedWrite);  // write-backs and reads go on, no command word
  EXPECT_EQ(exchange_.HeldFa06(), 0xC400);
  exchange_.ResumeCommandWrites();
  OwnJob job = Next();
  EXPECT_NE(job.kind, OwnJobKind::kCommandWrite);  // not armed: nothing sent during the suspension
  exchange_.SetCommandWordsMasked({0xC400, 0x1770, 0, 0, 0, 0}, kAllScannerWords);
  job = Next();
  EXPECT_EQ(job.kind, OwnJobKind::kCommandWrite);
  EXPECT_EQ(job.transaction.comm_number, 0xFA06);
}

TEST_F(DriveLinkScannerExchange, AFaultResetEdgeIsSentOnce) {
  Load();
  exchange_.SetCommandWordsMasked({0x2000, 0, 0, 0, 0, 0}, kAllScannerWords);
  OwnJob job = Next();
  EXPECT_EQ(job.transaction.comm_number, 0xFA06);
  EXPECT_EQ(job.transaction.data, 0x2000);
  exchange_.OnCommandWritten(job, OutcomeCompletion(Outcome::kNoReply));  // the inverter reset
  job = NextExchangeJob();
  EXPECT_EQ(job.transaction.comm_number, 0xFA07);  // forgotten by the reset: written again at once
  exchange_.OnCommandWritten(job, OkCompletion(0));
  job = NextExchangeJob();
  EXPECT_EQ(job.transaction.comm_number, 0xFA06);  // in the cycle, without the edge
  EXPECT_EQ(job.transaction.data, 0x0000);
}

TEST_F(DriveLinkScannerExchange, BlockReadCoversTheSourcesItSelects) {
  Load({{0x0875, 1}, {0x0876, 2}});  // F875 = FD01, F876 = FD00
  const OwnJob job = NextExchangeJob();
  ASSERT_EQ(job.kind, OwnJobKind::kBlockRead);
  EXPECT_EQ(job.transaction.kind, TransactionKind::kBlock);
  EXPECT_EQ(job.transaction.block_read_count, 2);
  Completion block = OkCompletion(0);
  block.block_read_count = 2;
  block.block_data[0] = 0x6400;
  block.block_data[1] = 0x0BB8;
  exchange_.OnMonitorRead(job, block);
  EXPECT_EQ(exchange_.MonitorWords(), (ScannerWords{0x6400, 0x0BB8, 0, 0, 0, 0}));
  EXPECT_EQ(counters_.block_reads, 1U);
}

}  // namespace
}  // namespace drive_link::test
