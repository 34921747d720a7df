// Unit 255, IO scanning (seed 000 §9, MB-4), and the c523 loss supervision (§3.2.3, MB-5).
#include <gtest/gtest.h>

#include "modbus_fakes.h"

namespace modbus {
namespace {

using drive_link::LossCause;
using test::Bytes;
using test::FakeLossSupervision;
using test::ServerHarness;
using Event = FakeLossSupervision::Event;

constexpr hal::Micros kSecond = hal::kMicrosPerSecond;

// FC 23: write output words 0-5 (word 0 reserved), then read input words 0-6.
const Bytes kScan = {0x00, 0x01, 0x00, 0x00, 0x00, 0x17, 0xFF, 0x17, 0x00, 0x00, 0x00, 0x07, 0x00, 0x00,
                     0x00, 0x06, 0x0C, 0xFF, 0xFF, 0x04, 0x00, 0x17, 0x70, 0x00, 0x03, 0x00, 0x04, 0x00, 0x05};
const Bytes kScanAnswer = {0x00, 0x01, 0x00, 0x00, 0x00, 0x11, 0xFF, 0x17, 0x0E, 0x00, 0x00, 0x40, 0x00, 0x17,
                           0x70, 0x00, 0x0D, 0x00, 0x0E, 0x00, 0x0F, 0x00, 0x10};
const Bytes kScanRefused = {0x00, 0x01, 0x00, 0x00, 0x00, 0x03, 0xFF, 0x97, 0x01};

class ModbusIoScanningTest : public ::testing::Test {
 protected:
  void SetUp() override {
    config_.io_scanning = true;
    config_.timeout_tenths = 20;  // c523 = 2.0 s
    h_.server.Configure(config_);
    h_.scanner.monitor_words = {0x4000, 0x1770, 0x000D, 0x000E, 0x000F, 0x0010};
  }

