// drive_link::RegisterProxy against the real simulated inverter (register_proxy_fixture.h): the
// configuration load, the cyclic exchange, on-demand accesses and their errors, f899 and e-23 reloads,
// the c101 loss actions and the values the card writes back. Register values are read from the model;
// times are exact on the fake clock (kExchange = one register exchange with the default server).
#include "drive_link/register_proxy.h"

#include <gtest/gtest.h>

#include <optional>

#include "register_proxy_fixture.h"

namespace drive_link::test {
namespace {

using sim::WriteTarget;

constexpr std::uint16_t kFa06 = 0xFA06;
constexpr std::uint16_t kFa07 = 0xFA07;
constexpr std::uint16_t kFd00 = 0xFD00;
constexpr std::uint16_t kFd01 = 0xFD01;
constexpr std::uint16_t kAcc = 0x0009;
constexpr std::uint16_t kDec = 0x0010;
constexpr std::uint16_t kFh = 0x0011;
constexpr std::uint16_t kSr2 = 0x0019;
constexpr std::uint8_t kEmergencyStopTrip = 0x11;

// 62 reads: the 57 configuration numbers and F875-F879.
constexpr Micros kLoadTime = 63 * kExchange;  // 57 configuration numbers, F875-F879, FD01
// A block read of 2 groups: 2 ms + 9 reply bytes (ceil(9 x 11 / 19200 s) = 5157 us).
constexpr Micros kBlockExchange2 = 2 * kMilli + 5157;

const ScannerWords kRun60Hz = {0xC400, 0x1770, 0, 0, 0, 0};

using RegisterProxyTest = RegisterProxyFixture;

// ---- Configuration at start-up --------------------------------------------------------------------

TEST_F(RegisterProxyTest, ReadsTheConfigurationAfterTheStartupSilence) {
  std::uint64_t executed_at_load = 0;
  Micros loaded_at = 0;
  bool status_known_at_load = false;
  config_.on_load = [&] {
    executed_at_load = server_->counters().executed;
    loaded_at = Now();
    status_known_at_load = proxy_->drive_status_known();
  };
  Start();
  EXPECT_EQ(proxy_->Start(Now()).code(), base::StatusCode::kFailedPrecondition);
  RunUntil(kStart + kSecond - 1);
  EXPECT_EQ(server_->counters().requests, 0U);  // the inverter's start-up silence is respected
  EXPECT_FALSE(proxy_->config_loaded());
  RunUntil(kStart + 3 * kSecond);

  ASSERT_EQ(config_.loads.size(), 1U);
  EXPECT_EQ(executed_at_load, 63U);  // nothing but the configuration reads (and FD01) before the listener
  EXPECT_TRUE(status_known_at_load);  // FD01 is the load's last read: the drive profile never sees a gap
  EXPECT_EQ(loaded_at, kStart + kSecond + kLoadTime);
  EXPECT_TRUE(proxy_->config_loaded());
  EXPECT_EQ(proxy_->counters().config_loads, 1U);
  const config::ParsedConfig& parsed = config_.loads[0];
  EXPECT_EQ(parsed.problems_total, 0U);
  // The seed's factory settings, as the simulated inverter holds them.
  const config::CardConfig& c = proxy_->config();
  EXPECT_EQ(c.command_menus, (std::array<std::uint16_t, 6>{1, 3, 0, 0, 0, 0}));
  EXPECT_EQ(c.monitor_menus, (std::array<std::uint16_t, 6>{1, 2, 0, 0, 0, 0}));
  EXPECT_EQ(c.loss_delay_tenths, 0);
  EXPECT_EQ(c.loss_action, 4);
  EXPECT_EQ(c.loss_condition, 0);
  EXPECT_EQ(c.timeout_tenths, 20);
  EXPECT_TRUE(c.web_server);
  EXPECT_FALSE(c.io_scanning);
  EXPECT_EQ(c.cmod, 1);
  EXPECT_EQ(c.fmod, 0);
  EXPECT_EQ(c.pole_pairs, 2);
  EXPECT_EQ(std::string(c.device_name.data()), "");
  EXPECT_EQ(proxy_->block_read_selections(), (std::array<std::uint16_t, 5>{0, 0, 0, 0, 0}));
  EXPECT_EQ(parsed.config.command_menus, c.command_menus);
}

TEST_F(RegisterProxyTest, ReportsAReservedMenuAndUsesTheFactoryDefault) {
  SetEeprom({{0xC001, 4}, {0xC022, 24}, {0xC081, 'V'}, {0xC082, 'F'}});
  StartLoaded();
  const config::ParsedConfig& parsed = proxy_->parsed_config();
  ASSERT_EQ(parsed.problem_count, 2U);
  EXPECT_EQ(parsed.problems[0].number, 0xC001);
  EXPECT_EQ(parsed.problems[0].value, 4);
  EXPECT_EQ(parsed.problems[0].kind, config::ConfigProblem::Kind::kReservedMenu);
  EXPECT_EQ(parsed.problems[1].number, 0xC022);
  EXPECT_EQ(parsed.problems[1].value, 24);
  EXPECT_EQ(proxy_->config().command_menus[0], 1);  // FA06, not the reserved menu
  EXPECT_EQ(proxy_->config().monitor_menus[1], 2);
  EXPECT_EQ(std::string(proxy_->config().device_name.data()), "VF");
  ASSERT_EQ(config_.loads.size(), 1U);
  EXPECT_EQ(config_.loads[0].problem_count, 2U);
}

TEST_F(RegisterProxyTest, AccessesWaitForTheConfiguration) {
  Start();
  RecordingListener listener;
  const base::Result<AccessToken> token = proxy_->Read(0x0003, listener);
  ASSERT_TRUE(token.ok());
  EXPECT_TRUE(listener.done.empty());  // never from inside Read
  proxy_->Poll(Now());
  ASSERT_EQ(listener.done.size(), 1U);
  EXPECT_EQ(listener.done[0].first, *token);
  EXPECT_EQ(listener.done[0].second.error, AccessError::kLinkDown);
  EXPECT_EQ(listener.done[0].second.number, 0x0003);
}

// ---- Cyclic exchange --------------------------------------------------------------------------------

TEST_F(RegisterProxyTest, ScannerWordsReachTheDriveAndMonitorWordsComeBack) {
  SetEeprom({{kAcc, 10}});  // 1.0 s from 0 to fh (80 Hz)
  StartLoaded();
  RunFor(kSecond);
  // Nothing is written before the master has sent words.
  EXPECT_EQ(proxy_->counters().command_writes, 0U);
  EXPECT_EQ(Reg(kFa06), 0);
  EXPECT_EQ(proxy_->MonitorWords(), (ScannerWords{0x4800, 0, 0, 0, 0, 0}));  // seed 000 §5.1.6 (1)

  proxy_->SetCommandWords(kRun60Hz);
  const Micros set_at = Now();
  const auto fa06_at = RunUntilTrue([this] { return Reg(kFa06) == 0xC400; }, kSecond);
  ASSERT_TRUE(fa06_at.has_value());
  EXPECT_LE(*fa06_at - set_at, kExchange);  // after the transaction on the wire, at once
  const auto fa07_at = RunUntilTrue([this] { return Reg(kFa07) == 0x1770; }, kSecond);
  ASSERT_TRUE(fa07_at.has_value());
  EXPECT_EQ(*fa07_at - *fa06_at, kExchange);
  EXPECT_EQ(proxy_->CommandWords(), kRun60Hz);

  RunFor(kSecond);  // 0 -> 60 Hz takes 0.75 s
  EXPECT_EQ(Reg(kFd00), 0x1770);
  EXPECT_EQ(Reg(kFd01), 0x6400);
  EXPECT_EQ(proxy_->MonitorWords(), (ScannerWords{0x6400, 0x1770, 0, 0, 0, 0}));
  EXPECT_EQ(proxy_->drive_status(), 0x6400);
}

TEST_F(RegisterProxyTest, BackToBackCyclePeriodIsTwoExchanges) {
  StartLoaded();
  RunFor(2 * kSecond);  // the write-back of the owned values is over
  const ProxyCounters& c = proxy_->counters();
  EXPECT_EQ(c.cycle_period_last, 2 * kExchange);  // R FD01, R FD00
  EXPECT_EQ(c.cycle_period_min, 2 * kExchange);
  EXPECT_EQ(c.cycle_period_max, 3 * kExchange);  // one write-back between two cycles
  EXPECT_EQ(c.block_reads, 0U);
  EXPECT_GT(c.cycles, 100U);
}

TEST_F(RegisterProxyTest, MinimumCyclePeriodKeepsItsBaseTime) {
  ProxyConfig config;
  config.min_cycle_period = 50 * kMilli;
  StartLoaded({}, config);
  RunFor(2 * kSecond);
  EXPECT_EQ(proxy_->counters().cycle_period_last, 50 * kMilli);
  const std::uint32_t cycles = proxy_->counters().cycles;
  RunFor(kSecond);
  EXPECT_EQ(proxy_->counters().cycles - cycles, 20U);
}

TEST_F(RegisterProxyTest, Rs485ProfileCyclePeriod) {
  StartLoaded(sim::Rs485Profile());
  RunFor(5 * kSecond);
  EXPECT_EQ(proxy_->counters().cycle_period_last, 2 * (20 * kMilli + 4011));
}

TEST_F(RegisterProxyTest, MonitorMenusShareReadsAndUnusedWordsReadZero) {
  SetEeprom({{0xC023, 10}, {0xC024, 1}});  // word 3: FE35 (VIA), word 4: FD01 again
  StartLoaded();
  model_.SetAnalogInput(sim::AnalogInput::kVia, 5000);
  RunFor(2 * kSecond);
  EXPECT_EQ(proxy_->MonitorWords(), (ScannerWords{0x4800, 0, 5000, 0x4800, 0, 0}));
  EXPECT_EQ(proxy_->counters().cycle_period_last, 3 * kExchange);  // FD01, FD00, FE35
}

TEST_F(RegisterProxyTest, BlockReadWhereTheSelectionsInForceCoverTheSources) {
  SetEeprom({{0x0875, 1}, {0x0876, 2}, {kAcc, 10}});  // block read data 1 = FD01, 2 = FD00
  StartLoaded();
  EXPECT_EQ(proxy_->block_read_selections(), (std::array<std::uint16_t, 5>{1, 2, 0, 0, 0}));
  RunFor(2 * kSecond);
  EXPECT_EQ(proxy_->counters().monitor_reads, 0U);
  EXPECT_GT(proxy_->counters().block_reads, 100U);
  EXPECT_EQ(proxy_->counters().cycle_period_last, kBlockExchange2);
  proxy_->SetCommandWords(kRun60Hz);
  RunFor(2 * kSecond);
  EXPECT_EQ(proxy_->MonitorWords(), (ScannerWords{0x6400, 0x1770, 0, 0, 0, 0}));
  EXPECT_EQ(proxy_->counters().monitor_reads, 0U);
}

TEST_F(RegisterProxyTest, TripHoldBlockSelectionsAreNotUsedForTheLiveMonitors) {
  // F875 = 3 is FE03 (held at a trip), not the FD03 of menu 3; F876 = 1 (FD01) is used: nR = 2.
  SetEeprom({{0x0875, 3}, {0x0876, 1}, {0xC023, 3}});
  StartLoaded();
  RunFor(2 * kSecond);
  const ProxyCounters& c = proxy_->counters();
  EXPECT_EQ(c.cycle_period_last, kBlockExchange2 + 2 * kExchange);  // X (FD01), R FD00, R FD03
  EXPECT_NEAR(static_cast<double>(c.monitor_reads), 2.0 * c.block_reads, 2.0);
}

TEST_F(RegisterProxyTest, CyclicDataNeverWritesTheEeprom) {
  SetEeprom({{0xC003, 13}});  // word 3 -> acc (0009), an EEPROM parameter
  StartLoaded();
  proxy_->SetCommandWords({0, 0, 30, 0, 0, 0});
  RunFor(3 * kSecond);
  EXPECT_EQ(Reg(kAcc), 30);
  EXPECT_GE(proxy_->counters().command_writes, 18U);  // 3 words, refreshed every 500 ms
  EXPECT_EQ(model_.EepromWriteCount(kAcc), 0U);
  EXPECT_EQ(model_.EepromValue(kAcc), 100);
  model_.PowerCycle();  // RAM only: a power cycle brings back the EEPROM value
  EXPECT_EQ(Reg(kAcc), 100);
}

TEST_F(RegisterProxyTest, RefreshRestoresAWordChangedBehindTheCardsBack) {
  StartLoaded();
  proxy_->SetCommandWords(kRun60Hz);
  const Micros set_at = Now();
  RunFor(100 * kMilli);
  ASSERT_EQ(model_.Write(kFa07, 0, WriteTarget::kRamOnly).outcome, sim::WriteOutcome::kOk);
  const auto restored = RunUntilTrue([this] { return Reg(kFa07) == 0x1770; }, kSecond);
  ASSERT_TRUE(restored.has_value());
  EXPECT_GT(*restored, set_at + 500 * kMilli);
  EXPECT_LE(*restored, set_at + 500 * kMilli + 6 * kExchange);
}

TEST_F(RegisterProxyTest, WordsAreWrittenAgainWhenTheLinkRecoversFromDegraded) {
  StartLoaded();
  proxy_->SetCommandWords(kRun60Hz);
  const Micros set_at = Now();
  RunFor(100 * kMilli);
  // A panel reset would clear FA07 and silence the inverter for a while; here: FA07 cleared, and the next
  // transaction lost on every attempt (fewer than three: degraded, not e-23).
  ASSERT_EQ(model_.Write(kFa07, 0, WriteTarget::kRamOnly).outcome, sim::WriteOutcome::kOk);
  server_->Inject({sim::Fault::Kind::kSilent, 3, 0});
  const auto restored = RunUntilTrue([this] { return Reg(kFa07) == 0x1770; }, kSecond);
  ASSERT_TRUE(restored.has_value());
  EXPECT_LT(*restored, set_at + 500 * kMilli);  // before the refresh would have done it
  EXPECT_EQ(proxy_->link().counters().failed_transactions, 1U);
  EXPECT_EQ(proxy_->link().state(), LinkState::kUp);
}

TEST_F(RegisterProxyTest, FaultResetBitIsSentOncePerEdgeAndTheWordsAreWrittenAgain) {
  SetEeprom({{kAcc, 10}});
  StartLoaded();
  proxy_->SetCommandWords(kRun60Hz);
  RunFor(1500 * kMilli);
  model_.Trip(kEmergencyStopTrip);
  RunFor(200 * kMilli);
  EXPECT_EQ(proxy_->MonitorWords()[0] & 0x0003, 0x0003);
  proxy_->SetCommandWords({0xE400, 0x1770, 0, 0, 0, 0});  // the master raises the fault-reset bit and holds it
  RunFor(3 * kSecond);
  EXPECT_FALSE(model_.tripped());
  EXPECT_EQ(server_->counters().no_reply, 1U);  // one reset, not one per refresh
  EXPECT_EQ(Reg(kFa06), 0xC400);               // written again after the reset, bit 13 cleared
  EXPECT_EQ(Reg(kFa07), 0x1770);
  EXPECT_EQ(Reg(kFd00), 0x1770);
  EXPECT_FALSE(proxy_->link().option_fault());
}

// ---- On-demand accesses ----------------------------------------------------------------------------

TEST_F(RegisterProxyTest, ReadsAndWritesThroughTheLink) {
  StartLoaded();
  AccessResult r = ReadNow(0x0003);
  EXPECT_EQ(r.error, AccessError::kNone);
  EXPECT_EQ(r.number, 0x0003);
  EXPECT_EQ(r.value, 1);
  r = WriteNow(kAcc, 50, WriteMode::kRamAndEeprom);  // W: RAM and EEPROM
  EXPECT_EQ(r.error, AccessError::kNone);
  EXPECT_EQ(r.value, 50);
  EXPECT_EQ(model_.EepromWriteCount(kAcc), 1U);
  EXPECT_EQ(model_.EepromValue(kAcc), 50);
  r = WriteNow(kDec, 70, WriteMode::kRamOnly);  // P: RAM only
  EXPECT_EQ(r.error, AccessError::kNone);
  EXPECT_EQ(Reg(kDec), 70);
  EXPECT_EQ(model_.EepromWriteCount(kDec), 0U);
  EXPECT_EQ(proxy_->counters().accesses, 3U);
  EXPECT_EQ(proxy_->counters().accesses_ok, 3U);
}

TEST_F(RegisterProxyTest, LocalRefusals) {
  StartLoaded();
  EXPECT_EQ(ReadNow(0x000A).error, AccessError::kNoSuchRegister);   // xxxA-xxxF do not exist
  EXPECT_EQ(WriteNow(0xFA0B, 1).error, AccessError::kNoSuchRegister);
  EXPECT_EQ(WriteNow(kFd00, 1).error, AccessError::kReadOnly);       // a monitor
  EXPECT_EQ(WriteNow(0xFE14, 1).error, AccessError::kReadOnly);
  const std::array<std::uint16_t, 10> owned_numbers = {0xC502, 0xC503, 0xC517, 0xC522, 0xC524,
                                                       0xC535, 0xC536, 0xC555, 0xC041, 0xC066};
  for (std::uint16_t owned : owned_numbers) {
    EXPECT_EQ(WriteNow(owned, 1).error, AccessError::kReadOnly) << std::hex << owned;
  }
  EXPECT_EQ(WriteNow(0xFA30, 27).error, AccessError::kReadOnly);  // the card's own fault line
  EXPECT_FALSE(model_.tripped());
  EXPECT_EQ(ReadNow(0xC536).error, AccessError::kNone);  // reading them is fine
  EXPECT_EQ(proxy_->counters().access_errors[static_cast<std::size_t>(AccessError::kReadOnly)], 13U);
  EXPECT_EQ(proxy_->counters().access_errors[static_cast<std::size_t>(AccessError::kNoSuchRegister)], 2U);
}

TEST_F(RegisterProxyTest, InverterErrorReplies) {
  SetEeprom({{kAcc, 10}});
  StartLoaded();
  EXPECT_EQ(ReadNow(0x0001).error, AccessError::kNoSuchRegister);   // 0002
  EXPECT_EQ(WriteNow(kFh, 10).error, AccessError::kOutOfRange);      // 0001: fh is 30.00-500.00 Hz
  EXPECT_EQ(WriteNow(0xFB05, 1).error, AccessError::kRefused);       // 0000, not a parameter
  EXPECT_EQ(WriteNow(kFh, 6000).error, AccessError::kNone);          // stopped: allowed
  proxy_->SetCommandWords(kRun60Hz);
  RunFor(kSecond);
  EXPECT_EQ(WriteNow(kFh, 7000).error, AccessError::kNotWritableWhileRunning);  // 0000 while running
  EXPECT_EQ(Reg(kFh), 6000);
}

TEST_F(RegisterProxyTest, ScannerTargetsAreReservedOnceTheMasterSendsWords) {
  StartLoaded();
  EXPECT_FALSE(proxy_->IsScannerTarget(kFa07));  // c604 = 0 and no words yet: FC06 to FA07 works
  EXPECT_EQ(WriteNow(kFa07, 1000).error, AccessError::kNone);
  EXPECT_EQ(Reg(kFa07), 1000);
  proxy_->SetCommandWords(kRun60Hz);
  EXPECT_TRUE(proxy_->IsScannerTarget(kFa06));
  EXPECT_TRUE(proxy_->IsScannerTarget(kFa07));
  EXPECT_FALSE(proxy_->IsScannerTarget(0xFA23));  // menu not in use
  EXPECT_EQ(WriteNow(kFa07, 1000).error, AccessError::kReservedForScanner);
  EXPECT_EQ(WriteNow(kFa06, 0).error, AccessError::kReservedForScanner);
  RunFor(100 * kMilli);
  EXPECT_EQ(ReadNow(kFa07).value, 0x1770);
}

TEST_F(RegisterProxyTest, IoScanningReservesTheTargetsBeforeTheFirstWords) {
  SetEeprom({{0xC604, 1}});
  StartLoaded();
  EXPECT_TRUE(proxy_->IsScannerTarget(kFa06));
  EXPECT_EQ(WriteNow(kFa06, 0xC400).error, AccessError::kReservedForScanner);
}

TEST_F(RegisterProxyTest, OnDemandFaultResetIsASuccessWithoutReply) {
  StartLoaded();
  model_.Trip(kEmergencyStopTrip);
  const AccessResult r = WriteNow(kFa06, 0x2000);
  EXPECT_EQ(r.error, AccessError::kNone);
  EXPECT_EQ(r.value, 0x2000);
  EXPECT_FALSE(model_.tripped());
  EXPECT_EQ(server_->counters().no_reply, 1U);
  RunFor(2 * kSecond);  // the link's reset silence, then the cycle again
  EXPECT_EQ(proxy_->link().state(), LinkState::kUp);
  EXPECT_EQ(proxy_->link().counters().failed_transactions, 0U);
}

TEST_F(RegisterProxyTest, TimeoutAfterEveryAttempt) {
  StartLoaded();
  RunFor(100 * kMilli);
  // The proxy's own request on the wire has been executed; the next three requests (the access and its
  // two retries) are lost.
  server_->Inject({sim::Fault::Kind::kSilent, 3, 0});
  EXPECT_EQ(ReadNow(0x0003).error, AccessError::kTimeout);
  RunFor(100 * kMilli);
  EXPECT_EQ(proxy_->link().state(), LinkState::kUp);
}

TEST_F(RegisterProxyTest, LinkDownForWaitingAccessesAndRefusalInFault) {
  StartLoaded();
  RunFor(100 * kMilli);
  server_->Inject({sim::Fault::Kind::kSilent, sim::Fault::kUntilCleared, 0});
  RecordingListener a, b, c;
  ASSERT_TRUE(proxy_->Read(0x0003, a).ok());
  ASSERT_TRUE(proxy_->Read(0x0004, b).ok());
  ASSERT_TRUE(proxy_->Read(0x0856, c).ok());
  ASSERT_TRUE(RunUntilTrue([&] { return !c.done.empty(); }, 2 * kSecond).has_value());
  // a fails, then the proxy's own read, then b: e-23; c never went out.
  ASSERT_EQ(a.done.size(), 1U);
  ASSERT_EQ(b.done.size(), 1U);
  EXPECT_EQ(a.done[0].second.error, AccessError::kTimeout);
  EXPECT_EQ(b.done[0].second.error, AccessError::kTimeout);
  EXPECT_EQ(c.done[0].second.error, AccessError::kLinkDown);
  EXPECT_TRUE(proxy_->link().option_fault());
  RecordingListener d;
  EXPECT_EQ(proxy_->Read(0x0003, d).status().code(), base::StatusCode::kFailedPrecondition);
  EXPECT_EQ(proxy_->Write(kAcc, 1, WriteMode::kRamOnly, d).status().code(), base::StatusCode::kFailedPrecondition);
}

TEST_F(RegisterProxyTest, PoolLimitOrderAndCancel) {
  StartLoaded();
  std::array<RecordingListener, kMaxPendingAccesses> listeners;
  std::vector<AccessToken> tokens;
  for (RecordingListener& l : listeners) {
    const base::Result<AccessToken> token = proxy_->Read(0x0003, l);
    ASSERT_TRUE(token.ok());
    tokens.push_back(*token);
  }
  RecordingListener extra;
  EXPECT_EQ(proxy_->Read(0x0003, extra).status().code(), base::StatusCode::kResourceExhausted);
  EXPECT_EQ(proxy_->counters().pool_full, 1U);
  EXPECT_EQ(proxy_->access_pool(), (base::PoolStats{kMaxPendingAccesses, kMaxPendingAccesses, kMaxPendingAccesses, 1}));
  proxy_->Cancel(listeners[3]);  // waiting: forgotten at once
  EXPECT_EQ(proxy_->access_pool().used, kMaxPendingAccesses - 1);
  const std::uint32_t cycles = proxy_->counters().cycles;
  RunFor(kSecond);
  for (std::size_t i = 0; i < listeners.size(); ++i) {
    if (i == 3) {
      EXPECT_TRUE(listeners[i].done.empty());
      continue;
    }
    ASSERT_EQ(listeners[i].done.size(), 1U) << i;
    EXPECT_EQ(listeners[i].done[0].first, tokens[i]);
    EXPECT_EQ(listeners[i].done[0].second.value, 1);
  }
  // The cycle kept running while 7 accesses went through (the link alternates them).
  EXPECT_GE(proxy_->counters().cycles - cycles, 3U);
  // Every completion delivered gave its slot back.
  EXPECT_EQ(proxy_->access_pool(), (base::PoolStats{0, kMaxPendingAccesses, kMaxPendingAccesses, 1}));
  for (RecordingListener& l : listeners) EXPECT_TRUE(proxy_->Read(0x0003, l).ok());  // the pool is free again
  for (RecordingListener& l : listeners) proxy_->Cancel(l);
}

// ---- Reloads ----------------------------------------------------------------------------------------

TEST_F(RegisterProxyTest, F899ReloadsTheConfigurationAfterTheResetSilence) {
  SetEeprom({{kAcc, 10}, {kDec, 10}});
  StartLoaded();
  config::CardStatus status;
  status.ip = {192, 168, 1, 12};
  proxy_->SetCardStatus(status);
  proxy_->SetCommandWords(kRun60Hz);
  RunFor(kSecond);
  ASSERT_EQ(Reg(0xC524), 192);
  EXPECT_EQ(WriteNow(0x0899, 1).error, AccessError::kNotWritableWhileRunning);  // f899: not during run
  const ScannerWords stopped = {0xC000, 0x1770, 0, 0, 0, 0};
  proxy_->SetCommandWords(stopped);
  RunFor(2 * kSecond);
  ASSERT_EQ(WriteNow(0xC002, 0, WriteMode::kRamAndEeprom).error, AccessError::kNone);  // word 2 not used
  Micros loaded_at = 0;
  std::optional<std::uint16_t> fd01_at_load;
  config_.on_load = [&] {
    loaded_at = Now();
    if (proxy_->drive_status_known()) fd01_at_load = proxy_->drive_status();
  };
  EXPECT_EQ(WriteNow(0x0899, 1).error, AccessError::kNone);
  const Micros reset_until = model_.ResetInProgressUntil();
  EXPECT_EQ(Reg(kFa06), 0);  // the inverter re-initialised
  ASSERT_TRUE(RunUntilTrue([this] { return config_.loads.size() == 2; }, 3 * kSecond).has_value());
  EXPECT_EQ(loaded_at, reset_until + kLoadTime);
  // The status after the reset, read by the load itself: a stopped drive in standby (FD01 bit 14).
  EXPECT_EQ(fd01_at_load, std::optional<std::uint16_t>(Reg(0xFD01)));
  EXPECT_NE(*fd01_at_load & 0x4000, 0);
  EXPECT_EQ(proxy_->config().command_menus, (std::array<std::uint16_t, 6>{1, 0, 0, 0, 0, 0}));
  EXPECT_EQ(proxy_->counters().config_loads, 2U);
  // A card reset: the master's words are forgotten and not written until it sends again.
  EXPECT_EQ(proxy_->CommandWords(), ScannerWords{});
  const std::uint32_t writes = proxy_->counters().command_writes;
  RunFor(kSecond);
  EXPECT_EQ(proxy_->counters().command_writes, writes);
  EXPECT_EQ(Reg(kFa06), 0);
  EXPECT_EQ(Reg(0xC524), 192);  // written back again (the reset cleared it)
  proxy_->SetCommandWords(stopped);
  RunFor(100 * kMilli);
  EXPECT_EQ(Reg(kFa06), 0xC000);
  EXPECT_EQ(Reg(kFa07), 0);  // word 2 is no longer exchanged
}

TEST_F(RegisterProxyTest, E23OnSilenceThenRecoveryReloadsAndWritesTheWordsAgain) {
  StartLoaded();
  proxy_->SetCommandWords(kRun60Hz);
  RunFor(kSecond);
  server_->Inject({sim::Fault::Kind::kSilent, sim::Fault::kUntilCleared, 0});
  const Micros silent_at = Now();
  const auto fault_at = RunUntilTrue([this] { return proxy_->link().option_fault(); }, 2 * kSecond);
  ASSERT_TRUE(fault_at.has_value());
  EXPECT_GE(*fault_at - silent_at, kSecond);  // three transactions of three attempts each
  EXPECT_LE(*fault_at - silent_at, 1100 * kMilli);
  RecordingListener listener;
  EXPECT_EQ(proxy_->Read(0x0003, listener).status().code(), base::StatusCode::kFailedPrecondition);
  model_.PowerCycle();  // while the link was down the inverter lost its RAM
  server_->ClearFaults();
  ASSERT_TRUE(RunUntilTrue([this] { return config_.loads.size() == 2; }, 4 * kSecond).has_value());
  EXPECT_FALSE(proxy_->link().option_fault());
  EXPECT_EQ(proxy_->link().counters().faults, 1U);
  // Not a card reset: the master's words are still held and written again.
  ASSERT_TRUE(RunUntilTrue([this] { return Reg(kFa06) == 0xC400 && Reg(kFa07) == 0x1770; }, kSecond).has_value());
  EXPECT_TRUE(proxy_->IsScannerTarget(kFa06));
}

// ---- Values the card owns --------------------------------------------------------------------------

TEST_F(RegisterProxyTest, WritesBackWhatTheCardOwnsWhenItChanges) {
  SetEeprom({{kAcc, 10}});
  StartLoaded();
  config::CardStatus status;
  status.port_rates = {3, 0};
  status.mac = {0x02, 0x00, 0x5E, 0x10, 0x20, 0x30};
  status.ip = {192, 168, 1, 12};
  status.netmask = {255, 255, 255, 0};
  status.gateway = {192, 168, 1, 1};
  proxy_->SetCardStatus(status);
  RunFor(2 * kSecond);
  EXPECT_EQ(Reg(0xC502), 3);
  EXPECT_EQ(Reg(0xC503), 0);
  const std::array<std::uint16_t, 6> mac_numbers = {0xC517, 0xC518, 0xC519, 0xC520, 0xC521, 0xC522};
  for (std::size_t i = 0; i < 6; ++i) EXPECT_EQ(Reg(mac_numbers[i]), status.mac.octets()[i]) << i;
  const std::array<std::uint16_t, 12> address_numbers = {0xC524, 0xC525, 0xC526, 0xC527, 0xC528, 0xC529,
                                                         0xC530, 0xC531, 0xC532, 0xC533, 0xC534, 0xC535};
  const std::array<std::uint16_t, 12> address_values = {192, 168, 1, 12, 255, 255, 255, 0, 192, 168, 1, 1};
  for (std::size_t i = 0; i < 12; ++i) EXPECT_EQ(Reg(address_numbers[i]), address_values[i]) << i;
  EXPECT_EQ(Reg(0xC536), 0);
  EXPECT_EQ(Reg(0xC555), 3);  // stopped: gate block
  EXPECT_EQ(Reg(0xC061), 0x4800);

  const std::uint32_t writes = proxy_->counters().owned_writes;
  proxy_->SetCardStatus(status);  // unchanged: nothing is written
  RunFor(kSecond);
  EXPECT_EQ(proxy_->counters().owned_writes, writes);
  status.ip = base::Ipv4Address(192, 168, 1, 13);
  proxy_->SetCardStatus(status);
  RunFor(200 * kMilli);
  EXPECT_EQ(Reg(0xC527), 13);
  EXPECT_EQ(proxy_->counters().owned_writes, writes + 1);

  proxy_->SetCommandWords(kRun60Hz);
  RunFor(2 * kSecond);
  EXPECT_EQ(Reg(0xC555), 4);  // running
  EXPECT_EQ(Reg(0xC041), 0xC400);
  EXPECT_EQ(Reg(0xC042), 0x1770);
  EXPECT_EQ(Reg(0xC043), 0);
  EXPECT_EQ(Reg(0xC061), 0x6400);
  EXPECT_EQ(Reg(0xC062), 0x1770);
  model_.Trip(kEmergencyStopTrip);
  RunFor(200 * kMilli);
  EXPECT_EQ(Reg(0xC555), 23);  // fault
  status.ethernet_error = 2;   // network overload, reported by the firmware
  proxy_->SetCardStatus(status);
  RunFor(200 * kMilli);
  EXPECT_EQ(Reg(0xC536), 2);
  EXPECT_EQ(model_.EepromWriteCount(0xC536), 0U);
}

// ---- Loss actions -----------------------------------------------------------------------------------

struct LossSetup {
  int c100 = 5;  // 0.5 s
  int c101 = 4;
  int c102 = 0;
  int c103 = 0;
  int cmod = 1;
  int fmod = 0;
};

class RegisterProxyLossTest : public RegisterProxyFixture {
 protected:
  // Runs the drive at 60 Hz from the master's words, then reports the network lost. acc = dec = 1.0 s
  // (0 <-> 80 Hz), sr2 = 20 Hz.
  void RunThenLose(const LossSetup& s, ScannerWords words = kRun60Hz, LossCause cause = LossCause::kModbusIoScanning) {
    SetEeprom({{0xC100, s.c100}, {0xC101, s.c101}, {0xC102, s.c102}, {0xC103, s.c103}, {0x0003, s.cmod},
               {0x0004, s.fmod}, {kAcc, 10}, {kDec, 10}, {kSr2, 2000}});
    StartLoaded();
    proxy_->SetCommandWords(words);
    RunFor(1500 * kMilli);
    lost_at_ = Now();
    deadline_ = lost_at_ + static_cast<Micros>(s.c100) * 100 * kMilli;
    proxy_->NetworkLost(cause, lost_at_);
  }

