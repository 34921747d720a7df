// The simulated inverter's protocol server (sim/include/sim/protocol_server.h): bytes written on the
// card's end of a socket pair, answered through the behaviour model, read back as exact bytes. Expected
// frames are the manual's worked examples (seed 003 §3, §4) wherever one exists.
#include "sim/protocol_server.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <memory>
#include <string_view>
#include <vector>

#include "drive_link/wire/toshiba_frame.h"
#include "fake_clock.h"
#include "sim/inverter_model.h"
#include "sim/register_numbers.h"
#include "socket_serial_port.h"

namespace sim {
namespace {

namespace wire = drive_link::wire;
using hal::kNever;
using hal::Micros;
using hal::host::PollSet;
using hal::host::SocketSerialPort;
using Bytes = std::vector<std::uint8_t>;

constexpr hal::Micros kSecond = hal::kMicrosPerSecond;
constexpr hal::Micros kMilli = hal::kMicrosPerMilli;

Bytes Ascii(std::string_view text) {
  Bytes bytes(text.begin(), text.end());
  bytes.push_back(wire::kCarriageReturn);
  return bytes;
}

class InverterProtocolServerTest : public ::testing::Test {
 protected:
  InverterProtocolServerTest() {
    auto pair = SocketSerialPort::CreatePair();
    EXPECT_TRUE(pair.ok());
    if (pair.ok()) pair_ = std::move(pair.value());
  }

  // Builds the server and runs it past the model's 1 s power-on silence.
  void Start(ServerConfig config = {}) {
    server_ = std::make_unique<InverterProtocolServer>(model_, *pair_.inverter, clock_, config);
    Poll();  // the model's time base: the silence runs to now + 1 s
    ASSERT_TRUE(model_.in_reset(clock_.NowMicros()));
    clock_.Advance(1100 * kMilli);
    Poll();
    ASSERT_FALSE(model_.in_reset(clock_.NowMicros()));
  }

  void Poll() { server_->Poll(clock_.NowMicros()); }

  void Send(const Bytes& bytes) {
    const auto written = pair_.card->Write(bytes);
    ASSERT_TRUE(written.ok());
    ASSERT_EQ(*written, bytes.size());
  }

  Bytes Received() {
    Bytes out;
    std::array<std::uint8_t, 64> buffer{};
    for (;;) {
      const auto read = pair_.card->Read(buffer);
      if (!read.ok() || *read == 0) break;
      out.insert(out.end(), buffer.begin(), buffer.begin() + static_cast<std::ptrdiff_t>(*read));
    }
    return out;
  }

  // Runs the server, jumping the clock from deadline to deadline, until it is idle; returns what the card
  // received. Bounded: a server that never settles fails the test instead of hanging it.
  Bytes Settle() {
    Bytes out;
    for (int i = 0; i < 100; ++i) {
      const Bytes got = Received();
      out.insert(out.end(), got.begin(), got.end());
      const hal::Micros deadline = server_->NextDeadline();
      if (deadline == kNever) return out;
      EXPECT_GE(deadline, clock_.NowMicros()) << "a deadline in the past: the loop would spin";
      clock_.Set(std::max(deadline, clock_.NowMicros()));
      Poll();
    }
    ADD_FAILURE() << "server never went idle";
    return out;
  }

  // One request, everything that comes back.
  Bytes Exchange(const Bytes& request) {
    Send(request);
    Poll();
    return Settle();
  }

