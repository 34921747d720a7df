// Connection traffic on a fake clock: class 1 consumption (sequence counts, run/idle, wrap), T->O
// production on absolute deadlines (no drift, no early packet, late slots skipped), watchdog timeouts
// and their consequences, multicast production, class 3 requests with repeated sequence counts, and
// sessions.
#include <gtest/gtest.h>

#include <cstdint>

#include "cip/connection_manager.h"
#include "cip_connection_fakes.h"

namespace cip {
namespace {

using test::Bytes;
using test::ConnectionCard;
using test::Hex;
using test::IoDatagramBytes;
using test::OpenParams;

constexpr std::uint32_t kOtoT = 0x11223344;  // the first connection ID the card draws
constexpr hal::Micros kRpi = 10000;
constexpr hal::Micros kTimeout = kRpi * 4 * 2;  // multiplier 1

class CipIoConnectionTest : public ::testing::Test {
 protected:
  void Feed(std::uint32_t encapsulation_sequence, std::uint16_t sequence, bool run, const Bytes& data,
            std::uint32_t id = kOtoT, base::Ipv4Address from = test::kOriginator) {
    card_.cm.OnIoDatagram(IoDatagramBytes(id, encapsulation_sequence, sequence, run, data), Ipv4Endpoint{from, 2222},
                          card_.now);
  }