  // Runs to just before the c100 deadline (nothing may have happened yet), then until FA06 holds `fa06`;
  // returns when that happened.
  std::optional<Micros> ExpectFa06AfterDelay(std::uint16_t fa06) {
    RunUntil(deadline_ - 1);
    EXPECT_FALSE(proxy_->loss_action_active());
    EXPECT_EQ(Reg(kFa06), 0xC400);
    return RunUntilTrue([this, fa06] { return Reg(kFa06) == fa06; }, kSecond);
  }

  Micros lost_at_ = 0;
  Micros deadline_ = 0;
};

TEST_F(RegisterProxyLossTest, Action0StopsAndLeavesTheDriveToCmodFmod) {
  RunThenLose({.c101 = 0});
  RunFor(400 * kMilli);
  EXPECT_EQ(Reg(0xC536), 1);  // Modbus IO scanning time-out, written back at once
  const auto at = ExpectFa06AfterDelay(0x0000);
  ASSERT_TRUE(at.has_value());
  EXPECT_GE(*at, deadline_);
  EXPECT_LE(*at, deadline_ + kExchange);  // the transaction on the wire, then the action
  EXPECT_TRUE(proxy_->loss_action_active());
  const std::uint32_t writes = proxy_->counters().command_writes;
  RunFor(1500 * kMilli);
  EXPECT_EQ(Reg(kFd00), 0);  // cmod = 1 (panel, not running): stopped
  EXPECT_EQ(Reg(kFa06), 0);
  EXPECT_EQ(proxy_->counters().command_writes, writes);  // the master's words are no longer written

  proxy_->NetworkRestored(Now());
  RunFor(200 * kMilli);
  EXPECT_FALSE(proxy_->loss_action_active());
  EXPECT_EQ(Reg(0xC536), 0);
  EXPECT_EQ(Reg(kFa06), 0);  // not before the master sends again
  proxy_->SetCommandWords(kRun60Hz);
  RunFor(100 * kMilli);
  EXPECT_EQ(Reg(kFa06), 0xC400);
}

TEST_F(RegisterProxyLossTest, WordsSentDuringTheActionAreWrittenWhenRestored) {
  RunThenLose({.c101 = 3});
  ASSERT_TRUE(ExpectFa06AfterDelay(0x8800).has_value());
  proxy_->SetCommandWords({0xC400, 0x0BB8, 0, 0, 0, 0});  // the master is back before the front end says so
  RunFor(100 * kMilli);
  EXPECT_EQ(Reg(kFa06), 0x8800);  // not while the action is in force
  EXPECT_EQ(Reg(kFa07), 0x1770);
  proxy_->NetworkRestored(Now());
  const Micros restored_at = Now();
  const auto at = RunUntilTrue([this] { return Reg(kFa06) == 0xC400 && Reg(kFa07) == 0x0BB8; }, kSecond);
  ASSERT_TRUE(at.has_value());
  EXPECT_LE(*at - restored_at, 2 * kExchange);
}

TEST_F(RegisterProxyLossTest, Action1ContinuesWithTheHeldWords) {
  RunThenLose({.c101 = 1});
  RunUntil(deadline_ + 100 * kMilli);
  EXPECT_EQ(proxy_->counters().loss_actions, 1U);
  EXPECT_FALSE(proxy_->loss_action_active());
  const std::uint32_t writes = proxy_->counters().command_writes;
  RunFor(kSecond);
  EXPECT_GT(proxy_->counters().command_writes, writes);  // refreshes go on
  EXPECT_EQ(Reg(kFa06), 0xC400);
  EXPECT_EQ(Reg(kFd00), 0x1770);
  EXPECT_EQ(proxy_->counters().loss_action_writes, 0U);
}

TEST_F(RegisterProxyLossTest, Action2DeceleratesToAStop) {
  RunThenLose({.c101 = 2});
  const auto at = ExpectFa06AfterDelay(0xC000);  // held C400 without run, command priority kept
  ASSERT_TRUE(at.has_value());
  EXPECT_LE(*at, deadline_ + kExchange);
  RunFor(200 * kMilli);
  EXPECT_GT(Reg(kFd00), 0);  // decelerating, not coasting
  RunFor(kSecond);
  EXPECT_EQ(Reg(kFd00), 0);
  EXPECT_EQ(Reg(kFa07), 0x1770);
}

TEST_F(RegisterProxyLossTest, Action3CoastsToAStop) {
  RunThenLose({.c101 = 3}, kRun60Hz, LossCause::kCarrierLost);
  RunFor(200 * kMilli);
  EXPECT_EQ(Reg(0xC536), 3);  // loss of carrier
  const auto at = ExpectFa06AfterDelay(0x8800);
  ASSERT_TRUE(at.has_value());
  EXPECT_LE(*at, deadline_ + kExchange);
  EXPECT_EQ(Reg(kFd00), 0);  // the output is cut at once
}

TEST_F(RegisterProxyLossTest, Action4TripsErr8ThroughFa30) {
  RunThenLose({.c101 = 4}, kRun60Hz, LossCause::kCipConnection);
  RunFor(200 * kMilli);
  EXPECT_EQ(Reg(0xC536), 0);  // no code for a CIP connection time-out
  RunUntil(deadline_ - 1);
  EXPECT_FALSE(model_.tripped());
  const auto at = RunUntilTrue([this] { return model_.tripped(); }, kSecond);
  ASSERT_TRUE(at.has_value());
  EXPECT_LE(*at, deadline_ + kExchange);
  EXPECT_EQ(model_.trip(), 27);  // err8
  EXPECT_EQ(Reg(0xFC90), 0x1B);
  RunFor(kSecond);
  EXPECT_EQ(proxy_->counters().loss_action_writes, 1U);  // written once
  EXPECT_EQ(proxy_->counters().loss_action_errors, 0U);
  EXPECT_EQ(Reg(0xC555), 23);
  proxy_->NetworkRestored(Now());
  RunFor(kSecond);
  EXPECT_TRUE(model_.tripped());  // err8 stays until a power cycle or f899
}

TEST_F(RegisterProxyLossTest, Action5RunsAtTheC102PresetSpeed) {
  RunThenLose({.c101 = 5, .c102 = 2});
  const auto at = ExpectFa06AfterDelay(0x8402);  // command priority, run, preset 2
  ASSERT_TRUE(at.has_value());
  EXPECT_LE(*at, deadline_ + kExchange);
  RunFor(kSecond);
  EXPECT_EQ(Reg(kFd00), 2000);  // sr2
  const std::uint32_t writes = proxy_->counters().loss_action_writes;
  RunFor(kSecond);
  EXPECT_EQ(proxy_->counters().loss_action_writes, writes + 2);  // refreshed every 500 ms
}

TEST_F(RegisterProxyLossTest, Action5WithoutPresetKeepsTheHeldCommandRunning) {
  RunThenLose({.c101 = 5, .c102 = 0}, {0x4000, 0x1770, 0, 0, 0, 0});  // frequency priority only: not running
  RunUntil(deadline_ + kExchange);
  EXPECT_TRUE(proxy_->loss_action_active());
  EXPECT_EQ(Reg(kFa06), 0xC400);  // held word + command priority + run
  RunFor(kSecond);
  EXPECT_EQ(Reg(kFd00), 0x1770);
}

TEST_F(RegisterProxyLossTest, Condition1NotMetLeavesTheDriveAlone) {
  RunThenLose({.c101 = 3, .c103 = 1});  // cmod 1 / fmod 0: not network modes
  RunUntil(deadline_ + 4 * kExchange);
  EXPECT_FALSE(proxy_->loss_action_active());
  EXPECT_EQ(proxy_->counters().loss_actions, 0U);
  RunFor(kSecond);
  EXPECT_EQ(Reg(kFa06), 0xC400);
  EXPECT_EQ(Reg(kFd00), 0x1770);
}

TEST_F(RegisterProxyLossTest, Condition1ReadsCmodAndFmodWhenTheDelayEnds) {
  // Loaded with cmod 1 / fmod 0, changed on the panel since (while stopped: not writable during run).
  RunThenLose({.c101 = 3, .c103 = 1}, {0xC000, 0x1770, 0, 0, 0, 0});
  ASSERT_EQ(model_.Write(0x0003, 4, WriteTarget::kRamOnly).outcome, sim::WriteOutcome::kOk);
  ASSERT_EQ(model_.Write(0x0004, 7, WriteTarget::kRamOnly).outcome, sim::WriteOutcome::kOk);
  RunUntil(deadline_ - 1);
  EXPECT_EQ(Reg(kFa06), 0xC000);
  const auto at = RunUntilTrue([this] { return Reg(kFa06) == 0x8800; }, kSecond);
  ASSERT_TRUE(at.has_value());
  EXPECT_LE(*at, deadline_ + 3 * kExchange);  // the transaction on the wire, cmod, fmod, then the action
  EXPECT_EQ(proxy_->config().cmod, 1);  // the configuration in force is not changed by that
}

TEST_F(RegisterProxyLossTest, Condition2NeedsTheDriveRunning) {
  RunThenLose({.c101 = 3, .c103 = 2, .cmod = 4, .fmod = 7});
  const auto at = ExpectFa06AfterDelay(0x8800);
  ASSERT_TRUE(at.has_value());
  EXPECT_LE(*at, deadline_ + 3 * kExchange);
}

TEST_F(RegisterProxyLossTest, Condition2NotMetWhenStopped) {
  RunThenLose({.c101 = 3, .c103 = 2, .cmod = 4, .fmod = 7}, {0xC000, 0x1770, 0, 0, 0, 0});
  RunUntil(deadline_ + 4 * kExchange);
  EXPECT_FALSE(proxy_->loss_action_active());
  EXPECT_EQ(Reg(kFa06), 0xC000);
}

TEST_F(RegisterProxyLossTest, RestoredBeforeTheDelayNothingHappens) {
  RunThenLose({.c100 = 10, .c101 = 3});
  RunFor(300 * kMilli);
  EXPECT_EQ(Reg(0xC536), 1);
  proxy_->NetworkRestored(Now());
  RunFor(2 * kSecond);
  EXPECT_EQ(proxy_->counters().loss_actions, 0U);
  EXPECT_EQ(Reg(kFa06), 0xC400);
  EXPECT_EQ(Reg(kFd00), 0x1770);
  EXPECT_EQ(Reg(0xC536), 0);
}

TEST_F(RegisterProxyLossTest, ALossReportedBeforeTheConfigurationWaitsForIt) {
  SetEeprom({{0xC101, 3}});
  Start();
  proxy_->NetworkLost(LossCause::kCarrierLost, Now());
  const auto at = RunUntilTrue([this] { return Reg(kFa06) == 0x8800; }, 3 * kSecond);
  ASSERT_TRUE(at.has_value());
  // c100 = 0, but c101 is only known once loaded: the first own transaction after the load is the action.
  EXPECT_EQ(*at, kStart + kSecond + kLoadTime);
  EXPECT_TRUE(proxy_->loss_action_active());
}

TEST_F(RegisterProxyLossTest, ZeroDelayActsAtOnce) {
  RunThenLose({.c100 = 0, .c101 = 3});
  const auto at = RunUntilTrue([this] { return Reg(kFa06) == 0x8800; }, kSecond);
  ASSERT_TRUE(at.has_value());
  EXPECT_LE(*at, lost_at_ + kExchange);
}

}  // namespace
}  // namespace drive_link::test