  config::CardConfig config_;
  ServerHarness h_;
};

TEST_F(ModbusIoScanningTest, ReadWrite_WritesCommandWordsThenReadsMonitorWords) {
  const ConnectionId id = h_.Connect();
  EXPECT_EQ(h_.Exchange(id, kScan), kScanAnswer);
  EXPECT_EQ(h_.scanner.command_words, (drive_link::ScannerWords{0x0400, 0x1770, 3, 4, 5, 0}));
  EXPECT_EQ(h_.scanner.set_calls, 1);
  EXPECT_TRUE(h_.drive.log.empty());
}

TEST_F(ModbusIoScanningTest, IoScanningOff_Exception01) {
  config_.io_scanning = false;
  h_.server.Configure(config_);
  const ConnectionId id = h_.Connect();
  EXPECT_EQ(h_.Exchange(id, kScan), kScanRefused);
  EXPECT_EQ(h_.Exchange(id, {0x00, 0x01, 0x00, 0x00, 0x00, 0x06, 0xFF, 0x03, 0x00, 0x01, 0x00, 0x01}),
            (Bytes{0x00, 0x01, 0x00, 0x00, 0x00, 0x03, 0xFF, 0x83, 0x01}));
  EXPECT_EQ(h_.scanner.set_calls, 0);
}

TEST_F(ModbusIoScanningTest, MasterSet_OnlyTheMasterIsServed) {
  config_.modbus_master = {192, 168, 1, 30};
  h_.server.Configure(config_);
  const ConnectionId other = h_.Connect(test::kOtherAddress);
  EXPECT_EQ(h_.Exchange(other, kScan), kScanRefused);
  EXPECT_EQ(h_.scanner.set_calls, 0);
  const ConnectionId master = h_.Connect(test::kClientAddress);
  EXPECT_EQ(h_.Exchange(master, kScan), kScanAnswer);
}

TEST_F(ModbusIoScanningTest, ReservedWords_ReadZeroWritesIgnored) {
  const ConnectionId id = h_.Connect();
  // FC 16 of all 32 output words (the seed's PL7 example writes 32): only words 1-6 reach the image.
  Bytes write_all = {0x00, 0x02, 0x00, 0x00, 0x00, 0x47, 0xFF, 0x10, 0x00, 0x00, 0x00, 0x20, 0x40};
  for (std::uint8_t word = 0; word < 32; ++word) {
    write_all.push_back(0x10);
    write_all.push_back(word);
  }
  EXPECT_EQ(h_.Exchange(id, write_all), (Bytes{0x00, 0x02, 0x00, 0x00, 0x00, 0x06, 0xFF, 0x10, 0x00, 0x00, 0x00, 0x20}));
  EXPECT_EQ(h_.scanner.command_words, (drive_link::ScannerWords{0x1001, 0x1002, 0x1003, 0x1004, 0x1005, 0x1006}));
  // Words 7-31 only: the image is not touched.
  EXPECT_EQ(h_.Exchange(id, {0x00, 0x03, 0x00, 0x00, 0x00, 0x09, 0xFF, 0x10, 0x00, 0x07, 0x00, 0x01, 0x02, 0x12,
                             0x34}),
            (Bytes{0x00, 0x03, 0x00, 0x00, 0x00, 0x06, 0xFF, 0x10, 0x00, 0x07, 0x00, 0x01}));
  EXPECT_EQ(h_.scanner.set_calls, 1);
  // Input words 6-8: monitor word 6, then reserved zeros.
  EXPECT_EQ(h_.Exchange(id, {0x00, 0x04, 0x00, 0x00, 0x00, 0x06, 0xFF, 0x03, 0x00, 0x06, 0x00, 0x03}),
            (Bytes{0x00, 0x04, 0x00, 0x00, 0x00, 0x09, 0xFF, 0x03, 0x06, 0x00, 0x10, 0x00, 0x00, 0x00, 0x00}));
}

TEST_F(ModbusIoScanningTest, WriteSingleOutputWord_EchoAndOneCommandWord) {
  const ConnectionId id = h_.Connect();
  EXPECT_EQ(h_.Exchange(id, {0x00, 0x05, 0x00, 0x00, 0x00, 0x06, 0xFF, 0x06, 0x00, 0x02, 0x0B, 0xB8}),
            (Bytes{0x00, 0x05, 0x00, 0x00, 0x00, 0x06, 0xFF, 0x06, 0x00, 0x02, 0x0B, 0xB8}));
  EXPECT_EQ(h_.scanner.command_words, (drive_link::ScannerWords{0, 0x0BB8, 0, 0, 0, 0}));
}

TEST_F(ModbusIoScanningTest, WordsBeyond31_Exception02NothingWritten) {
  const ConnectionId id = h_.Connect();
  EXPECT_EQ(h_.Exchange(id, {0x00, 0x06, 0x00, 0x00, 0x00, 0x06, 0xFF, 0x03, 0x00, 0x1F, 0x00, 0x02}),
            (Bytes{0x00, 0x06, 0x00, 0x00, 0x00, 0x03, 0xFF, 0x83, 0x02}));
  // FC 23 with a good write range and a bad read range: refused before writing.
  EXPECT_EQ(h_.Exchange(id, {0x00, 0x07, 0x00, 0x00, 0x00, 0x0F, 0xFF, 0x17, 0x00, 0x1F, 0x00, 0x02, 0x00, 0x01,
                             0x00, 0x02, 0x04, 0x00, 0x01, 0x00, 0x02}),
            (Bytes{0x00, 0x07, 0x00, 0x00, 0x00, 0x03, 0xFF, 0x97, 0x02}));
  EXPECT_EQ(h_.Exchange(id, {0x00, 0x08, 0x00, 0x00, 0x00, 0x06, 0xFF, 0x06, 0x00, 0x20, 0x00, 0x01}),
            (Bytes{0x00, 0x08, 0x00, 0x00, 0x00, 0x03, 0xFF, 0x86, 0x02}));
  EXPECT_EQ(h_.scanner.set_calls, 0);
}

TEST_F(ModbusIoScanningTest, ReadWriteLimits20_Exception03) {
  const ConnectionId id = h_.Connect();
  // Read 21 words.
  EXPECT_EQ(h_.Exchange(id, {0x00, 0x09, 0x00, 0x00, 0x00, 0x0D, 0xFF, 0x17, 0x00, 0x00, 0x00, 0x15, 0x00, 0x01,
                             0x00, 0x01, 0x02, 0x00, 0x01}),
            (Bytes{0x00, 0x09, 0x00, 0x00, 0x00, 0x03, 0xFF, 0x97, 0x03}));
  // Write 21 words.
  Bytes write21 = {0x00, 0x0A, 0x00, 0x00, 0x00, 0x00, 0xFF, 0x17, 0x00, 0x00, 0x00, 0x01, 0x00, 0x00, 0x00, 0x15, 0x2A};
  write21.resize(write21.size() + 42, 0x00);
  write21[5] = static_cast<std::uint8_t>(write21.size() - 6);
  EXPECT_EQ(h_.Exchange(id, write21), (Bytes{0x00, 0x0A, 0x00, 0x00, 0x00, 0x03, 0xFF, 0x97, 0x03}));
  // Byte count not twice the write count.
  EXPECT_EQ(h_.Exchange(id, {0x00, 0x0B, 0x00, 0x00, 0x00, 0x0D, 0xFF, 0x17, 0x00, 0x00, 0x00, 0x01, 0x00, 0x01,
                             0x00, 0x01, 0x03, 0x00, 0x01}),
            (Bytes{0x00, 0x0B, 0x00, 0x00, 0x00, 0x03, 0xFF, 0x97, 0x03}));
  // 20/20 is served.
  Bytes full = {0x00, 0x0C, 0x00, 0x00, 0x00, 0x00, 0xFF, 0x17, 0x00, 0x00, 0x00, 0x14, 0x00, 0x00, 0x00, 0x14, 0x28};
  full.resize(full.size() + 40, 0x00);
  full[5] = static_cast<std::uint8_t>(full.size() - 6);
  const Bytes answer = h_.Exchange(id, full);
  ASSERT_EQ(answer.size(), 9u + 40u);
  EXPECT_EQ(answer[7], 0x17);
  EXPECT_EQ(answer[8], 40);
}

// --- Loss supervision (c523) ---

TEST_F(ModbusIoScanningTest, NoCommunicationYet_NoLoss) {
  h_.Connect();
  h_.Advance(60 * kSecond);
  EXPECT_TRUE(h_.loss.events.empty());
  EXPECT_EQ(h_.server.loss_state(), LossState::kWaiting);
}

TEST_F(ModbusIoScanningTest, ScannerStops_LostExactlyC523AfterLastScanThenRestored) {
  const ConnectionId id = h_.Connect();
  h_.Exchange(id, kScan);
  const hal::Micros last = h_.now;
  EXPECT_EQ(h_.server.NextDeadline(), last + 2 * kSecond);
  h_.Advance(2 * kSecond - 1);
  EXPECT_TRUE(h_.loss.events.empty());
  h_.Advance(1);
  EXPECT_EQ(h_.loss.events, (std::vector<Event>{{true, LossCause::kModbusIoScanning, last + 2 * kSecond}}));
  EXPECT_EQ(h_.server.loss_state(), LossState::kLost);
  h_.Advance(10 * kSecond);
  EXPECT_EQ(h_.loss.events.size(), 1u);
  // The master is back.
  h_.Exchange(id, kScan);
  ASSERT_EQ(h_.loss.events.size(), 2u);
  EXPECT_EQ(h_.loss.events[1], (Event{false, LossCause::kModbusConnection, h_.now}));
  EXPECT_EQ(h_.server.loss_state(), LossState::kRunning);
}

TEST_F(ModbusIoScanningTest, LatePoll_LossReportedAtTheExpiryInstant) {
  const ConnectionId id = h_.Connect();
  h_.Exchange(id, kScan);
  const hal::Micros last = h_.now;
  h_.Advance(7 * kSecond);
  EXPECT_EQ(h_.loss.events, (std::vector<Event>{{true, LossCause::kModbusIoScanning, last + 2 * kSecond}}));
}

TEST_F(ModbusIoScanningTest, ScansKeepTheTimerRunning) {
  const ConnectionId id = h_.Connect();
  for (int i = 0; i < 10; ++i) {
    h_.Exchange(id, kScan);
    h_.Advance(1900 * hal::kMicrosPerMilli);
  }
  EXPECT_TRUE(h_.loss.events.empty());
  EXPECT_EQ(h_.server.counters().counted, 10u);
}

TEST_F(ModbusIoScanningTest, ReadsAndOtherClientsDoNotCount) {
  config_.modbus_master = {192, 168, 1, 30};
  h_.server.Configure(config_);
  const ConnectionId master = h_.Connect(test::kClientAddress);
  const ConnectionId other = h_.Connect(test::kOtherAddress);
  h_.Exchange(master, kScan);
  const hal::Micros last = h_.now;
  h_.Advance(kSecond);
  h_.Exchange(other, kScan);  // refused: not the master
  h_.Exchange(master, {0x00, 0x01, 0x00, 0x00, 0x00, 0x06, 0xFF, 0x03, 0x00, 0x01, 0x00, 0x01});  // a read
  h_.Exchange(master, {0x00, 0x01, 0x00, 0x00, 0x00, 0x06, 0x01, 0x06, 0xFA, 0x07, 0x00, 0x01});  // not unit 255
  h_.Advance(kSecond);
  EXPECT_EQ(h_.loss.events, (std::vector<Event>{{true, LossCause::kModbusIoScanning, last + 2 * kSecond}}));
}

TEST_F(ModbusIoScanningTest, TimeoutDisabled_NoLoss) {
  config_.timeout_tenths = 0;
  h_.server.Configure(config_);
  const ConnectionId id = h_.Connect();
  h_.Exchange(id, kScan);
  h_.Advance(100 * kSecond);
  EXPECT_TRUE(h_.loss.events.empty());
  EXPECT_EQ(h_.server.loss_state(), LossState::kDisabled);
}

class ModbusConnectionLossTest : public ::testing::Test {
 protected:
  void SetUp() override {
    config_.io_scanning = false;
    config_.timeout_tenths = 5;  // 0.5 s, the smallest non-zero c523
    h_.server.Configure(config_);
    h_.drive.registers = {{0x0009, 100}, {0xFA06, 0}, {0xFA07, 0}};
    id_ = h_.Connect();
  }