  ConnectionCard card_;
  const Bytes kOutput = Hex("01 02 03 04 05 06 07 08");
};

TEST_F(CipIoConnectionTest, ConsumesNewDataWithRunIdle) {
  ASSERT_EQ(card_.Open()[2], 0x00);
  Feed(1, 1, false, kOutput);
  ASSERT_EQ(card_.io.consumed.size(), 1U);
  EXPECT_EQ(card_.io.consumed[0].point, 100U);
  EXPECT_EQ(card_.io.consumed[0].data, kOutput);
  EXPECT_FALSE(card_.io.consumed[0].run);
  EXPECT_TRUE(card_.events.run_idle.empty());  // idle is where a connection starts
  EXPECT_EQ(card_.cm.IoStatus(), ExtendedDeviceStatus::kIoConnectionsIdle);

  Feed(2, 2, true, kOutput);
  ASSERT_EQ(card_.events.run_idle.size(), 1U);
  EXPECT_EQ(card_.events.run_idle[0], std::make_pair(kOtoT, true));
  EXPECT_TRUE(card_.io.consumed.back().run);
  EXPECT_EQ(card_.cm.IoStatus(), ExtendedDeviceStatus::kIoConnectionInRunMode);

  // The same CIP sequence count is no new data: neither the data nor the header are taken.
  Feed(3, 2, false, Hex("FF FF FF FF FF FF FF FF"));
  EXPECT_EQ(card_.io.consumed.size(), 2U);
  EXPECT_EQ(card_.cm.IoStatus(), ExtendedDeviceStatus::kIoConnectionInRunMode);

  Feed(4, 3, false, kOutput);
  EXPECT_EQ(card_.events.run_idle.back(), std::make_pair(kOtoT, false));
  EXPECT_FALSE(card_.io.consumed.back().run);
  EXPECT_EQ(card_.cm.IoStatus(), ExtendedDeviceStatus::kIoConnectionsIdle);
}

TEST_F(CipIoConnectionTest, SequenceCountsWrap) {
  ASSERT_EQ(card_.Open()[2], 0x00);
  Feed(0xFFFFFFFE, 0xFFFE, true, kOutput);
  Feed(0xFFFFFFFF, 0xFFFF, true, kOutput);
  Feed(0x00000000, 0x0000, true, kOutput);
  Feed(0x00000001, 0x0001, true, kOutput);
  EXPECT_EQ(card_.io.consumed.size(), 4U);
  Feed(0x00000002, 0xFFFF, true, kOutput);  // older than 0x0001
  Feed(0x00000003, 0x0001, true, kOutput);  // repeated
  EXPECT_EQ(card_.io.consumed.size(), 4U);
  Feed(0x00000004, 0x0002, true, kOutput);
  EXPECT_EQ(card_.io.consumed.size(), 5U);
  EXPECT_EQ(card_.cm.dropped_datagrams(), 0U);
}

TEST_F(CipIoConnectionTest, DropsStrangersStalePacketsAndWrongSizes) {
  ASSERT_EQ(card_.Open()[2], 0x00);
  Feed(5, 1, true, kOutput, kOtoT + 1);          // unknown connection
  Feed(5, 1, true, kOutput, kOtoT, base::Ipv4Address(0x0A000299));  // another host
  Feed(5, 1, true, Hex("01 02 03"));             // wrong size
  card_.cm.OnIoDatagram(Hex("02 00 02 80 08 00 44 33"), Ipv4Endpoint{test::kOriginator, 2222}, card_.now);  // cut
  EXPECT_TRUE(card_.io.consumed.empty());
  EXPECT_EQ(card_.cm.dropped_datagrams(), 4U);
  Feed(5, 1, true, kOutput);
  Feed(5, 2, true, kOutput);  // the encapsulation sequence number did not advance: a duplicate
  Feed(4, 3, true, kOutput);  // older
  EXPECT_EQ(card_.io.consumed.size(), 1U);
  EXPECT_EQ(card_.cm.dropped_datagrams(), 6U);
}

TEST_F(CipIoConnectionTest, TimesOutExactlyAtRpiTimesFourTimesTwoToTheMultiplier) {
  ASSERT_EQ(card_.Open()[2], 0x00);
  const hal::Micros opened = card_.now;
  // Until the first packet the watchdog allows 10 s.
  EXPECT_EQ(card_.cm.NextDeadline(), opened);  // (the first production is due at once)
  card_.now = opened + 9999999;
  card_.cm.CheckTimeouts(card_.now);
  EXPECT_EQ(card_.cm.ActiveConnections(), 1);
  Feed(1, 1, true, kOutput);
  const hal::Micros fed = card_.now;
  card_.now = fed + kTimeout - 1;
  card_.cm.CheckTimeouts(card_.now);
  EXPECT_EQ(card_.cm.ActiveConnections(), 1);
  EXPECT_TRUE(card_.events.timeouts.empty());
  card_.now = fed + kTimeout;
  card_.cm.CheckTimeouts(card_.now);
  EXPECT_EQ(card_.cm.ActiveConnections(), 0);
  ASSERT_EQ(card_.events.timeouts.size(), 1U);
  EXPECT_EQ(card_.events.timeouts[0].transport_class, 1);
  EXPECT_EQ(card_.events.timeouts[0].kind, IoConnectionKind::kExclusiveOwner);
  EXPECT_EQ(card_.events.timeouts[0].points, (IoPoints{1U, 100, 150}));
  EXPECT_EQ(card_.events.timeouts[0].originator_address, test::kOriginator);
  EXPECT_EQ(card_.cm.counters().connection_timeouts, 1);
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 06 24 01 30 08")), Hex("8E 00 00 00 01 00"));
  EXPECT_FALSE(card_.cm.IsOwned(100));
  // Faulted until a class 1 connection opens again.
  EXPECT_EQ(card_.cm.IoStatus(), ExtendedDeviceStatus::kFaultedIoConnection);
  ASSERT_EQ(card_.Open()[2], 0x00);
  EXPECT_EQ(card_.cm.IoStatus(), ExtendedDeviceStatus::kIoConnectionsIdle);
}

TEST_F(CipIoConnectionTest, TimeoutMultiplierSeven) {
  OpenParams params;
  params.multiplier = 7;
  params.o_to_t_rpi = 100000;
  ASSERT_EQ(card_.Open(params)[2], 0x00);
  Feed(1, 1, true, kOutput);
  const hal::Micros fed = card_.now;
  card_.cm.CheckTimeouts(fed + 100000 * 4 * 128 - 1);
  EXPECT_EQ(card_.cm.ActiveConnections(), 1);
  card_.cm.CheckTimeouts(fed + 100000 * 4 * 128);
  EXPECT_EQ(card_.cm.ActiveConnections(), 0);
}

TEST_F(CipIoConnectionTest, TimeoutOfTheOwnerClosesItsListeners) {
  ASSERT_EQ(card_.Open()[2], 0x00);
  OpenParams listen;
  listen.triad.connection_serial = 2;
  listen.o_to_t.size = 2;
  listen.path = Hex("20 04 24 01 2C C7 2C 96");
  ASSERT_EQ(card_.Open(listen)[2], 0x00);
  const std::uint32_t listener = 0x12233445;
  card_.now += 1000;
  Feed(1, 1, true, kOutput);
  card_.cm.OnIoDatagram(IoDatagramBytes(listener, 1, 1, false, {}, false), Ipv4Endpoint{test::kOriginator, 2222},
                        card_.now);
  // The listener keeps sending heartbeats; the owner stops.
  for (int i = 1; i <= 8; ++i) {
    card_.now += kRpi;
    card_.cm.OnIoDatagram(IoDatagramBytes(listener, 1 + i, static_cast<std::uint16_t>(1 + i), false, {}, false),
                          Ipv4Endpoint{test::kOriginator, 2222}, card_.now);
    card_.cm.CheckTimeouts(card_.now);
  }
  EXPECT_EQ(card_.cm.ActiveConnections(), 0);
  ASSERT_EQ(card_.events.timeouts.size(), 1U);  // only the owner timed out; the listener was closed
  EXPECT_EQ(card_.events.timeouts[0].o_to_t_connection_id, kOtoT);
}

TEST_F(CipIoConnectionTest, ProducesAtOpenThenEveryApiWithoutDrift) {
  ASSERT_EQ(card_.Open()[2], 0x00);
  const hal::Micros opened = card_.now;
  EXPECT_EQ(card_.Take(), Hex("02 00 | 02 80 08 00 01 00 00 20 01 00 00 00 | B1 00 08 00 01 00 96 97 98 99 9A 9B"));
  EXPECT_EQ(card_.last_to, (Ipv4Endpoint{test::kOriginator, 2222}));
  EXPECT_TRUE(card_.Take().empty());  // nothing more at the same time
  EXPECT_EQ(card_.cm.NextDeadline(), opened + kRpi);
  card_.now = opened + kRpi - 1;
  EXPECT_TRUE(card_.Take().empty());  // never early

  // 10,000 periods, each served up to 3 ms late: the slots stay on the grid opened + k × API.
  std::uint32_t encapsulation_sequence = 0;
  for (std::uint32_t k = 1; k <= 10000; ++k) {
    const hal::Micros slot = opened + k * kRpi;
    ASSERT_EQ(card_.cm.NextDeadline(), slot) << k;
    card_.now = slot + (k * 7919) % 3000;
    Feed(++encapsulation_sequence, static_cast<std::uint16_t>(k), true, kOutput);
    const Bytes datagram = card_.Take();
    ASSERT_EQ(datagram.size(), 26U);
    // Sequence numbers: 32-bit at bytes 10-13, 16-bit at 18-19.
    EXPECT_EQ(datagram[10] | datagram[11] << 8 | datagram[12] << 16, static_cast<int>(k + 1));
    EXPECT_EQ(datagram[18] | datagram[19] << 8, static_cast<int>((k + 1) & 0xFFFF));
    ASSERT_TRUE(card_.Take().empty());
  }
  EXPECT_EQ(card_.cm.missed_productions(), 0U);
  EXPECT_EQ(card_.io.productions, 10001);
}

TEST_F(CipIoConnectionTest, LateProductionSkipsToTheNextSlotWithoutBurst) {
  ASSERT_EQ(card_.Open()[2], 0x00);
  const hal::Micros opened = card_.now;
  ASSERT_FALSE(card_.Take().empty());
  card_.now = opened + kRpi + 2 * kRpi + kRpi / 2;  // 2.5 periods late
  Feed(1, 1, true, kOutput);
  EXPECT_FALSE(card_.Take().empty());
  EXPECT_TRUE(card_.Take().empty());  // no catching up
  EXPECT_EQ(card_.cm.missed_productions(), 2U);
  EXPECT_EQ(card_.cm.NextDeadline(), opened + 4 * kRpi);
}

TEST_F(CipIoConnectionTest, ProducesToTheRequestedPortAndToMulticast) {
  // A T->O socket address item in the Forward_Open names the originator's port.
  Bytes reply(128);
  RequestContext context;
  context.now = card_.now;
  context.peer = Ipv4Endpoint{test::kOriginator, 50000};
  context.request_t_to_o = SocketAddress{SocketAddress::kAfInet, 2300, 0};
  reply.resize(card_.card.cip.router().HandleUnconnected(test::ForwardOpenRequestBytes(OpenParams{}), context, reply));
  ASSERT_EQ(reply[2], 0x00);
  ASSERT_FALSE(card_.Take().empty());
  EXPECT_EQ(card_.last_to, (Ipv4Endpoint{test::kOriginator, 2300}));

  // Multicast: one datagram per API for all the connections sharing it.
  OpenParams input = test::InputOnly151(2);
  input.t_to_o.type = ConnectionType::kMulticast;
  ASSERT_EQ(card_.Open(input)[2], 0x00);
  input.triad.connection_serial = 3;
  input.path = Hex("20 04 24 01 2C C7 2C 97");
  ASSERT_EQ(card_.Open(input)[2], 0x00);
  EXPECT_EQ(card_.Take(), Hex("02 00 | 02 80 08 00 46 35 24 13 01 00 00 00 | B1 00 06 00 01 00 97 98 99 9A"));
  EXPECT_EQ(card_.last_to, (Ipv4Endpoint{base::Ipv4Address(0xEFC00120), 2222}));
  EXPECT_TRUE(card_.Take().empty());
}

TEST_F(CipIoConnectionTest, ProductionsCarryTheTtoOPriorityOfTheirForwardOpen) {
  OpenParams params;
  params.t_to_o.priority = ConnectionPriority::kUrgent;
  params.o_to_t.priority = ConnectionPriority::kLow;  // the O->T direction is the originator's
  ASSERT_EQ(card_.Open(params)[2], 0x00);
  ASSERT_FALSE(card_.Take().empty());
  EXPECT_EQ(card_.last_priority, ConnectionPriority::kUrgent);

  OpenParams high = test::InputOnly151(2);
  high.t_to_o.priority = ConnectionPriority::kHigh;
  ASSERT_EQ(card_.Open(high)[2], 0x00);
  ASSERT_FALSE(card_.Take().empty());
  EXPECT_EQ(card_.last_priority, ConnectionPriority::kHigh);
}

TEST_F(CipIoConnectionTest, HeartbeatConnectionsFeedTheirWatchdogWithoutData) {
  OpenParams input;
  input.o_to_t.size = 2;
  input.path = Hex("20 04 24 01 2C C6 2C 96");
  ASSERT_EQ(card_.Open(input)[2], 0x00);
  card_.cm.OnIoDatagram(IoDatagramBytes(kOtoT, 1, 1, false, {}, false), Ipv4Endpoint{test::kOriginator, 2222},
                        card_.now);
  EXPECT_TRUE(card_.io.consumed.empty());
  card_.cm.CheckTimeouts(card_.now + kTimeout - 1);
  EXPECT_EQ(card_.cm.ActiveConnections(), 1);
  EXPECT_EQ(card_.cm.dropped_datagrams(), 0U);
  // An input-only connection has no run/idle: idle for the Identity status.
  EXPECT_EQ(card_.cm.IoStatus(), ExtendedDeviceStatus::kIoConnectionsIdle);
}

// ---- Class 3 ---------------------------------------------------------------------------------------

class CipExplicitConnectionTest : public ::testing::Test {
 protected:
  CipExplicitConnectionTest() { EXPECT_EQ(card_.Open(test::ExplicitParams())[2], 0x00); }

