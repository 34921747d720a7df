// The Connection Manager object through the message router: its attributes, Forward_Open success for
// every connection type, every rejection with its exact reply, Forward_Close, and the counters.
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <string_view>

#include "cip/connection_manager.h"
#include "cip_connection_fakes.h"

namespace cip {
namespace {

using test::Bytes;
using test::ConnectionCard;
using test::Hex;
using test::OpenParams;

// The reply to a refused Forward_Open with the default triad: general status 0x01, the additional
// status words given, the triad, remaining path size and reserved byte.
Bytes Refused(std::string_view additional, std::uint8_t remaining_words = 0, std::uint8_t service = 0xD4) {
  const Bytes words = Hex(additional);
  Bytes reply = {service, 0x00, 0x01, static_cast<std::uint8_t>(words.size() / 2)};
  reply.insert(reply.end(), words.begin(), words.end());
  const Bytes tail = Hex("37 13 33 33 78 56 34 12");
  reply.insert(reply.end(), tail.begin(), tail.end());
  reply.push_back(remaining_words);
  reply.push_back(0);
  return reply;
}

OpenParams InputOnly(std::uint16_t serial, std::uint32_t produced = 0x96) {
  OpenParams params;
  params.triad.connection_serial = serial;
  params.o_to_t.size = 2;
  params.t_to_o.size = produced == 0x96 ? 8 : 6;
  params.path = Hex("20 04 24 01 2C C6 2C 00");
  params.path.back() = static_cast<std::uint8_t>(produced);
  return params;
}

OpenParams ListenOnly(std::uint16_t serial) {
  OpenParams params = InputOnly(serial);
  params.path = Hex("20 04 24 01 2C C7 2C 96");
  return params;
}

TEST(CipConnectionManagerTest, ClassAndInstanceAttributes) {
  ConnectionCard card;
  EXPECT_EQ(card.Ask(Hex("0E 03 20 06 24 00 30 01")), Hex("8E 00 00 00 01 00"));
  EXPECT_EQ(card.Ask(Hex("0E 03 20 06 24 00 30 02")), Hex("8E 00 00 00 01 00"));
  EXPECT_EQ(card.Ask(Hex("0E 03 20 06 24 00 30 03")), Hex("8E 00 00 00 01 00"));
  EXPECT_EQ(card.Ask(Hex("0E 03 20 06 24 00 30 04")),
            Hex("8E 00 00 00 08 00 01 00 02 00 03 00 04 00 05 00 06 00 07 00 08 00"));
  EXPECT_EQ(card.Ask(Hex("0E 03 20 06 24 00 30 06")), Hex("8E 00 00 00 07 00"));
  EXPECT_EQ(card.Ask(Hex("0E 03 20 06 24 00 30 07")), Hex("8E 00 00 00 08 00"));
  EXPECT_EQ(card.Ask(Hex("0E 03 20 06 24 00 30 05")), Hex("8E 00 14 00"));
  for (std::uint8_t id = 1; id <= 8; ++id) {
    EXPECT_EQ(card.Ask(Bytes{0x0E, 0x03, 0x20, 0x06, 0x24, 0x01, 0x30, id}), Hex("8E 00 00 00 00 00"));
  }
  EXPECT_EQ(card.Ask(Hex("0E 03 20 06 24 01 30 09")), Hex("8E 00 14 00"));
  EXPECT_EQ(card.Ask(Hex("0E 03 20 06 24 02 30 01")), Hex("8E 00 16 00"));
  // Services the manual does not list, and the connection services at class level: 0x08.
  EXPECT_EQ(card.Ask(Hex("01 02 20 06 24 01")), Hex("81 00 08 00"));
  EXPECT_EQ(card.Ask(Hex("54 02 20 06 24 00")), Hex("D4 00 08 00"));
  EXPECT_EQ(card.Ask(Hex("4E 02 20 06 24 00")), Hex("CE 00 08 00"));
}

TEST(CipConnectionManagerTest, OpensExclusiveOwner) {
  ConnectionCard card;
  EXPECT_EQ(
      card.Ask(Hex("54 02 20 06 24 01 | 0A 0E 00 00 00 00 01 00 00 20 37 13 33 33 78 56 34 12 01 00 00 00"
                   "| 10 27 00 00 0E 48 10 27 00 00 08 48 01 | 09"
                   "| 34 04 79 01 02 00 00 7D 01 08 20 04 24 01 2C 64 2C 96")),
      Hex("D4 00 00 00 | 44 33 22 11 | 01 00 00 20 | 37 13 33 33 78 56 34 12 | 10 27 00 00 | 10 27 00 00 | 00 00"));
  EXPECT_FALSE(card.context.reply_t_to_o.has_value());  // point-to-point: no socket address item
  EXPECT_EQ(card.cm.ActiveConnections(), 1);
  EXPECT_TRUE(card.cm.IsOwned(100));
  EXPECT_FALSE(card.cm.IsOwned(198));
  EXPECT_EQ(card.events.changes, 1);
  EXPECT_EQ(card.cm.IoStatus(), ExtendedDeviceStatus::kIoConnectionsIdle);
  // Message Router attribute 3 counts it.
  EXPECT_EQ(card.Ask(Hex("0E 03 20 02 24 01 30 03")), Hex("8E 00 00 00 01 00"));
  EXPECT_EQ(card.Ask(Hex("0E 03 20 06 24 01 30 01")), Hex("8E 00 00 00 01 00"));
  EXPECT_TRUE(card.io.configured.empty());  // no data segment: Configure is not called
}

TEST(CipConnectionManagerTest, OpensWithLargeForwardOpenAndConfigurationData) {
  ConnectionCard card;
  OpenParams params;
  params.large = true;
  params.path = Hex("20 04 24 02 2C 64 2C 96 80 02 01 02 03 04");
  EXPECT_EQ(
      card.Open(params),
      Hex("DB 00 00 00 | 44 33 22 11 | 01 00 00 20 | 37 13 33 33 78 56 34 12 | 10 27 00 00 | 10 27 00 00 | 00 00"));
  ASSERT_EQ(card.io.configured.size(), 1U);
  EXPECT_EQ(card.io.configured[0].first, 2U);
  EXPECT_EQ(card.io.configured[0].second, Hex("01 02 03 04"));
}

TEST(CipConnectionManagerTest, OpensInputOnlyAndListenOnly) {
  ConnectionCard card;
  EXPECT_EQ(card.Open(InputOnly(1)),
            Hex("D4 00 00 00 44 33 22 11 01 00 00 20 01 00 33 33 78 56 34 12 10 27 00 00 10 27 00 00 00 00"));
  OpenParams listen = ListenOnly(2);
  listen.t_to_o_id = 0x20000002;
  EXPECT_EQ(card.Open(listen),
            Hex("D4 00 00 00 45 34 23 12 02 00 00 20 02 00 33 33 78 56 34 12 10 27 00 00 10 27 00 00 00 00"));
  // A heartbeat may come with a run/idle header too (O->T size 6).
  OpenParams with_header = InputOnly(3, 0x97);
  with_header.o_to_t.size = 6;
  EXPECT_EQ(card.Open(with_header)[2], 0x00);
  EXPECT_EQ(card.cm.ActiveConnections(), 3);
  EXPECT_FALSE(card.cm.IsOwned(198));
}

TEST(CipConnectionManagerTest, OpensMulticastAndSharesTheProduction) {
  ConnectionCard card;
  OpenParams owner;
  owner.t_to_o.type = ConnectionType::kMulticast;
  EXPECT_EQ(
      card.Open(owner),
      Hex("D4 00 00 00 | 44 33 22 11 | 45 34 23 12 | 37 13 33 33 78 56 34 12 | 10 27 00 00 | 10 27 00 00 | 00 00"));
  ASSERT_TRUE(card.context.reply_t_to_o.has_value());
  EXPECT_EQ(*card.context.reply_t_to_o, (SocketAddress{SocketAddress::kAfInet, 2222, 0xEFC00120}));

  OpenParams listen = ListenOnly(2);
  listen.t_to_o.type = ConnectionType::kMulticast;
  EXPECT_EQ(
      card.Open(listen),
      Hex("D4 00 00 00 | 46 35 24 13 | 45 34 23 12 | 02 00 33 33 78 56 34 12 | 10 27 00 00 | 10 27 00 00 | 00 00"));
  EXPECT_EQ(*card.context.reply_t_to_o, (SocketAddress{SocketAddress::kAfInet, 2222, 0xEFC00120}));

  // Another point needs a group of its own: none when the allocation (TCP/IP attribute 9) has one.
  OpenParams input = InputOnly(3, 0x97);
  input.t_to_o.type = ConnectionType::kMulticast;
  card.groups.count = 1;
  Bytes expected = Refused("13 01");
  expected[6] = 0x03;  // connection serial 3
  expected[7] = 0x00;
  EXPECT_EQ(card.Open(input), expected);
  // Two connections on one production: the refusal was the production pool's, not the table's.
  EXPECT_EQ(card.cm.production_pool(), (base::PoolStats{1, kMaxCipConnections, 1, 1}));
  EXPECT_EQ(card.cm.connection_pool(), (base::PoolStats{2, kMaxCipConnections, 2, 0}));
  card.groups.count = 2;
  EXPECT_EQ(card.Open(input)[2], 0x00);
  EXPECT_EQ(*card.context.reply_t_to_o, (SocketAddress{SocketAddress::kAfInet, 2222, 0xEFC00121}));
  OpenParams more = InputOnly(4, 0x97);
  more.t_to_o.type = ConnectionType::kMulticast;
  EXPECT_EQ(card.Open(more)[2], 0x00);  // shares 151's production
  EXPECT_EQ(*card.context.reply_t_to_o, (SocketAddress{SocketAddress::kAfInet, 2222, 0xEFC00121}));
  EXPECT_EQ(card.cm.ActiveConnections(), 4);
}

TEST(CipConnectionManagerTest, ForwardOpenOverEncapsulationCarriesTheMulticastAddressItem) {
  ConnectionCard card;
  auto& encapsulation = card.card.cip.encapsulation();
  const TcpConnectionId id = encapsulation.OpenTcpConnection(Ipv4Endpoint{test::kOriginator, 51000}, 0).value();
  ASSERT_EQ(encapsulation
                .OnTcpData(id,
                           Hex("65 00 04 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00"
                               "01 00 00 00"),
                           0)
                .consumed,
            28U);
  OpenParams params;
  params.t_to_o.type = ConnectionType::kMulticast;
  const Bytes open = test::ForwardOpenRequestBytes(params);
  Bytes request =
      Hex("6F 00 00 00 44 33 22 11 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00"
          "00 00 00 00 00 00 02 00 00 00 00 00 B2 00 00 00");
  request[2] = static_cast<std::uint8_t>(16 + open.size());
  request[38] = static_cast<std::uint8_t>(open.size());
  request.insert(request.end(), open.begin(), open.end());
  const TcpStep step = encapsulation.OnTcpData(id, request, 0);
  EXPECT_EQ(test::Of(step.reply),
            Hex("6F 00 42 00 44 33 22 11 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00"
                "| 00 00 00 00 00 00 03 00 | 00 00 00 00 | B2 00 1E 00"
                "| D4 00 00 00 44 33 22 11 45 34 23 12 37 13 33 33 78 56 34 12 10 27 00 00 10 27 00 00 00 00"
                "| 01 80 10 00 00 02 08 AE EF C0 01 20 00 00 00 00 00 00 00 00"));
  // The session owns a connection: the inactivity timeout leaves its TCP connection open.
  EXPECT_TRUE(card.cm.SessionHasConnections(0x11223344));
}

TEST(CipConnectionManagerTest, RefusesDuplicateAndOwnershipConflict) {
  ConnectionCard card;
  ASSERT_EQ(card.Open()[2], 0x00);
  EXPECT_EQ(card.Open(), Refused("00 01"));
  OpenParams other;
  other.triad.connection_serial = 0x1338;
  EXPECT_EQ(card.Open(other)[4], 0x06);
  other.triad.connection_serial = 0x1337;
  other.triad.originator_serial = 1;
  Bytes expected = Refused("06 01");
  expected[10] = 0x01;  // originator serial 1
  expected[11] = expected[12] = expected[13] = 0x00;
  EXPECT_EQ(card.Open(other), expected);
}

TEST(CipConnectionManagerTest, RefusesTransportAndTrigger) {
  ConnectionCard card;
  // Class 0, class 2, class 1 change of state / application object (server or not), class 3 with
  // a reserved trigger, classes 4 and 15.
  const std::array<std::uint8_t, 8> transports = {0x00, 0x02, 0x11, 0x21, 0x91, 0x33, 0x04, 0x0F};
  for (const std::uint8_t transport : transports) {
    OpenParams params;
    params.transport = transport;
    EXPECT_EQ(card.Open(params), Refused("03 01")) << int{transport};
  }
  // Class 1 to the Message Router, class 3 to an assembly.
  OpenParams to_router;
  to_router.path = Hex("20 02 24 01");
  EXPECT_EQ(card.Open(to_router), Refused("03 01"));
  OpenParams explicit_to_assembly = test::ExplicitParams();
  explicit_to_assembly.path = Hex("20 04 24 01 2C 64 2C 96");
  EXPECT_EQ(card.Open(explicit_to_assembly), Refused("03 01"));
}

TEST(CipConnectionManagerTest, RefusesConnectionTypes) {
  ConnectionCard card;
  OpenParams params;
  params.o_to_t.type = ConnectionType::kMulticast;
  EXPECT_EQ(card.Open(params), Refused("23 01"));
  params.o_to_t.type = ConnectionType::kNull;
  EXPECT_EQ(card.Open(params), Refused("23 01"));
  params.o_to_t.type = ConnectionType::kReserved;
  EXPECT_EQ(card.Open(params), Refused("23 01"));
  params = OpenParams{};
  params.t_to_o.type = ConnectionType::kNull;
  EXPECT_EQ(card.Open(params), Refused("24 01"));
  params.t_to_o.type = ConnectionType::kReserved;
  EXPECT_EQ(card.Open(params), Refused("24 01"));
  OpenParams explicit_multicast = test::ExplicitParams();
  explicit_multicast.t_to_o.type = ConnectionType::kMulticast;
  EXPECT_EQ(card.Open(explicit_multicast), Refused("24 01"));
  params = OpenParams{};
  params.o_to_t.redundant_owner = true;
  EXPECT_EQ(card.Open(params), Refused("25 01"));
  params = OpenParams{};
  params.o_to_t.type = ConnectionType::kNull;
  params.t_to_o.type = ConnectionType::kNull;
  EXPECT_EQ(card.Open(params), Refused("32 01"));

  // Without a multicast provider, multicast T->O is a connection type the card does not offer.
  card.cm.set_multicast_provider(nullptr);
  params = OpenParams{};
  params.t_to_o.type = ConnectionType::kMulticast;
  EXPECT_EQ(card.Open(params), Refused("24 01"));
}

TEST(CipConnectionManagerTest, RefusesTimeoutMultiplierAndRpi) {
  ConnectionCard card;
  OpenParams params;
  params.multiplier = 8;
  EXPECT_EQ(card.Open(params), Refused("33 01"));
  params.multiplier = 7;
  params.o_to_t_rpi = 999;  // below the 1 ms floor: the floor is the acceptable O->T RPI
  EXPECT_EQ(card.Open(params), Refused("11 01 | 02 00 | E8 03 00 00 | 10 27 00 00"));
  params.o_to_t_rpi = 10000;
  params.t_to_o_rpi = 10000001;  // above 10 s
  EXPECT_EQ(card.Open(params), Refused("11 01 | 00 03 | 10 27 00 00 | 80 96 98 00"));
  params.t_to_o_rpi = 1000;
  EXPECT_EQ(card.Open(params)[2], 0x00);  // exactly the floor
  EXPECT_EQ(card.cm.counters().open_other_rejects, 3);

  // The firmware sets its own floor.
  ConnectionManagerOptions options;
  options.min_rpi = 2000;
  ConnectionCard slow(options);
  params = OpenParams{};
  params.o_to_t_rpi = 1000;
  params.t_to_o_rpi = 1500;
  EXPECT_EQ(slow.Open(params), Refused("11 01 | 02 02 | D0 07 00 00 | D0 07 00 00"));
}

TEST(CipConnectionManagerTest, RefusesMismatchedRpiOnASharedMulticastProduction) {
  ConnectionCard card;
  OpenParams owner;
  owner.t_to_o.type = ConnectionType::kMulticast;
  ASSERT_EQ(card.Open(owner)[2], 0x00);
  OpenParams listen = ListenOnly(0x1337);
  listen.triad.originator_serial = 0x12345678;
  listen.triad.connection_serial = 0x1337;
  listen.triad.originator_vendor = 0x3334;
  listen.t_to_o.type = ConnectionType::kMulticast;
  listen.t_to_o_rpi = 20000;
  Bytes expected = Refused("12 01 | 00 04 | 10 27 00 00 | 10 27 00 00");
  expected[18] = 0x34;  // vendor 0x3334
  EXPECT_EQ(card.Open(listen), expected);
  // Point-to-point it has its own production at its own RPI.
  listen.t_to_o.type = ConnectionType::kPointToPoint;
  EXPECT_EQ(card.Open(listen)[2], 0x00);
}

TEST(CipConnectionManagerTest, RefusesElectronicKeys) {
  ConnectionCard card;
  const auto with_key = [](std::string_view key) {
    OpenParams params;
    params.path = Hex(key);
    const Bytes rest = Hex("20 04 24 01 2C 64 2C 96");
    params.path.insert(params.path.end(), rest.begin(), rest.end());
    return params;
  };
  EXPECT_EQ(card.Open(with_key("34 04 7A 01 02 00 00 7D 01 08")), Refused("14 01"));
  EXPECT_EQ(card.Open(with_key("34 04 79 01 02 00 01 7D 01 08")), Refused("14 01"));  // a VF-S15's code
  EXPECT_EQ(card.Open(with_key("34 04 79 01 0C 00 00 7D 01 08")), Refused("15 01"));
  EXPECT_EQ(card.Open(with_key("34 04 79 01 02 00 00 7D 02 08")), Refused("16 01"));
  EXPECT_EQ(card.Open(with_key("34 04 79 01 02 00 00 7D 81 09")), Refused("16 01"));
  // The product code follows the connected drive.
  card.card.device.model = DriveModel::kVfS15;
  EXPECT_EQ(card.Open(with_key("34 04 79 01 02 00 01 7D 81 07"))[2], 0x00);
}

TEST(CipConnectionManagerTest, IoDataUpToKMaxIoDataOneByteMoreIsRefused) {
  // Points whose data is kMaxIoData (32) bytes open (O->T 2 + 4 + 32, T->O 2 + 32); a point of 33 bytes is
  // refused 0x01 with the consuming / producing path's extended status, before its sizes are compared.
  ConnectionCard card;
  OpenParams params;
  params.path = Hex("20 04 24 01 2C 66 2C 98");  // 102 / 152
  params.o_to_t.size = 2 + 4 + kMaxIoData;
  params.t_to_o.size = 2 + kMaxIoData;
  card.io.scanner_consumed_size = kMaxIoData;
  card.io.scanner_produced_size = kMaxIoData;
  EXPECT_EQ(card.Open(params).at(2), 0x00);
  // Another triad (serial 0x1338), so that the refusals are for the sizes, not a duplicate.
  params.triad.connection_serial = 0x1338;
  const auto refused = [](std::string_view extended) {
    Bytes expected = Refused(extended);
    expected[6] = 0x38;
    return expected;
  };
  card.io.scanner_consumed_size = kMaxIoData + 1;
  EXPECT_EQ(card.Open(params), refused("2A 01"));
  card.io.scanner_consumed_size = kMaxIoData;
  card.io.scanner_produced_size = kMaxIoData + 1;
  EXPECT_EQ(card.Open(params), refused("2B 01"));
}

TEST(CipConnectionManagerTest, RefusesApplicationPathsAndSizes) {
  ConnectionCard card;
  const auto with_path = [](std::string_view path) {
    OpenParams params;
    params.path = Hex(path);
    return params;
  };
  EXPECT_EQ(card.Open(with_path("20 04 24 05 2C 64 2C 96")), Refused("29 01"));
  EXPECT_EQ(card.Open(with_path("20 04 24 01 2C 65 2C 96")), Refused("2A 01"));
  EXPECT_EQ(card.Open(with_path("20 04 24 01 2C 64 2C 99")), Refused("2B 01"));
  EXPECT_EQ(card.Open(with_path("20 04 24 01 2C 64 2C 97")), Refused("2F 01"));
  EXPECT_EQ(card.Open(with_path("20 04 24 01")), Refused("2A 01"));
  EXPECT_EQ(card.Open(with_path("20 04 24 01 2C 64")), Refused("2B 01"));
  // Sizes, with the size the connection needs.
  OpenParams params;
  params.o_to_t.size = 12;
  EXPECT_EQ(card.Open(params), Refused("27 01 0E 00"));
  params = OpenParams{};
  params.t_to_o.size = 10;
  EXPECT_EQ(card.Open(params), Refused("28 01 08 00"));
  params = InputOnly(0x1337);
  params.o_to_t.size = 4;  // heartbeat: 2 (or 6 with a header)
  EXPECT_EQ(card.Open(params), Refused("27 01 02 00"));
  // Configuration data of the wrong size; data without a configuration point.
  EXPECT_EQ(card.Open(with_path("20 04 24 02 2C 64 2C 96 80 01 01 02")), Refused("26 01 04 00"));
  EXPECT_EQ(card.Open(with_path("20 04 24 01 2C 64 2C 96 80 01 01 02")), Refused("26 01 00 00"));
  EXPECT_EQ(card.Open(with_path("20 04 2C 64 2C 96 80 00")), Refused("29 01"));
  // The application refuses the configuration.
  card.io.refuse_configuration = 0x0126;
  EXPECT_EQ(card.Open(with_path("20 04 24 02 2C 64 2C 96 80 02 01 02 03 04")), Refused("26 01"));
  EXPECT_EQ(card.cm.ActiveConnections(), 0);
  // Without an application no class 1 connection exists.
  card.cm.set_io_application(nullptr);
  EXPECT_EQ(card.Open(), Refused("2A 01"));
}

TEST(CipConnectionManagerTest, PointsWithAChoiceOfSizesTakeTheRequestedOnes) {
  ConnectionCard card;
  OpenParams params;
  params.o_to_t.size = 16;  // sequence count, run/idle header, 10 bytes
  params.t_to_o.size = 14;  // sequence count, 12 bytes
  params.path = Hex("20 04 24 01 2C 66 2C 98");
  EXPECT_EQ(card.Open(params)[2], 0x00);
  EXPECT_EQ(card.io.last_requested, (IoRequestedSizes{10, 12}));
  EXPECT_EQ(card.Take().size(), 20U + 12U);

  // Sizes the point does not take: refused with the connection size of the one it suggests.
  ConnectionCard other;
  params.o_to_t.size = 17;
  EXPECT_EQ(other.Open(params), Refused("27 01 16 00"));
  params.o_to_t.size = 16;
  params.t_to_o.size = 20;
  EXPECT_EQ(other.Open(params), Refused("28 01 12 00"));
  // A heartbeat asks for no data.
  OpenParams input = InputOnly(0x1337, 0x98);
  input.t_to_o.size = 10;
  input.t_to_o.type = ConnectionType::kMulticast;
  EXPECT_EQ(other.Open(input)[2], 0x00);
  EXPECT_EQ(other.io.last_requested, (IoRequestedSizes{0, 8}));
  // Joining a multicast production needs its size.
  OpenParams listen = ListenOnly(2);
  listen.path = Hex("20 04 24 01 2C C7 2C 98");
  listen.t_to_o.type = ConnectionType::kMulticast;
  listen.t_to_o.size = 14;
  Bytes expected = Refused("28 01 0A 00");
  expected[8] = 0x02;  // connection serial 2
  expected[9] = 0x00;
  EXPECT_EQ(other.Open(listen), expected);
  listen.t_to_o.size = 10;
  EXPECT_EQ(other.Open(listen)[2], 0x00);
}

TEST(CipConnectionManagerTest, RefusesPathSegments) {
  ConnectionCard card;
  const auto with_path = [](std::string_view path) {
    OpenParams params;
    params.path = Hex(path);
    return params;
  };
  EXPECT_EQ(card.Open(with_path("20 04 24 01 2C 64 91 02 41 42")), Refused("15 03", 5));
  EXPECT_EQ(card.Open(with_path("20 01 24 01")), Refused("15 03", 2));  // Identity: not connectable
  EXPECT_EQ(card.Open(with_path("02 01 20 04 24 01 2C 64 2C 96")), Refused("12 03", 5));
  EXPECT_EQ(card.Open(with_path("05 00 20 04 24 01 2C 64 2C 96")), Refused("11 03", 5));
  OpenParams explicit_params = test::ExplicitParams();
  explicit_params.path = Hex("20 02 24 02");
  EXPECT_EQ(card.Open(explicit_params), Refused("15 03", 2));
  EXPECT_EQ(card.cm.counters().open_format_rejects, 5);
}

TEST(CipConnectionManagerTest, RefusesFraming) {
  ConnectionCard card;
  Bytes request = test::ForwardOpenRequestBytes(OpenParams{});
  EXPECT_EQ(card.Ask(Bytes(request.begin(), request.begin() + 6 + 35)), Hex("D4 00 13 00"));
  EXPECT_EQ(card.Ask(Bytes(request.begin(), request.end() - 2)), Hex("D4 00 13 00 37 13 33 33 78 56 34 12 00 00"));
  request.push_back(0);
  EXPECT_EQ(card.Ask(request), Hex("D4 00 15 00 37 13 33 33 78 56 34 12 00 00"));
  EXPECT_EQ(card.cm.counters().open_requests, 3);
  EXPECT_EQ(card.cm.counters().open_format_rejects, 3);
}

TEST(CipConnectionManagerTest, RefusesListenOnlyWithoutProducerAndOverLimits) {
  ConnectionCard card;
  EXPECT_EQ(card.Open(ListenOnly(0x1337)), Refused("19 01"));
  // An input-only connection produces 150: listen-only connections may join it.
  ASSERT_EQ(card.Open(InputOnly(1))[2], 0x00);
  ASSERT_EQ(card.Open(ListenOnly(2))[2], 0x00);
  ASSERT_EQ(card.Open(InputOnly(3))[2], 0x00);
  ASSERT_EQ(card.Open(InputOnly(4))[2], 0x00);
  Bytes expected = Refused("1A 01");
  expected[6] = 0x05;  // connection serial 5
  expected[7] = 0x00;
  EXPECT_EQ(card.Open(InputOnly(5)), expected);  // four per point
  EXPECT_EQ(card.cm.counters().open_resource_rejects, 1);
}

TEST(CipConnectionManagerTest, OutOfConnections) {
  ConnectionManagerOptions options;
  options.max_connections_per_point = 16;
  ConnectionCard card(options);
  for (std::uint16_t serial = 1; serial <= 16; ++serial) {
    ASSERT_EQ(card.Open(InputOnly(serial, serial % 2 == 0 ? 0x96 : 0x97))[2], 0x00) << serial;
  }
  Bytes expected = Refused("13 01");
  expected[6] = 0x11;  // connection serial 17
  expected[7] = 0x00;
  EXPECT_EQ(card.Open(InputOnly(17)), expected);
  EXPECT_EQ(card.cm.ActiveConnections(), 16);
  EXPECT_EQ(card.Ask(Hex("0E 03 20 02 24 01 30 03")), Hex("8E 00 00 00 10 00"));
  EXPECT_EQ(card.cm.connection_pool(), (base::PoolStats{16, kMaxCipConnections, 16, 1}));
  EXPECT_EQ(card.cm.production_pool(), (base::PoolStats{16, kMaxCipConnections, 16, 0}));
  // Forward_Close of every one gives every entry and every production back.
  for (std::uint16_t serial = 1; serial <= 16; ++serial) {
    ASSERT_EQ(card.Ask(test::ForwardCloseRequestBytes({serial, 0x3333, 0x12345678}))[2], 0x00) << serial;
  }
  EXPECT_EQ(card.cm.connection_pool(), (base::PoolStats{0, kMaxCipConnections, 16, 1}));
  EXPECT_EQ(card.cm.production_pool(), (base::PoolStats{0, kMaxCipConnections, 16, 0}));
}

TEST(CipConnectionManagerTest, ExplicitConnectionLimit) {
  ConnectionCard card;
  for (std::uint16_t serial = 1; serial <= 6; ++serial) {
    OpenParams params = test::ExplicitParams();
    params.triad.connection_serial = serial;
    ASSERT_EQ(card.Open(params)[2], 0x00) << serial;
  }
  OpenParams seventh = test::ExplicitParams();
  EXPECT_EQ(card.Open(seventh), Refused("1A 01"));
  EXPECT_EQ(card.cm.ActiveConnections(), 6);
  EXPECT_EQ(card.cm.explicit_pool(), (base::PoolStats{6, kMaxExplicitConnections, 6, 1}));
  EXPECT_EQ(card.cm.connection_pool(), (base::PoolStats{6, kMaxCipConnections, 6, 0}));
  ASSERT_EQ(card.Ask(test::ForwardCloseRequestBytes({2, 0x3333, 0x12345678}))[2], 0x00);
  EXPECT_EQ(card.cm.explicit_pool(), (base::PoolStats{5, kMaxExplicitConnections, 6, 1}));
  EXPECT_EQ(card.Open(seventh)[2], 0x00);  // the freed reply store serves the next one
  EXPECT_EQ(card.cm.explicit_pool(), (base::PoolStats{6, kMaxExplicitConnections, 6, 1}));
}

TEST(CipConnectionManagerTest, ForwardClose) {
  ConnectionCard card;
  ASSERT_EQ(card.Open()[2], 0x00);
  EXPECT_EQ(card.Ask(test::ForwardCloseRequestBytes({0x1337, 0x3333, 0x12345678})),
            Hex("CE 00 00 00 37 13 33 33 78 56 34 12 00 00"));
  EXPECT_EQ(card.cm.ActiveConnections(), 0);
  EXPECT_FALSE(card.cm.IsOwned(100));
  EXPECT_EQ(card.Ask(test::ForwardCloseRequestBytes({0x1337, 0x3333, 0x12345678})), Refused("07 01", 0, 0xCE));
  EXPECT_EQ(card.cm.IoStatus(), ExtendedDeviceStatus::kNoIoConnections);
  // The triad is free again.
  EXPECT_EQ(card.Open()[2], 0x00);
  // Framing.
  const Bytes close = test::ForwardCloseRequestBytes({0x1337, 0x3333, 0x12345678});
  EXPECT_EQ(card.Ask(Bytes(close.begin(), close.begin() + 10)), Hex("CE 00 13 00"));
  EXPECT_EQ(card.Ask(Bytes(close.begin(), close.end() - 2)), Hex("CE 00 13 00 37 13 33 33 78 56 34 12 00 00"));
  EXPECT_EQ(card.cm.counters().close_requests, 4);
  EXPECT_EQ(card.cm.counters().close_format_rejects, 2);
  EXPECT_EQ(card.cm.counters().close_other_rejects, 1);
  EXPECT_EQ(card.Ask(Hex("0E 03 20 06 24 01 30 05")), Hex("8E 00 00 00 04 00"));
}

TEST(CipConnectionManagerTest, ForwardCloseOnlyFromTheOriginator) {
  ConnectionCard card;
  ASSERT_EQ(card.Open()[2], 0x00);
  Bytes reply(64);
  RequestContext stranger;
  stranger.peer = Ipv4Endpoint{base::Ipv4Address(0x0A000299), 50000};
  const Bytes close = test::ForwardCloseRequestBytes({0x1337, 0x3333, 0x12345678});
  reply.resize(card.card.cip.router().HandleUnconnected(close, stranger, reply));
  EXPECT_EQ(reply, Refused("07 01", 0, 0xCE));
  EXPECT_EQ(card.cm.ActiveConnections(), 1);
}

TEST(CipConnectionManagerTest, ClosingTheProducerClosesItsListeners) {
  ConnectionCard card;
  ASSERT_EQ(card.Open()[2], 0x00);  // exclusive owner 100 -> 150
  ASSERT_EQ(card.Open(ListenOnly(2))[2], 0x00);
  ASSERT_EQ(card.Open(ListenOnly(3))[2], 0x00);
  ASSERT_EQ(card.Open(InputOnly(4, 0x97))[2], 0x00);  // another point: stays
  const int changes = card.events.changes;
  ASSERT_EQ(card.Ask(test::ForwardCloseRequestBytes({0x1337, 0x3333, 0x12345678}))[2], 0x00);
  EXPECT_EQ(card.cm.ActiveConnections(), 1);
  EXPECT_EQ(card.events.changes, changes + 1);
}

TEST(CipConnectionManagerTest, UnconnectedSendCarriesAForwardOpen) {
  ConnectionCard card;
  const Bytes open = test::ForwardOpenRequestBytes(OpenParams{});
  Bytes request = Hex("52 02 20 06 24 01 0A F0 00 00");
  request[8] = static_cast<std::uint8_t>(open.size());
  request.insert(request.end(), open.begin(), open.end());
  const Bytes route = Hex("01 00 01 00");
  request.insert(request.end(), route.begin(), route.end());
  EXPECT_EQ(
      card.Ask(request),
      Hex("D4 00 00 00 | 44 33 22 11 | 01 00 00 20 | 37 13 33 33 78 56 34 12 | 10 27 00 00 | 10 27 00 00 | 00 00"));
}

}  // namespace
}  // namespace cip