  config::CardConfig config_;
  ServerHarness h_;
  ConnectionId id_ = 0;
};

TEST_F(ModbusConnectionLossTest, CommandWriteArmsTimer_LostWithConnectionCause) {
  h_.Exchange(id_, {0x00, 0x01, 0x00, 0x00, 0x00, 0x06, 0x01, 0x06, 0xFA, 0x07, 0x17, 0x70});
  const hal::Micros last = h_.now;
  h_.Advance(500 * hal::kMicrosPerMilli);
  EXPECT_EQ(h_.loss.events, (std::vector<Event>{{true, LossCause::kModbusConnection, last + 500'000}}));
}

TEST_F(ModbusConnectionLossTest, ReadsAndParameterWrites_DoNotCount) {
  h_.Exchange(id_, {0x00, 0x01, 0x00, 0x00, 0x00, 0x06, 0x01, 0x03, 0xFA, 0x07, 0x00, 0x01});
  h_.Exchange(id_, {0x00, 0x02, 0x00, 0x00, 0x00, 0x06, 0x01, 0x06, 0x00, 0x09, 0x00, 0x01});
  h_.Advance(10 * kSecond);
  EXPECT_TRUE(h_.loss.events.empty());
  EXPECT_EQ(h_.server.counters().counted, 0u);
}

TEST_F(ModbusConnectionLossTest, MultipleWriteReachingCommandArea_Counts) {
  // FA05..FA07 over two registers: FA05, FA06.
  h_.Exchange(id_, {0x00, 0x03, 0x00, 0x00, 0x00, 0x0B, 0x01, 0x10, 0xFA, 0x05, 0x00, 0x02, 0x04, 0x00, 0x00,
                    0x00, 0x00});
  EXPECT_EQ(h_.server.counters().counted, 1u);
}

TEST_F(ModbusConnectionLossTest, CountedAtArrivalEvenWhenTheDriveFails) {
  h_.drive.link_down = true;
  const Bytes answer = h_.Exchange(id_, {0x00, 0x04, 0x00, 0x00, 0x00, 0x06, 0x01, 0x06, 0xFA, 0x06, 0x04, 0x00});
  EXPECT_EQ(answer, (Bytes{0x00, 0x04, 0x00, 0x00, 0x00, 0x03, 0x01, 0x86, 0x04}));
  EXPECT_EQ(h_.server.counters().counted, 1u);
  EXPECT_EQ(h_.server.loss_state(), LossState::kRunning);
}

TEST_F(ModbusConnectionLossTest, PipelinedCommand_TimedFromItsArrival) {
  // Two command writes in one segment; the second is served only after the first one's drive access,
  // but the timer runs from the moment both arrived.
  const Bytes write = {0x00, 0x05, 0x00, 0x00, 0x00, 0x06, 0x01, 0x06, 0xFA, 0x07, 0x00, 0x01};
  Bytes two = write;
  two.insert(two.end(), write.begin(), write.end());
  h_.server.Receive(id_, two, h_.now);
  const hal::Micros arrival = h_.now;
  h_.now += 300 * hal::kMicrosPerMilli;
  h_.drive.Poll();
  h_.drive.Poll();
  h_.Advance(200 * hal::kMicrosPerMilli);
  EXPECT_EQ(h_.loss.events, (std::vector<Event>{{true, LossCause::kModbusConnection, arrival + 500'000}}));
}

}  // namespace
}  // namespace modbus