  hal::test::FakeClock clock_{1000 * kSecond};
  InverterModel model_{Model::kVfMb1};
  SocketSerialPort::Pair pair_;
  std::unique_ptr<InverterProtocolServer> server_;
};

// --- Reads and writes ---

TEST_F(InverterProtocolServerTest, BinaryReadOfStatusWhenStopped) {
  Start();
  // Power-on, FA06 = FA00 = 0: ready, ST off (seed 000 §5.1.6 (1): 4800h).
  EXPECT_EQ(Exchange({0x2F, 0x52, 0xFD, 0x01, 0x7F}), (Bytes{0x2F, 0x52, 0xFD, 0x01, 0x48, 0x00, 0xC7}));
  // P FA00 = 8000h (RS485 command priority): stopped and ready, 4000h (seed 003 §9.1, §4 example).
  EXPECT_EQ(Exchange({0x2F, 0x50, 0xFA, 0x00, 0x80, 0x00, 0xF9}), (Bytes{0x2F, 0x50, 0xFA, 0x00, 0x80, 0x00, 0xF9}));
  EXPECT_EQ(Exchange({0x2F, 0x52, 0xFD, 0x01, 0x7F}), (Bytes{0x2F, 0x52, 0xFD, 0x01, 0x40, 0x00, 0xBF}));
  EXPECT_EQ(server_->counters().requests, 3U);
  EXPECT_EQ(server_->counters().replies, 3U);
  EXPECT_EQ(server_->NextDeadline(), kNever);  // idle: nothing to wake up for
}

TEST_F(InverterProtocolServerTest, WriteThenReadFa07) {
  Start();
  EXPECT_EQ(Exchange({0x2F, 0x57, 0xFA, 0x07, 0x17, 0x70, 0x0E}), (Bytes{0x2F, 0x57, 0xFA, 0x07, 0x17, 0x70, 0x0E}));
  EXPECT_EQ(Exchange({0x2F, 0x52, 0xFA, 0x07, 0x82}), (Bytes{0x2F, 0x52, 0xFA, 0x07, 0x17, 0x70, 0x09}));
  EXPECT_EQ(*model_.Read(reg::kFa07), 0x1770);
}

TEST_F(InverterProtocolServerTest, WWritesEepromAndPDoesNot) {
  Start();
  // The manual's W example: dec := 10 s (seed 003 §3.8).
  EXPECT_EQ(Exchange({0x2F, 0x57, 0x00, 0x10, 0x00, 0x64, 0xFA}), (Bytes{0x2F, 0x57, 0x00, 0x10, 0x00, 0x64, 0xFA}));
  EXPECT_EQ(model_.EepromWriteCount(reg::kDec), 1U);
  EXPECT_EQ(model_.EepromValue(reg::kDec), 100);
  // P dec := 20 s: RAM only.
  EXPECT_EQ(Exchange({0x2F, 0x50, 0x00, 0x10, 0x00, 0xC8, 0x57}), (Bytes{0x2F, 0x50, 0x00, 0x10, 0x00, 0xC8, 0x57}));
  EXPECT_EQ(model_.EepromWriteCount(reg::kDec), 1U);
  EXPECT_EQ(model_.EepromValue(reg::kDec), 100);
  EXPECT_EQ(*model_.Read(reg::kDec), 200);
}

TEST_F(InverterProtocolServerTest, AsciiRequestGetsAsciiReply) {
  Start();
  // The manual's sample program 2 (seed 003 §3.12): fh reads 80 Hz, is set to 60 Hz and reads back.
  EXPECT_EQ(Exchange(Ascii("(R0011&62)")), Ascii("(R00111F40&3D)"));
  EXPECT_EQ(Exchange(Ascii("(W00111770&36)")), Ascii("(W00111770&36)"));
  EXPECT_EQ(Exchange(Ascii("(R0011&62)")), Ascii("(R00111770&31)"));
  // Session of program 3: with an inverter number, without, and short data padded in the reply.
  EXPECT_EQ(Exchange(Ascii("(00R0011)")), Ascii("(00R00111770)"));
  EXPECT_EQ(Exchange(Ascii("(R0011)")), Ascii("(R00111770)"));
  EXPECT_EQ(Exchange(Ascii("()")), Bytes{});
  EXPECT_EQ(Exchange(Ascii("(W08030)")), Ascii("(W08030000)"));
}

// --- Error replies: the model's refusals mapped to the manual's codes ---

TEST_F(InverterProtocolServerTest, ErrorRepliesMatchTheManual) {
  Start();
  // 0001 does not exist: communication number error, exactly seed 003 §3.7's frame.
  EXPECT_EQ(Exchange({0x2F, 0x52, 0x00, 0x01, 0x82}), (Bytes{0x2F, 0x4E, 0x00, 0x02, 0x7F}));
  EXPECT_EQ(Exchange(Ascii("(R0001&61)")), Ascii("(N0002&5E)"));
  // FA01 = FFFFh is above fh: data error.
  EXPECT_EQ(Exchange({0x2F, 0x57, 0xFA, 0x01, 0xFF, 0xFF, 0x7F}), (Bytes{0x2F, 0x4E, 0x00, 0x01, 0x7E}));
  EXPECT_EQ(Exchange(Ascii("(PFA01FFFF&9E)")), Ascii("(N0001&5D)"));
  // A monitor (FD00) is read-only: impossible to execute.
  EXPECT_EQ(Exchange({0x2F, 0x57, 0xFD, 0x00, 0x00, 0x00, 0x83}), (Bytes{0x2F, 0x4E, 0x00, 0x00, 0x7D}));
  // Checksum error (the manual's R example with its sum off by one), and an ASCII command error.
  EXPECT_EQ(Exchange({0x2F, 0x52, 0xFD, 0x01, 0x7E}), (Bytes{0x2F, 0x4E, 0x00, 0x04, 0x81}));
  EXPECT_EQ(Exchange(Ascii("(L0000&5A)")), Ascii("(N0003&5F)"));
  // Binary command errors and format errors stay silent.
  EXPECT_EQ(Exchange({0x2F, 0x4C, 0x00, 0x00, 0x7B}), Bytes{});
  EXPECT_EQ(Exchange(Ascii("(R0000}")), Bytes{});
  EXPECT_EQ(server_->counters().errors, 7U);
}

TEST_F(InverterProtocolServerTest, WriteDuringRunIsImpossibleToExecute) {
  Start();
  ASSERT_TRUE(model_.Write(reg::kFa00, 0xC400, WriteTarget::kRamOnly).ok());  // run forward, priorities
  ASSERT_TRUE(model_.Write(reg::kFa01, 0x1770, WriteTarget::kRamOnly).ok());
  clock_.Advance(100 * kMilli);
  Poll();
  ASSERT_TRUE(model_.running());
  // W fh := 60 Hz while running (seed 003 §3.9 (1)).
  EXPECT_EQ(Exchange({0x2F, 0x57, 0x00, 0x11, 0x17, 0x70, 0x1E}), (Bytes{0x2F, 0x4E, 0x00, 0x00, 0x7D}));
}

// --- Addressing ---

TEST_F(InverterProtocolServerTest, InverterNumberFromF802OrConfig) {
  Start();
  // F802 = 0: the manual's binary broadcast example, answered by 00 with its own number.
  EXPECT_EQ(Exchange({0x2F, 0xFF, 0x50, 0xFA, 0x01, 0x17, 0x70, 0x00}),
            (Bytes{0x2F, 0x00, 0x50, 0xFA, 0x01, 0x17, 0x70, 0x01}));
  ASSERT_TRUE(model_.Write(0x0802, 3, WriteTarget::kRamOnly).ok());
  EXPECT_EQ(server_->inverter_number(), 3);
  EXPECT_EQ(Exchange(Ascii("(00R0011)")), Bytes{});  // another inverter's frame
  EXPECT_EQ(Exchange(Ascii("(03R0011)")), Ascii("(03R00111F40)"));
  // A broadcast write is executed by member 03 but answered only by 00.
  EXPECT_EQ(Exchange(Ascii("(**PFA010BB8)")), Bytes{});
  EXPECT_EQ(*model_.Read(reg::kFa01), 0x0BB8);
  EXPECT_EQ(server_->counters().ignored, 1U);
}

TEST_F(InverterProtocolServerTest, ConfiguredNumberAndBroadcastReads) {
  ServerConfig config;
  config.inverter_number = 0;
  config.broadcast_reads = false;
  Start(config);
  EXPECT_EQ(Exchange(Ascii("(**R0011)")), Bytes{});  // refused broadcast read
  EXPECT_EQ(Exchange(Ascii("(**PFA010BB8)")), Ascii("(00PFA010BB8)"));
  EXPECT_EQ(server_->counters().ignored, 1U);
}

// --- Trips, fault reset and the reset silence ---

TEST_F(InverterProtocolServerTest, LowercaseRepliesWhileTripped) {
  Start();
  model_.Trip(trip_code::kRs485Timeout);
  // Seed 003 §3.11: status and trip code while tripped by err5.
  EXPECT_EQ(Exchange({0x2F, 0x52, 0xFD, 0x01, 0x7F}), (Bytes{0x2F, 0x72, 0xFD, 0x01, 0x00, 0x03, 0xA2}));
  EXPECT_EQ(Exchange({0x2F, 0x52, 0xFC, 0x90, 0x0D}), (Bytes{0x2F, 0x72, 0xFC, 0x90, 0x00, 0x18, 0x45}));
  EXPECT_EQ(Exchange(Ascii("(RFD01)")), Ascii("(rFD010003)"));
  // Error replies too: 'n'.
  EXPECT_EQ(Exchange({0x2F, 0x52, 0x00, 0x01, 0x82}), (Bytes{0x2F, 0x6E, 0x00, 0x02, 0x9F}));
}

TEST_F(InverterProtocolServerTest, NoReplyToFaultResetNorDuringTheResetSilence) {
  Start();
  model_.Trip(trip_code::kRs485Timeout);
  // P FA00 = 2000h: the fault-reset edge, never answered.
  EXPECT_EQ(Exchange({0x2F, 0x50, 0xFA, 0x00, 0x20, 0x00, 0x99}), Bytes{});
  EXPECT_FALSE(model_.tripped());
  EXPECT_EQ(server_->counters().no_reply, 1U);
  ASSERT_TRUE(model_.in_reset(clock_.NowMicros()));
  // Still initialising: the drive does not communicate, not even a checksum error.
  EXPECT_EQ(Exchange({0x2F, 0x52, 0xFD, 0x01, 0x7F}), Bytes{});
  EXPECT_EQ(Exchange({0x2F, 0x52, 0xFD, 0x01, 0x7E}), Bytes{});
  EXPECT_EQ(server_->counters().in_reset, 2U);
  clock_.Set(model_.ResetInProgressUntil());
  EXPECT_EQ(Exchange({0x2F, 0x52, 0xFD, 0x01, 0x7F}), (Bytes{0x2F, 0x52, 0xFD, 0x01, 0x48, 0x00, 0xC7}));
}

// --- Block communication ---

TEST_F(InverterProtocolServerTest, BlockCommunication) {
  Start();
  // F870/F871/F875-F879 unset: both writes fail, reads are dummies (seed 003 §4, first reply).
  const Bytes run_request = {0x2F, 0x58, 0x02, 0x05, 0xC4, 0x00, 0x17, 0x70, 0xD9};
  EXPECT_EQ(Exchange(run_request),
            (Bytes{0x2F, 0x59, 0x05, 0x03, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0x90}));
  // The example's selections, in force after a power cycle.
  const std::uint16_t selections[][2] = {{0x0870, 1}, {0x0871, 3}, {0x0875, 1}, {0x0876, 2},
                                         {0x0877, 3}, {0x0878, 4}, {0x0879, 5}};
  for (const auto& s : selections) ASSERT_TRUE(model_.Write(s[0], s[1], WriteTarget::kRamAndEeprom).ok());
  model_.PowerCycle();
  Poll();
  clock_.Set(model_.ResetInProgressUntil());
  // FA00 = 8000h (priority, stopped), FA01 = 60 Hz: status 4000h standby (the example's second reply).
  EXPECT_EQ(Exchange({0x2F, 0x58, 0x02, 0x05, 0x80, 0x00, 0x17, 0x70, 0x95}),
            (Bytes{0x2F, 0x59, 0x05, 0x00, 0x40, 0x00, 0, 0, 0, 0, 0, 0, 0, 0, 0xCD}));
  EXPECT_EQ(*model_.Read(reg::kFa00), 0x8000);
  EXPECT_EQ(*model_.Read(reg::kFa01), 0x1770);
  EXPECT_EQ(model_.EepromWriteCount(reg::kFa01), 0U);
  // Run: after the ramp the reply carries 6400h and 60 Hz.
  ASSERT_FALSE(Exchange(run_request).empty());
  clock_.Advance(20 * kSecond);
  Poll();
  const Bytes running = Exchange({0x2F, 0x58, 0x00, 0x02, 0x89});
  const wire::DecodedReply decoded = wire::DecodeReply(running);
  ASSERT_TRUE(decoded.ok()) << wire::FrameFaultName(decoded.fault);
  ASSERT_EQ(decoded.kind, wire::ReplyKind::kBlock);
  EXPECT_EQ(decoded.block.read_count, 2);
  EXPECT_EQ(decoded.block.write_status, 0);
  EXPECT_EQ(decoded.block.read_data[0], 0x6400);
  EXPECT_EQ(decoded.block.read_data[1], 0x1770);
  // Checksum error: the example's bad frame (seed 003 §4).
  EXPECT_EQ(Exchange({0x2F, 0x58, 0x02, 0x05, 0xC4, 0x00, 0x17, 0x70, 0xD8}), (Bytes{0x2F, 0x4E, 0x00, 0x04, 0x81}));
  // nR above 5: zero read groups; tripped: 'y'.
  model_.Trip(trip_code::kEmergencyStop);
  EXPECT_EQ(Exchange({0x2F, 0x58, 0x00, 0x06, 0x8D}), (Bytes{0x2F, 0x79, 0x00, 0x00, 0xA8}));
}

// --- Timing ---

TEST_F(InverterProtocolServerTest, ReplyWaitsForProcessingAndTransmissionTime) {
  Start();
  const hal::Micros t0 = clock_.NowMicros();
  Send({0x2F, 0x52, 0xFD, 0x01, 0x7F});
  Poll();
  // 2 ms processing + 7 bytes x 11 bits at 19200 baud = 4010.4 us, rounded up.
  const hal::Micros due = t0 + 2 * kMilli + 4011;
  EXPECT_EQ(server_->TransmissionTime(7), 4011U);
  EXPECT_EQ(server_->NextDeadline(), due);
  clock_.Set(due - 1);
  Poll();
  EXPECT_EQ(Received(), Bytes{});
  clock_.Set(due);
  Poll();
  EXPECT_EQ(Received(), (Bytes{0x2F, 0x52, 0xFD, 0x01, 0x48, 0x00, 0xC7}));
  EXPECT_EQ(server_->NextDeadline(), kNever);
}

TEST_F(InverterProtocolServerTest, Rs485ProfileAndF805WaitingTime) {
  const ServerConfig profile = Rs485Profile();
  EXPECT_EQ(profile.baud, 19200U);
  EXPECT_EQ(profile.bits_per_character, 11);
  EXPECT_EQ(profile.processing_delay, 20 * kMilli);
  Start(profile);
  hal::Micros t0 = clock_.NowMicros();
  Send({0x2F, 0x52, 0xFD, 0x01, 0x7F});
  Poll();
  EXPECT_EQ(server_->NextDeadline(), t0 + 20 * kMilli + 4011);
  Settle();
  // F805 = 0.50 s: the reply waits at least that long after the request.
  ASSERT_TRUE(model_.Write(0x0805, 50, WriteTarget::kRamOnly).ok());
  t0 = clock_.NowMicros();
  Send({0x2F, 0x52, 0xFD, 0x01, 0x7F});
  Poll();
  EXPECT_EQ(server_->NextDeadline(), t0 + 500 * kMilli + 4011);
}

TEST_F(InverterProtocolServerTest, BackToBackRequestsAreAnsweredInTurn) {
  Start();
  const hal::Micros t0 = clock_.NowMicros();
  Send({0x2F, 0x52, 0xFD, 0x01, 0x7F, 0x2F, 0x52, 0xFA, 0x07, 0x82});
  Poll();
  EXPECT_EQ(server_->pending_replies(), 2U);
  EXPECT_EQ(server_->NextDeadline(), t0 + 2 * kMilli + 4011);
  clock_.Set(t0 + 2 * kMilli + 4011);
  Poll();
  EXPECT_EQ(Received().size(), 7U);
  // The second reply follows the first on the half-duplex line.
  EXPECT_EQ(server_->NextDeadline(), t0 + 2 * kMilli + 2 * 4011);
  EXPECT_EQ(Settle(), (Bytes{0x2F, 0x52, 0xFA, 0x07, 0x00, 0x00, 0x82}));
}

TEST_F(InverterProtocolServerTest, PartialFrameDroppedAfterTheFrameTimeout) {
  Start();
  const hal::Micros t0 = clock_.NowMicros();
  Send({0x2F, 0x52, 0xFD});
  Poll();
  EXPECT_EQ(server_->NextDeadline(), t0 + 500 * kMilli);
  clock_.Set(t0 + 500 * kMilli);
  Poll();
  EXPECT_EQ(server_->counters().timeouts, 1U);
  EXPECT_EQ(server_->NextDeadline(), kNever);
  EXPECT_EQ(Exchange({0x01, 0x7F}), Bytes{});  // the rest arrives too late: garbage
  EXPECT_EQ(Exchange({0x2F, 0x52, 0xFD, 0x01, 0x7F}).size(), 7U);
}

// --- Fault injection ---

TEST_F(InverterProtocolServerTest, InjectedDropExecutesButDoesNotAnswer) {
  Start();
  server_->Inject({.kind = Fault::Kind::kDrop, .count = 1});
  EXPECT_EQ(Exchange({0x2F, 0x57, 0xFA, 0x07, 0x17, 0x70, 0x0E}), Bytes{});
  EXPECT_EQ(*model_.Read(reg::kFa07), 0x1770);
  EXPECT_EQ(server_->counters().dropped, 1U);
  EXPECT_EQ(server_->active_faults(), 0U);
  EXPECT_EQ(Exchange({0x2F, 0x52, 0xFA, 0x07, 0x82}), (Bytes{0x2F, 0x52, 0xFA, 0x07, 0x17, 0x70, 0x09}));
}

TEST_F(InverterProtocolServerTest, InjectedSilenceNeitherExecutesNorAnswers) {
  Start();
  server_->Inject({.kind = Fault::Kind::kSilent, .count = Fault::kUntilCleared});
  EXPECT_EQ(Exchange({0x2F, 0x57, 0xFA, 0x07, 0x17, 0x70, 0x0E}), Bytes{});
  EXPECT_EQ(Exchange({0x2F, 0x52, 0xFA, 0x07, 0x82}), Bytes{});
  EXPECT_EQ(*model_.Read(reg::kFa07), 0);
  EXPECT_EQ(server_->counters().dropped, 2U);
  server_->ClearFaults();
  EXPECT_EQ(Exchange({0x2F, 0x52, 0xFA, 0x07, 0x82}), (Bytes{0x2F, 0x52, 0xFA, 0x07, 0x00, 0x00, 0x82}));
}

TEST_F(InverterProtocolServerTest, InjectedDelayPostponesTheReply) {
  Start();
  server_->Inject({.kind = Fault::Kind::kDelay, .count = 1, .delay_us = 300 * kMilli});
  const hal::Micros t0 = clock_.NowMicros();
  Send({0x2F, 0x52, 0xFD, 0x01, 0x7F});
  Poll();
  const hal::Micros due = t0 + 2 * kMilli + 4011 + 300 * kMilli;
  EXPECT_EQ(server_->NextDeadline(), due);
  clock_.Set(due - 1);
  Poll();
  EXPECT_EQ(Received(), Bytes{});
  clock_.Set(due);
  Poll();
  EXPECT_EQ(Received(), (Bytes{0x2F, 0x52, 0xFD, 0x01, 0x48, 0x00, 0xC7}));
  EXPECT_EQ(server_->counters().delayed, 1U);
  // Only one: the next reply is on time again.
  const hal::Micros t1 = clock_.NowMicros();
  Send({0x2F, 0x52, 0xFD, 0x01, 0x7F});
  Poll();
  EXPECT_EQ(server_->NextDeadline(), t1 + 2 * kMilli + 4011);
}

TEST_F(InverterProtocolServerTest, InjectedCorruptionFailsTheChecksum) {
  Start();
  server_->Inject({.kind = Fault::Kind::kCorrupt, .count = 2});
  const Bytes binary = Exchange({0x2F, 0x52, 0xFD, 0x01, 0x7F});
  EXPECT_EQ(binary, (Bytes{0x2F, 0x52, 0xFD, 0x01, 0x48, 0x00, 0xC6}));
  EXPECT_EQ(wire::DecodeReply(binary).fault, wire::FrameFault::kBadChecksum);
  const Bytes ascii = Exchange(Ascii("(R0011&62)"));
  EXPECT_EQ(ascii, Ascii("(R00111F40&0D)"));
  EXPECT_EQ(wire::DecodeReply(ascii).fault, wire::FrameFault::kBadChecksum);
  EXPECT_EQ(server_->counters().corrupted, 2U);
  EXPECT_EQ(Exchange({0x2F, 0x52, 0xFD, 0x01, 0x7F}), (Bytes{0x2F, 0x52, 0xFD, 0x01, 0x48, 0x00, 0xC7}));
}

// --- Event-loop glue ---

TEST_F(InverterProtocolServerTest, PollSourceLowersTheDeadlineAndPolls) {
  Start();
  ProtocolServerPollSource source(*server_);
  PollSet set;
  Micros deadline = kNever;
  source.PrepareWait(set, deadline);
  EXPECT_EQ(deadline, kNever);
  EXPECT_EQ(set.size(), 0U);
  Send({0x2F, 0x52, 0xFD, 0x01, 0x7F});
  source.AfterWait(set);  // polls at the server's clock
  source.PrepareWait(set, deadline);
  EXPECT_EQ(deadline, clock_.NowMicros() + 2 * kMilli + 4011);
}

}  // namespace
}  // namespace sim
