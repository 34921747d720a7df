// The card's encapsulation server: every command over TCP and UDP with exact request and reply bytes,
// the session table and its limits, handles bound to their connection, stream framing through the
// server, the inactivity timeout and the delayed broadcast ListIdentity.
#include "cip/encapsulation_server.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include "cip_test_support.h"

namespace cip {
namespace {

using test::Bytes;
using test::Hex;
using test::Of;

// Answers every request with the reply bytes set by the test and remembers what it saw.
class FakeRouter final : public UnconnectedMessageHandler {
 public:
  std::size_t HandleUnconnected(std::span<const std::uint8_t> request, RequestContext& context,
                                std::span<std::uint8_t> reply) override {
    requests.push_back(Of(request));
    last_context = context;
    if (reply_t_to_o) context.reply_t_to_o = reply_t_to_o;
    std::copy(reply_bytes.begin(), reply_bytes.end(), reply.begin());
    return reply_bytes.size();
  }
  Bytes reply_bytes = Hex("8E 00 00 00 79 01");
  std::optional<SocketAddress> reply_t_to_o;
  std::vector<Bytes> requests;
  RequestContext last_context;
};

class FakeDiscovery final : public DiscoverySource {
 public:
  IdentityItem ListIdentity() const override {
    IdentityItem item;
    item.socket_address = SocketAddress{SocketAddress::kAfInet, 44818, 0x0A00020F};
    item.vendor_id = 377;
    item.device_type = 2;
    item.product_code = 32001;
    item.major_revision = 1;
    item.minor_revision = 8;
    item.status = 0x0030;
    item.serial_number = 0x33445566;
    (void)item.product_name.Assign(product_name);
    item.state = 0xFF;
    return item;
  }
  std::string product_name = "VF-S15";
};

class FakeConnected final : public ConnectedMessageHandler {
 public:
  std::size_t HandleConnected(std::uint32_t connection_id, std::uint16_t sequence_count,
                              std::span<const std::uint8_t> request, RequestContext& context,
                              std::span<std::uint8_t> reply, std::uint32_t& reply_connection_id) override {
    seen_connection_id = connection_id;
    seen_session = context.session_handle;
    if (connection_id != known_connection) return 0;
    const Bytes answer = test::Concat({static_cast<std::uint8_t>(sequence_count), 0x00}, Hex("8E 00 00 00 02 00"));
    std::copy(answer.begin(), answer.end(), reply.begin());
    (void)request;
    reply_connection_id = 0xCAFEF00D;
    return answer.size();
  }
  bool SessionHasConnections(std::uint32_t session_handle) const override { return session_handle == busy_session; }
  void OnSessionClosed(std::uint32_t session_handle) override { closed_sessions.push_back(session_handle); }

  std::uint32_t known_connection = 0x12345678;
  std::uint32_t seen_connection_id = 0;
  std::uint32_t seen_session = 0;
  std::uint32_t busy_session = 0;
  std::vector<std::uint32_t> closed_sessions;
};

const Bytes kContext = Hex("01 02 03 04 05 06 07 08");

// A request header: command, length, session handle, context 01..08, options.
Bytes Header(std::uint16_t command, std::uint16_t length, std::uint32_t session, std::uint32_t options = 0) {
  Bytes bytes = {static_cast<std::uint8_t>(command), static_cast<std::uint8_t>(command >> 8),
                 static_cast<std::uint8_t>(length), static_cast<std::uint8_t>(length >> 8)};
  for (int i = 0; i < 4; ++i) bytes.push_back(static_cast<std::uint8_t>(session >> (8 * i)));
  bytes.insert(bytes.end(), 4, 0);
  bytes.insert(bytes.end(), kContext.begin(), kContext.end());
  for (int i = 0; i < 4; ++i) bytes.push_back(static_cast<std::uint8_t>(options >> (8 * i)));
  return bytes;
}

Bytes RegisterSessionRequest() { return test::Concat(Header(0x65, 4, 0), Hex("01 00 00 00")); }

class CipEncapsulationServerTest : public ::testing::Test {
 protected:
  TcpConnectionId Open(std::uint32_t peer_address = 0x0A000202) {
    return server_.OpenTcpConnection(Ipv4Endpoint{base::Ipv4Address(peer_address), 50000}, now_).value();
  }
  // Feeds a whole request and returns the one reply (empty when there is none).
  Bytes Exchange(TcpConnectionId id, const Bytes& request, bool* close = nullptr) {
    const TcpStep step = server_.OnTcpData(id, request, now_);
    EXPECT_EQ(step.consumed, request.size());
    if (close != nullptr) *close = step.close;
    return Of(step.reply);
  }
  std::uint32_t Register(TcpConnectionId id) {
    const Bytes reply = Exchange(id, RegisterSessionRequest());
    return static_cast<std::uint32_t>(reply.at(4) | reply.at(5) << 8 | reply.at(6) << 16 | reply.at(7) << 24);
  }