  Bytes Send(std::uint16_t sequence, const Bytes& request, std::uint32_t id = kOtoT,
             std::uint32_t session = test::kSession) {
    RequestContext context;
    context.now = card_.now;
    context.session_handle = session;
    context.peer = Ipv4Endpoint{test::kOriginator, 50000};
    Bytes reply(600);
    reply_id_ = 0;
    reply.resize(card_.cm.HandleConnected(id, sequence, request, context, reply, reply_id_));
    return reply;
  }

  ConnectionCard card_;
  std::uint32_t reply_id_ = 0;
};

TEST_F(CipExplicitConnectionTest, AnswersThroughTheMessageRouter) {
  EXPECT_EQ(Send(1, Hex("0E 03 20 01 24 01 30 01")), Hex("01 00 8E 00 00 00 79 01"));
  EXPECT_EQ(reply_id_, 0x20000001U);
  EXPECT_EQ(Send(2, Hex("0E 03 20 01 24 01 30 02")), Hex("02 00 8E 00 00 00 02 00"));
}

TEST_F(CipExplicitConnectionTest, RepeatedSequenceCountGetsThePreviousReplyWithoutExecuting) {
  // A Forward_Open over the class 3 connection: executed once, answered twice.
  OpenParams io;
  io.triad.connection_serial = 0x2000;
  const Bytes open = test::ForwardOpenRequestBytes(io);
  const Bytes first = Send(7, open);
  ASSERT_EQ(first.size(), 32U);
  EXPECT_EQ(first[4], 0x00);
  EXPECT_EQ(card_.cm.ActiveConnections(), 2);
  EXPECT_EQ(Send(7, open), first);
  EXPECT_EQ(Send(7, Hex("0E 03 20 01 24 01 30 01")), first);
  EXPECT_EQ(card_.cm.ActiveConnections(), 2);
  EXPECT_EQ(card_.cm.counters().open_requests, 2);  // the class 3 open and this one
  // The next sequence count executes again: now it is a duplicate.
  EXPECT_EQ(Send(8, open)[4], 0x01);
}

TEST_F(CipExplicitConnectionTest, IgnoresOtherSessionsAndUnknownIds) {
  EXPECT_TRUE(Send(1, Hex("0E 03 20 01 24 01 30 01"), kOtoT + 1).empty());
  EXPECT_TRUE(Send(1, Hex("0E 03 20 01 24 01 30 01"), kOtoT, test::kSession + 1).empty());
}

TEST_F(CipExplicitConnectionTest, RepliesAreBoundedByTheTtoOSize) {
  ConnectionCard card;
  OpenParams small = test::ExplicitParams();
  small.t_to_o.size = 8;
  ASSERT_EQ(card.Open(small)[2], 0x00);
  RequestContext context;
  context.session_handle = test::kSession;
  Bytes reply(600);
  std::uint32_t id = 0;
  // Identity attribute 7 (the product name) does not fit 8 - 2 bytes: 0x11.
  reply.resize(card.cm.HandleConnected(kOtoT, 1, Hex("0E 03 20 01 24 01 30 07"), context, reply, id));
  EXPECT_EQ(reply, Hex("01 00 8E 00 11 00"));
}

TEST_F(CipExplicitConnectionTest, TimesOutAndClosesWithItsSession) {
  // 2 s × 4 × 2 = 16 s.
  Send(1, Hex("0E 03 20 01 24 01 30 01"));
  card_.cm.CheckTimeouts(card_.now + 16000000 - 1);
  EXPECT_EQ(card_.cm.ActiveConnections(), 1);
  card_.cm.CheckTimeouts(card_.now + 16000000);
  EXPECT_EQ(card_.cm.ActiveConnections(), 0);
  ASSERT_EQ(card_.events.timeouts.size(), 1U);
  EXPECT_EQ(card_.events.timeouts[0].transport_class, 3);
  EXPECT_EQ(card_.cm.IoStatus(), ExtendedDeviceStatus::kNoIoConnections);  // class 3 is not I/O
}

TEST_F(CipExplicitConnectionTest, SessionEndClosesClassThreeButNotIo) {
  OpenParams io;
  io.triad.connection_serial = 0x2000;
  ASSERT_EQ(card_.Open(io)[2], 0x00);
  EXPECT_TRUE(card_.cm.SessionHasConnections(test::kSession));
  EXPECT_FALSE(card_.cm.SessionHasConnections(test::kSession + 1));
  EXPECT_FALSE(card_.cm.SessionHasConnections(0));
  card_.cm.OnSessionClosed(test::kSession);
  EXPECT_EQ(card_.cm.ActiveConnections(), 1);
  EXPECT_TRUE(card_.cm.IsOwned(100));
  EXPECT_FALSE(card_.cm.SessionHasConnections(test::kSession));
  EXPECT_TRUE(Send(1, Hex("0E 03 20 01 24 01 30 01")).empty());
}

TEST_F(CipExplicitConnectionTest, ForwardCloseOverTheConnectionItself) {
  const Bytes close = test::ForwardCloseRequestBytes({0x1337, 0x3333, 0x12345678}, Hex("20 02 24 01"));
  EXPECT_EQ(Send(1, close), Hex("01 00 CE 00 00 00 37 13 33 33 78 56 34 12 00 00"));
  EXPECT_EQ(card_.cm.ActiveConnections(), 0);
  EXPECT_TRUE(Send(1, close).empty());  // gone: no reply, not even the cached one
}

}  // namespace
}  // namespace cip