  hal::Micros now_ = 1'000'000;
  test::ScriptedRandom random_;
  FakeRouter router_;
  FakeDiscovery discovery_;
  EncapsulationServer server_{router_, discovery_, random_};
};

TEST_F(CipEncapsulationServerTest, RegisterSessionGivesARandomHandle) {
  const TcpConnectionId id = Open();
  EXPECT_EQ(Exchange(id, RegisterSessionRequest()),
            Hex("65 00 04 00 | 44 33 22 11 | 00 00 00 00 | 01 02 03 04 05 06 07 08 | 00 00 00 00 | 01 00 00 00"));
  EXPECT_EQ(server_.session_count(), 1U);
}

TEST_F(CipEncapsulationServerTest, SecondRegisterSessionOnAConnectionIsRefusedWithTheExistingHandle) {
  const TcpConnectionId id = Open();
  ASSERT_EQ(Register(id), 0x11223344U);
  random_.Push(0x99999999);
  EXPECT_EQ(Exchange(id, RegisterSessionRequest()),
            Hex("65 00 04 00 | 44 33 22 11 | 01 00 00 00 | 01 02 03 04 05 06 07 08 | 00 00 00 00 | 01 00 00 00"));
  EXPECT_EQ(server_.session_count(), 1U);
}

TEST_F(CipEncapsulationServerTest, RegisterSessionWithAnotherVersionOrOptions) {
  const TcpConnectionId id = Open();
  EXPECT_EQ(Exchange(id, test::Concat(Header(0x65, 4, 0), Hex("02 00 00 00"))),
            Hex("65 00 04 00 00 00 00 00 69 00 00 00 01 02 03 04 05 06 07 08 00 00 00 00 | 01 00 00 00"));
  EXPECT_EQ(Exchange(id, test::Concat(Header(0x65, 4, 0), Hex("01 00 01 00"))),
            Hex("65 00 04 00 00 00 00 00 69 00 00 00 01 02 03 04 05 06 07 08 00 00 00 00 | 01 00 01 00"));
  EXPECT_EQ(server_.session_count(), 0U);
}

TEST_F(CipEncapsulationServerTest, RegisterSessionWithAWrongLength) {
  const TcpConnectionId id = Open();
  EXPECT_EQ(Exchange(id, test::Concat(Header(0x65, 2, 0), Hex("01 00"))),
            Hex("65 00 00 00 00 00 00 00 65 00 00 00 01 02 03 04 05 06 07 08 00 00 00 00"));
  EXPECT_EQ(server_.session_count(), 0U);
}

TEST_F(CipEncapsulationServerTest, NinthSessionIsRefusedAndTheOthersStillWork) {
  std::vector<TcpConnectionId> ids;
  std::vector<std::uint32_t> handles;
  for (std::uint32_t i = 0; i < kMaxSessions; ++i) {
    random_.Push(0x1000 + i);
    ids.push_back(Open(0x0A000100 + i));
    handles.push_back(Register(ids.back()));
  }
  EXPECT_EQ(server_.session_count(), kMaxSessions);
  const TcpConnectionId ninth = Open();
  EXPECT_EQ(Exchange(ninth, RegisterSessionRequest()),
            Hex("65 00 04 00 00 00 00 00 02 00 00 00 01 02 03 04 05 06 07 08 00 00 00 00 | 01 00 00 00"));
  EXPECT_EQ(server_.session_count(), kMaxSessions);
  EXPECT_EQ(server_.session_pool(), (base::PoolStats{kMaxSessions, kMaxSessions, kMaxSessions, 1}));
  for (std::size_t i = 0; i < ids.size(); ++i) {
    const Bytes request = test::Concat(Header(0x6F, 16, handles[i]),
                                       Hex("00 00 00 00 00 00 02 00 00 00 00 00 B2 00 00 00"));
    EXPECT_EQ(Exchange(ids[i], request).at(8), 0x00) << i;  // status success
  }
  // Closing one connection frees its session for the ninth.
  server_.CloseTcpConnection(ids[3]);
  EXPECT_EQ(server_.session_pool(), (base::PoolStats{kMaxSessions - 1, kMaxSessions, kMaxSessions, 1}));
  random_.Push(0xABCDEF01);
  EXPECT_EQ(Register(ninth), 0xABCDEF01U);
  EXPECT_EQ(server_.session_pool(), (base::PoolStats{kMaxSessions, kMaxSessions, kMaxSessions, 1}));
  // Every connection gone: every session with it, and the pools are back where they started.
  for (std::size_t i = 0; i < ids.size(); ++i) server_.CloseTcpConnection(ids[i]);
  server_.CloseTcpConnection(ninth);
  EXPECT_EQ(server_.session_pool(), (base::PoolStats{0, kMaxSessions, kMaxSessions, 1}));
  EXPECT_EQ(server_.connection_pool(), (base::PoolStats{0, kMaxTcpConnections, kMaxSessions + 1, 0}));
}

TEST_F(CipEncapsulationServerTest, HandleCollisionsAndZeroAreDrawnAgain) {
  const TcpConnectionId first = Open();
  ASSERT_EQ(Register(first), 0x11223344U);
  random_.Push(0x11223344);  // already in use
  random_.Push(0);           // never a handle
  random_.Push(0x55667788);
  EXPECT_EQ(Register(Open()), 0x55667788U);
}

TEST_F(CipEncapsulationServerTest, TooManyConnectionsAreRefused) {
  for (std::size_t i = 0; i < kMaxTcpConnections; ++i) Open();
  EXPECT_EQ(server_.OpenTcpConnection(Ipv4Endpoint{base::Ipv4Address(1), 2}, now_).status(), base::ResourceExhausted());
  EXPECT_EQ(server_.OpenTcpConnection(Ipv4Endpoint{base::Ipv4Address(1), 3}, now_).status(), base::ResourceExhausted());
  EXPECT_EQ(server_.connection_pool(),
            (base::PoolStats{kMaxTcpConnections, kMaxTcpConnections, kMaxTcpConnections, 2}));
  server_.CloseTcpConnection(TcpConnectionId{4});
  EXPECT_EQ(server_.connection_pool().used, kMaxTcpConnections - 1);
  EXPECT_EQ(server_.OpenTcpConnection(Ipv4Endpoint{base::Ipv4Address(1), 2}, now_).value(), TcpConnectionId{4});
}

TEST_F(CipEncapsulationServerTest, SendRRDataReachesTheRouterAndWrapsItsReply) {
  const TcpConnectionId id = Open(0x0A000202);
  const std::uint32_t handle = Register(id);
  const Bytes request = test::Concat(Header(0x6F, 0x16, handle),
                                     Hex("00 00 00 00 | 0A 00 | 02 00 | 00 00 00 00 | B2 00 06 00 0E 03 20 01 24 01"));
  EXPECT_EQ(Exchange(id, request),
            Hex("6F 00 16 00 44 33 22 11 00 00 00 00 01 02 03 04 05 06 07 08 00 00 00 00"
                "| 00 00 00 00 | 00 00 | 02 00 | 00 00 00 00 | B2 00 06 00 8E 00 00 00 79 01"));
  ASSERT_EQ(router_.requests.size(), 1U);
  EXPECT_EQ(router_.requests[0], Hex("0E 03 20 01 24 01"));
  EXPECT_EQ(router_.last_context.session_handle, handle);
  EXPECT_EQ(router_.last_context.peer, (Ipv4Endpoint{base::Ipv4Address(0x0A000202), 50000}));
  EXPECT_EQ(router_.last_context.now, now_);
}

TEST_F(CipEncapsulationServerTest, SendRRDataReplyCarriesTheRoutersSocketAddressItem) {
  const TcpConnectionId id = Open();
  const std::uint32_t handle = Register(id);
  router_.reply_t_to_o = SocketAddress{2, 2222, 0xEFC00120};
  router_.reply_bytes = Hex("D4 00 00 00");
  const Bytes request = test::Concat(Header(0x6F, 0x11, handle), Hex("00 00 00 00 00 00 02 00 00 00 00 00 B2 00 01 00 54"));
  EXPECT_EQ(Exchange(id, request),
            Hex("6F 00 28 00 44 33 22 11 00 00 00 00 01 02 03 04 05 06 07 08 00 00 00 00"
                "| 00 00 00 00 00 00 03 00 | 00 00 00 00 | B2 00 04 00 D4 00 00 00"
                "| 01 80 10 00 00 02 08 AE EF C0 01 20 00 00 00 00 00 00 00 00"));
}

TEST_F(CipEncapsulationServerTest, SendRRDataWithoutOrWithAForeignSessionHandle) {
  const TcpConnectionId mine = Open();
  const TcpConnectionId other = Open();
  const std::uint32_t handle = Register(mine);
  const Bytes body = Hex("00 00 00 00 00 00 02 00 00 00 00 00 B2 00 00 00");
  // The other connection has no session; the handle is not its own.
  EXPECT_EQ(Exchange(other, test::Concat(Header(0x6F, 16, handle), body)),
            Hex("6F 00 00 00 44 33 22 11 64 00 00 00 01 02 03 04 05 06 07 08 00 00 00 00"));
  // A made-up handle on the registered connection.
  EXPECT_EQ(Exchange(mine, test::Concat(Header(0x6F, 16, handle + 1), body)),
            Hex("6F 00 00 00 45 33 22 11 64 00 00 00 01 02 03 04 05 06 07 08 00 00 00 00"));
  EXPECT_TRUE(router_.requests.empty());
}

TEST_F(CipEncapsulationServerTest, SendRRDataMalformedPackets) {
  const TcpConnectionId id = Open();
  const std::uint32_t handle = Register(id);
  // Shorter than interface handle + timeout + item count.
  EXPECT_EQ(Exchange(id, test::Concat(Header(0x6F, 6, handle), Hex("00 00 00 00 00 00"))).at(8), 0x65);
  // Item count 3 with two items; a trailing byte; a connected address item.
  EXPECT_EQ(Exchange(id, test::Concat(Header(0x6F, 16, handle), Hex("00 00 00 00 00 00 03 00 00 00 00 00 B2 00 00 00")))
                .at(8),
            0x03);
  EXPECT_EQ(
      Exchange(id, test::Concat(Header(0x6F, 17, handle), Hex("00 00 00 00 00 00 02 00 00 00 00 00 B2 00 00 00 00")))
          .at(8),
      0x03);
  EXPECT_EQ(Exchange(id, test::Concat(Header(0x6F, 20, handle),
                                      Hex("00 00 00 00 00 00 02 00 A1 00 04 00 01 00 00 00 B2 00 00 00")))
                .at(8),
            0x03);
  EXPECT_TRUE(router_.requests.empty());
}

TEST_F(CipEncapsulationServerTest, SendUnitDataGoesToTheConnectionManager) {
  FakeConnected connected;
  server_.set_connected_handler(&connected);
  const TcpConnectionId id = Open();
  const std::uint32_t handle = Register(id);
  const Bytes request = test::Concat(Header(0x70, 0x1C, handle), Hex("00 00 00 00 00 00 02 00 | A1 00 04 00 78 56 34 12"
                                                                     "| B1 00 08 00 07 00 0E 03 20 01 24 01"));
  EXPECT_EQ(Exchange(id, request), Hex("70 00 1C 00 44 33 22 11 00 00 00 00 01 02 03 04 05 06 07 08 00 00 00 00"
                                       "| 00 00 00 00 00 00 02 00 | A1 00 04 00 0D F0 FE CA"
                                       "| B1 00 08 00 07 00 8E 00 00 00 02 00"));
  EXPECT_EQ(connected.seen_session, handle);
  // An unknown connection ID is not answered.
  connected.known_connection = 1;
  EXPECT_TRUE(Exchange(id, request).empty());
}

TEST_F(CipEncapsulationServerTest, SendUnitDataWithoutAConnectionManagerIsNotAnswered) {
  const TcpConnectionId id = Open();
  const std::uint32_t handle = Register(id);
  const Bytes request = test::Concat(Header(0x70, 0x16, handle), Hex("00 00 00 00 00 00 02 00 A1 00 04 00 78 56 34 12"
                                                                     "B1 00 02 00 07 00"));
  EXPECT_TRUE(Exchange(id, request).empty());
  // ... but a bad session is still reported.
  EXPECT_EQ(Exchange(id, test::Concat(Header(0x70, 0x16, 0), Bytes(request.begin() + 24, request.end()))).at(8), 0x64);
}

TEST_F(CipEncapsulationServerTest, UnRegisterSessionClosesWithoutAReply) {
  FakeConnected connected;
  server_.set_connected_handler(&connected);
  const TcpConnectionId id = Open();
  const std::uint32_t handle = Register(id);
  bool close = false;
  EXPECT_EQ(Exchange(id, Header(0x66, 0, handle + 1), &close),
            Hex("66 00 00 00 45 33 22 11 64 00 00 00 01 02 03 04 05 06 07 08 00 00 00 00"));
  EXPECT_FALSE(close);
  EXPECT_TRUE(Exchange(id, Header(0x66, 0, handle), &close).empty());
  EXPECT_TRUE(close);
  EXPECT_EQ(server_.session_count(), 0U);
  EXPECT_EQ(connected.closed_sessions, std::vector<std::uint32_t>{handle});
}

TEST_F(CipEncapsulationServerTest, NopIsNeverAnswered) {
  const TcpConnectionId id = Open();
  bool close = true;
  EXPECT_TRUE(Exchange(id, test::Concat(Header(0x00, 3, 0), Hex("01 02 03")), &close).empty());
  EXPECT_FALSE(close);
}

TEST_F(CipEncapsulationServerTest, UnknownCommandGetsInvalidCommand) {
  const TcpConnectionId id = Open();
  EXPECT_EQ(Exchange(id, test::Concat(Header(0x0001, 2, 0x42), Hex("AA BB"))),
            Hex("01 00 00 00 42 00 00 00 01 00 00 00 01 02 03 04 05 06 07 08 00 00 00 00"));
}

TEST_F(CipEncapsulationServerTest, NonZeroOptionsAreDroppedSilently) {
  const TcpConnectionId id = Open();
  EXPECT_TRUE(Exchange(id, test::Concat(Header(0x65, 4, 0, 1), Hex("01 00 00 00"))).empty());
  EXPECT_EQ(server_.session_count(), 0U);
}

TEST_F(CipEncapsulationServerTest, DiscoveryCommandsOverTcp) {
  const TcpConnectionId id = Open();
  EXPECT_EQ(Exchange(id, Header(0x63, 0, 0)),
            Hex("63 00 2E 00 00 00 00 00 00 00 00 00 01 02 03 04 05 06 07 08 00 00 00 00"
                "| 01 00 0C 00 28 00 01 00 00 02 AF 12 0A 00 02 0F 00 00 00 00 00 00 00 00"
                "| 79 01 02 00 01 7D 01 08 30 00 66 55 44 33 06 56 46 2D 53 31 35 FF"));
  EXPECT_EQ(Exchange(id, Header(0x04, 0, 0)),
            Hex("04 00 1A 00 00 00 00 00 00 00 00 00 01 02 03 04 05 06 07 08 00 00 00 00"
                "| 01 00 00 01 14 00 01 00 20 01 43 6F 6D 6D 75 6E 69 63 61 74 69 6F 6E 73 00 00"));
  EXPECT_EQ(Exchange(id, Header(0x64, 0, 0)),
            Hex("64 00 02 00 00 00 00 00 00 00 00 00 01 02 03 04 05 06 07 08 00 00 00 00 | 00 00"));
  // A discovery request carries no data.
  EXPECT_EQ(Exchange(id, test::Concat(Header(0x63, 1, 0), Hex("00"))),
            Hex("63 00 00 00 00 00 00 00 65 00 00 00 01 02 03 04 05 06 07 08 00 00 00 00"));
}

TEST_F(CipEncapsulationServerTest, MessagesSplitAndJoinedOnTheStream) {
  const TcpConnectionId id = Open();
  const Bytes stream = test::Concat(RegisterSessionRequest(), Header(0x64, 0, 0));
  // The first 10 bytes: nothing to answer yet.
  TcpStep step = server_.OnTcpData(id, std::span(stream).first(10), now_);
  EXPECT_EQ(step.consumed, 10U);
  EXPECT_TRUE(step.reply.empty());
  // The rest in one go: the first call answers RegisterSession and stops there ...
  std::span<const std::uint8_t> rest = std::span(stream).subspan(10);
  step = server_.OnTcpData(id, rest, now_);
  EXPECT_EQ(step.consumed, 28U - 10U);
  EXPECT_EQ(step.reply.size(), 28U);
  // ... the second answers ListInterfaces.
  rest = rest.subspan(step.consumed);
  step = server_.OnTcpData(id, rest, now_);
  EXPECT_EQ(step.consumed, 24U);
  EXPECT_EQ(Of(step.reply).at(0), 0x64);
}

TEST_F(CipEncapsulationServerTest, OversizedMessageGetsInsufficientMemoryAndTheStreamCarriesOn) {
  const TcpConnectionId id = Open();
  Bytes stream = Header(0x6F, 1000, 0);
  stream.resize(stream.size() + 1000, 0);
  const Bytes after = Header(0x64, 0, 0);
  stream.insert(stream.end(), after.begin(), after.end());
  TcpStep step = server_.OnTcpData(id, stream, now_);
  EXPECT_EQ(step.consumed, 1024U);
  EXPECT_EQ(Of(step.reply), Hex("6F 00 00 00 00 00 00 00 02 00 00 00 01 02 03 04 05 06 07 08 00 00 00 00"));
  step = server_.OnTcpData(id, std::span(stream).subspan(1024), now_);
  EXPECT_EQ(Of(step.reply).at(0), 0x64);
}

TEST_F(CipEncapsulationServerTest, UnknownConnectionIsClosed) {
  const Bytes request = Header(0x64, 0, 0);
  const TcpStep step = server_.OnTcpData(TcpConnectionId{3}, request, now_);
  EXPECT_TRUE(step.close);
  EXPECT_EQ(step.consumed, request.size());
}

TEST_F(CipEncapsulationServerTest, InactivityTimeoutClosesIdleConnections) {
  FakeConnected connected;
  server_.set_connected_handler(&connected);
  const hal::Micros opened = now_;
  const TcpConnectionId idle = Open();
  EXPECT_EQ(server_.NextDeadline(), opened + kTcpInactivityTimeout);
  // Traffic moves the deadline.
  now_ += 60 * hal::kMicrosPerSecond;
  const TcpConnectionId busy = Open();
  (void)Exchange(idle, Header(0x00, 0, 0));
  EXPECT_EQ(server_.NextDeadline(), now_ + kTcpInactivityTimeout);
  TcpConnectionId expired;
  EXPECT_FALSE(server_.TakeExpiredConnection(now_ + kTcpInactivityTimeout - 1, expired));
  ASSERT_TRUE(server_.TakeExpiredConnection(now_ + kTcpInactivityTimeout, expired));
  EXPECT_EQ(expired, idle);
  // A session that owns CIP connections is not closed, and is only looked at again later.
  const std::uint32_t handle = Register(busy);
  connected.busy_session = handle;
  const hal::Micros later = now_ + 2 * kTcpInactivityTimeout;
  EXPECT_FALSE(server_.TakeExpiredConnection(later, expired));
  EXPECT_EQ(server_.NextDeadline(), later + kTcpInactivityTimeout);
  connected.busy_session = 0;
  ASSERT_TRUE(server_.TakeExpiredConnection(later + kTcpInactivityTimeout, expired));
  EXPECT_EQ(expired, busy);
  server_.CloseTcpConnection(busy);
  server_.CloseTcpConnection(idle);
  EXPECT_EQ(server_.NextDeadline(), hal::kNever);
  EXPECT_EQ(connected.closed_sessions, std::vector<std::uint32_t>{handle});
}

// --- UDP ------------------------------------------------------------------------------------------

const UdpSource kUnicast{Ipv4Endpoint{base::Ipv4Address(0x0A000202), 44818}, false};
const UdpSource kBroadcast{Ipv4Endpoint{base::Ipv4Address(0x0A000203), 50123}, true};

TEST_F(CipEncapsulationServerTest, UnicastListIdentityIsAnsweredAtOnce) {
  const UdpDecision decision = server_.OnUdpDatagram(Header(0x63, 0, 0), kUnicast, now_);
  ASSERT_EQ(decision.action, UdpDecision::Action::kSendNow);
  EXPECT_EQ(Of(decision.reply).size(), 24U + 46U);
  EXPECT_EQ(Of(decision.reply).at(0), 0x63);
  const UdpDecision services = server_.OnUdpDatagram(Header(0x04, 0, 0), kBroadcast, now_);
  ASSERT_EQ(services.action, UdpDecision::Action::kSendNow);
  EXPECT_EQ(Of(services.reply).at(0), 0x04);
}

TEST_F(CipEncapsulationServerTest, ListIdentityWithTheLongestProductNameFillsTheUdpReplyExactly) {
  // The Identity object's product name is at most 32 characters; one more is not accepted by the item.
  IdentityItem item;
  EXPECT_FALSE(item.product_name.Assign(std::string(33, 'N')));
  discovery_.product_name = std::string(32, 'N');
  const UdpDecision decision = server_.OnUdpDatagram(Header(0x63, 0, 0), kUnicast, now_);
  ASSERT_EQ(decision.action, UdpDecision::Action::kSendNow);
  const Bytes reply = Of(decision.reply);
  ASSERT_EQ(reply.size(), kMaxUdpReply);
  EXPECT_EQ(Bytes(reply.begin(), reply.begin() + 4), Hex("63 00 48 00"));  // 72 bytes of data
  EXPECT_EQ(Bytes(reply.end() - 34, reply.end()), test::Concat(test::Concat(Hex("20"), Bytes(32, 'N')), Hex("FF")));
  // The same reply when it leaves later, to a broadcast request.
  random_.Push(0);
  ASSERT_EQ(server_.OnUdpDatagram(Header(0x63, 0, 0), kBroadcast, now_).action, UdpDecision::Action::kSendLater);
  DueDatagram due;
  ASSERT_TRUE(server_.TakeDueDatagram(now_ + kDefaultListIdentityMaxDelay, due));
  EXPECT_EQ(Of(due.bytes).size(), kMaxUdpReply);
}

TEST_F(CipEncapsulationServerTest, BroadcastListIdentityWaitsARandomTimeWithinTheMaxDelay) {
  // Sender context bytes 0-1 = max delay in ms: 0x03E8 = 1000 ms.
  Bytes request = Header(0x63, 0, 0);
  request[12] = 0xE8;
  request[13] = 0x03;
  random_.Push(1'000'001 + 250'000);  // modulo 1'000'001 -> 250 ms
  const UdpDecision decision = server_.OnUdpDatagram(request, kBroadcast, now_);
  ASSERT_EQ(decision.action, UdpDecision::Action::kSendLater);
  EXPECT_EQ(decision.send_at, now_ + 250'000);
  EXPECT_EQ(server_.NextDeadline(), now_ + 250'000);
  DueDatagram due;
  EXPECT_FALSE(server_.TakeDueDatagram(now_ + 249'999, due));
  ASSERT_TRUE(server_.TakeDueDatagram(now_ + 250'000, due));
  EXPECT_EQ(due.to, kBroadcast.peer);
  EXPECT_EQ(Of(due.bytes),
            Hex("63 00 2E 00 00 00 00 00 00 00 00 00 E8 03 03 04 05 06 07 08 00 00 00 00"
                "| 01 00 0C 00 28 00 01 00 00 02 AF 12 0A 00 02 0F 00 00 00 00 00 00 00 00"
                "| 79 01 02 00 01 7D 01 08 30 00 66 55 44 33 06 56 46 2D 53 31 35 FF"));
  EXPECT_FALSE(server_.TakeDueDatagram(now_ + 300'000, due));
  EXPECT_EQ(server_.NextDeadline(), hal::kNever);
}

TEST_F(CipEncapsulationServerTest, ListIdentityMaxDelayDefaultsAndFloor) {
  random_.Push(0xFFFFFFFF);
  // 0 means 2000 ms: the delay stays within [0, 2000 ms].
  const UdpDecision defaulted = server_.OnUdpDatagram(
      test::Concat(Hex("63 00 00 00 00 00 00 00 00 00 00 00"), Hex("00 00 00 00 00 00 00 00 00 00 00 00")), kBroadcast,
      now_);
  ASSERT_EQ(defaulted.action, UdpDecision::Action::kSendLater);
  EXPECT_EQ(defaulted.send_at, now_ + 0xFFFFFFFFULL % 2'000'001);
  // 100 ms is raised to 500 ms.
  random_.Push(499'999 + 500'001);
  const UdpDecision floored = server_.OnUdpDatagram(
      test::Concat(Hex("63 00 00 00 00 00 00 00 00 00 00 00"), Hex("64 00 00 00 00 00 00 00 00 00 00 00")), kBroadcast,
      now_);
  EXPECT_EQ(floored.send_at, now_ + 499'999);
  // A third one while two wait is dropped.
  EXPECT_EQ(server_.OnUdpDatagram(Header(0x63, 0, 0), kBroadcast, now_).action, UdpDecision::Action::kDrop);
  EXPECT_EQ(server_.delayed_reply_pool(), (base::PoolStats{2, kMaxDelayedReplies, 2, 1}));
  DueDatagram due;
  while (server_.TakeDueDatagram(now_ + 2'000'000, due)) {
  }
  EXPECT_EQ(server_.delayed_reply_pool(), (base::PoolStats{0, kMaxDelayedReplies, 2, 1}));
}

TEST_F(CipEncapsulationServerTest, TcpOnlyCommandsOverUdp) {
  const UdpDecision unicast = server_.OnUdpDatagram(RegisterSessionRequest(), kUnicast, now_);
  ASSERT_EQ(unicast.action, UdpDecision::Action::kSendNow);
  EXPECT_EQ(Of(unicast.reply), Hex("65 00 00 00 00 00 00 00 01 00 00 00 01 02 03 04 05 06 07 08 00 00 00 00"));
  EXPECT_EQ(server_.session_count(), 0U);
  EXPECT_EQ(server_.OnUdpDatagram(RegisterSessionRequest(), kBroadcast, now_).action, UdpDecision::Action::kDrop);
  EXPECT_EQ(server_.OnUdpDatagram(Header(0x00, 0, 0), kUnicast, now_).action, UdpDecision::Action::kDrop);
}

TEST_F(CipEncapsulationServerTest, MalformedDatagramsAreDropped) {
  const Bytes list_identity = Header(0x63, 0, 0);
  EXPECT_EQ(server_.OnUdpDatagram(std::span(list_identity).first(23), kUnicast, now_).action,
            UdpDecision::Action::kDrop);
  EXPECT_EQ(server_.OnUdpDatagram(test::Concat(list_identity, Hex("00")), kUnicast, now_).action,
            UdpDecision::Action::kDrop);
  EXPECT_EQ(server_.OnUdpDatagram(Header(0x63, 0, 0, 4), kUnicast, now_).action, UdpDecision::Action::kDrop);
  // A length that is consistent but wrong for the command is answered on unicast only.
  const Bytes with_data = test::Concat(Header(0x63, 1, 0), Hex("00"));
  EXPECT_EQ(Of(server_.OnUdpDatagram(with_data, kUnicast, now_).reply).at(8), 0x65);
  EXPECT_EQ(server_.OnUdpDatagram(with_data, kBroadcast, now_).action, UdpDecision::Action::kDrop);
}

}  // namespace
}  // namespace cip
