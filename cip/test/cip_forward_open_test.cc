// Forward_Open / Large_Forward_Open / Forward_Close codecs, connection paths, electronic keys and the
// reply encoders, with the exact bytes of every layout.
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <vector>

#include "cip/forward_open.h"
#include "cip/io_connection.h"
#include "cip/message_router.h"
#include "cip_test_support.h"

namespace cip {
namespace {

using test::Bytes;
using test::Hex;
using test::Of;

// Exclusive owner 1 / 100 / 150, electronic key 377 / 2 / 32000 / 1.8, O->T 14 bytes, T->O 8 bytes,
// 10 ms both ways, multiplier 1 (x8), class 1 cyclic.
const Bytes kForwardOpen =
    Hex("0A 0E | 00 00 00 00 | 01 00 00 20 | 37 13 | 33 33 | 78 56 34 12 | 01 | 00 00 00 |"
        "10 27 00 00 | 0E 48 | 10 27 00 00 | 08 48 | 01 | 09 |"
        "34 04 79 01 02 00 00 7D 01 08 | 20 04 24 01 2C 64 2C 96");

TEST(CipForwardOpenTest, DecodesForwardOpen) {
  const Decoded<ForwardOpenRequest> decoded = DecodeForwardOpen(kForwardOpen, false);
  ASSERT_EQ(decoded.framing, RequestFraming::kOk);
  const ForwardOpenRequest& request = decoded.request;
  EXPECT_FALSE(request.large);
  EXPECT_EQ(request.priority_tick, 0x0A);
  EXPECT_EQ(request.timeout_ticks, 0x0E);
  EXPECT_EQ(request.o_to_t_connection_id, 0U);
  EXPECT_EQ(request.t_to_o_connection_id, 0x20000001U);
  EXPECT_EQ(request.triad, (ConnectionTriad{0x1337, 0x3333, 0x12345678}));
  EXPECT_EQ(request.timeout_multiplier, 1);
  EXPECT_EQ(request.o_to_t_rpi, 10000U);
  EXPECT_EQ(request.o_to_t, (NetworkConnectionParameters{14, false, ConnectionPriority::kScheduled,
                                                         ConnectionType::kPointToPoint, false}));
  EXPECT_EQ(request.t_to_o_rpi, 10000U);
  EXPECT_EQ(request.t_to_o.size, 8);
  EXPECT_EQ(request.transport, (TransportClassTrigger{false, kTriggerCyclic, 1}));
  EXPECT_EQ(Of(request.connection_path), Hex("34 04 79 01 02 00 00 7D 01 08 20 04 24 01 2C 64 2C 96"));
}

TEST(CipForwardOpenTest, DecodesLargeForwardOpenWith32BitParameters) {
  const Bytes large =
      Hex("0A 0E | 00 00 00 00 | 01 00 00 20 | 37 13 | 33 33 | 78 56 34 12 | 03 | 00 00 00 |"
          "D0 07 00 00 | 0E 00 00 48 | D0 07 00 00 | 08 02 00 2E | 01 | 04 |"
          "20 04 24 01 2C 64 2C 96");
  const Decoded<ForwardOpenRequest> decoded = DecodeForwardOpen(large, true);
  ASSERT_EQ(decoded.framing, RequestFraming::kOk);
  EXPECT_TRUE(decoded.request.large);
  EXPECT_EQ(decoded.request.o_to_t_rpi, 2000U);
  EXPECT_EQ(decoded.request.o_to_t, (NetworkConnectionParameters{14, false, ConnectionPriority::kScheduled,
                                                                 ConnectionType::kPointToPoint, false}));
  // 0x2E000208: multicast, urgent, variable, 520 bytes (more than a Forward_Open's 9 bits hold).
  EXPECT_EQ(decoded.request.t_to_o,
            (NetworkConnectionParameters{520, true, ConnectionPriority::kUrgent, ConnectionType::kMulticast, false}));
  EXPECT_EQ(decoded.request.timeout_multiplier, 3);
  EXPECT_EQ(decoded.request.connection_path.size(), 8U);

  // The same bytes as a regular Forward_Open are 4 bytes off: the path size byte lands elsewhere.
  EXPECT_NE(DecodeForwardOpen(large, false).framing, RequestFraming::kOk);
}

TEST(CipForwardOpenTest, EncodeDecodeRoundTrip) {
  const Decoded<ForwardOpenRequest> decoded = DecodeForwardOpen(kForwardOpen, false);
  std::array<std::uint8_t, 128> buffer{};
  base::ByteWriter out(buffer);
  EncodeForwardOpen(decoded.request, out);
  ASSERT_TRUE(out.ok());
  EXPECT_EQ(Of(out.written()), kForwardOpen);

  ForwardOpenRequest large = decoded.request;
  large.large = true;
  large.t_to_o.size = 600;
  base::ByteWriter large_out(buffer);
  EncodeForwardOpen(large, large_out);
  const Decoded<ForwardOpenRequest> again = DecodeForwardOpen(large_out.written(), true);
  ASSERT_EQ(again.framing, RequestFraming::kOk);
  EXPECT_EQ(again.request.t_to_o.size, 600);
  EXPECT_EQ(again.request.triad, large.triad);
}

TEST(CipForwardOpenTest, Framing) {
  // 35 bytes: the path size byte is missing.
  EXPECT_EQ(DecodeForwardOpen(Bytes(kForwardOpen.begin(), kForwardOpen.begin() + 35), false).framing,
            RequestFraming::kFixedPartShort);
  EXPECT_EQ(DecodeForwardOpen(Bytes(kForwardOpen.begin(), kForwardOpen.begin() + 39), true).framing,
            RequestFraming::kFixedPartShort);
  // The path says 9 words, one byte is missing: the triad is still there to be echoed.
  const Decoded<ForwardOpenRequest> cut = DecodeForwardOpen(Bytes(kForwardOpen.begin(), kForwardOpen.end() - 1), false);
  EXPECT_EQ(cut.framing, RequestFraming::kPathShort);
  EXPECT_EQ(cut.request.triad.connection_serial, 0x1337);
  Bytes longer = kForwardOpen;
  longer.push_back(0);
  EXPECT_EQ(DecodeForwardOpen(longer, false).framing, RequestFraming::kExtraData);
  EXPECT_EQ(DecodeForwardOpen({}, false).framing, RequestFraming::kFixedPartShort);
}

TEST(CipForwardOpenTest, DecodesForwardClose) {
  const Bytes close = Hex("0A 0E | 37 13 | 33 33 | 78 56 34 12 | 04 | 00 | 20 04 24 01 2C 64 2C 96");
  const Decoded<ForwardCloseRequest> decoded = DecodeForwardClose(close);
  ASSERT_EQ(decoded.framing, RequestFraming::kOk);
  EXPECT_EQ(decoded.request.triad, (ConnectionTriad{0x1337, 0x3333, 0x12345678}));
  EXPECT_EQ(decoded.request.connection_path.size(), 8U);
  std::array<std::uint8_t, 64> buffer{};
  base::ByteWriter out(buffer);
  EncodeForwardClose(decoded.request, out);
  EXPECT_EQ(Of(out.written()), close);

  EXPECT_EQ(DecodeForwardClose(Hex("0A 0E 37 13 33 33 78 56 34 12 04")).framing, RequestFraming::kFixedPartShort);
  EXPECT_EQ(DecodeForwardClose(Hex("0A 0E 37 13 33 33 78 56 34 12 04 00 20 04")).framing, RequestFraming::kPathShort);
  EXPECT_EQ(DecodeForwardClose(Hex("0A 0E 37 13 33 33 78 56 34 12 00 00 00")).framing, RequestFraming::kExtraData);
}

TEST(CipForwardOpenTest, NetworkConnectionParameterBits) {
  EXPECT_EQ(DecodeNetworkParameters16(0x8000).redundant_owner, true);
  EXPECT_EQ(DecodeNetworkParameters16(0x0000).type, ConnectionType::kNull);
  EXPECT_EQ(DecodeNetworkParameters16(0x2000).type, ConnectionType::kMulticast);
  EXPECT_EQ(DecodeNetworkParameters16(0x4000).type, ConnectionType::kPointToPoint);
  EXPECT_EQ(DecodeNetworkParameters16(0x6000).type, ConnectionType::kReserved);
  EXPECT_EQ(DecodeNetworkParameters16(0x0400).priority, ConnectionPriority::kHigh);
  EXPECT_EQ(DecodeNetworkParameters16(0x0C00).priority, ConnectionPriority::kUrgent);
  EXPECT_EQ(DecodeNetworkParameters16(0x0200).variable, true);
  EXPECT_EQ(DecodeNetworkParameters16(0x01FF).size, 511);
  EXPECT_EQ(DecodeNetworkParameters16(0x1000), NetworkConnectionParameters{});  // bit 12 reserved

  EXPECT_EQ(DecodeNetworkParameters32(0x80000000U).redundant_owner, true);
  EXPECT_EQ(DecodeNetworkParameters32(0x20000000U).type, ConnectionType::kMulticast);
  EXPECT_EQ(DecodeNetworkParameters32(0x04000000U).priority, ConnectionPriority::kHigh);
  EXPECT_EQ(DecodeNetworkParameters32(0x02000000U).variable, true);
  EXPECT_EQ(DecodeNetworkParameters32(0x0000FFFFU).size, 0xFFFF);
  EXPECT_EQ(DecodeNetworkParameters32(0x01FF0000U), NetworkConnectionParameters{});  // bits 16-24 reserved

  const NetworkConnectionParameters all{300, true, ConnectionPriority::kUrgent, ConnectionType::kMulticast, true};
  EXPECT_EQ(EncodeNetworkParameters16(all), 0xAF2C);
  EXPECT_EQ(EncodeNetworkParameters32(all), 0xAE00012CU);
  EXPECT_EQ(DecodeNetworkParameters16(EncodeNetworkParameters16(all)), all);
  EXPECT_EQ(DecodeNetworkParameters32(EncodeNetworkParameters32(all)), all);
}

TEST(CipForwardOpenTest, TransportClassTriggerBits) {
  EXPECT_EQ(DecodeTransportClassTrigger(0x01), (TransportClassTrigger{false, kTriggerCyclic, 1}));
  EXPECT_EQ(DecodeTransportClassTrigger(0xA3), (TransportClassTrigger{true, kTriggerApplicationObject, 3}));
  EXPECT_EQ(DecodeTransportClassTrigger(0x11), (TransportClassTrigger{false, kTriggerChangeOfState, 1}));
  EXPECT_EQ(DecodeTransportClassTrigger(0x7F), (TransportClassTrigger{false, 7, 15}));
  EXPECT_EQ(EncodeTransportClassTrigger(TransportClassTrigger{true, kTriggerApplicationObject, 3}), 0xA3);
}

TEST(CipForwardOpenTest, ConnectionPathWithKeyConfigurationPointsAndData) {
  const Bytes bytes = Hex("34 04 79 01 02 00 00 7D 01 08 20 04 24 02 2C 64 2C 96 80 02 AA BB CC DD");
  const ParsedConnectionPath parsed = ParseConnectionPath(bytes);
  ASSERT_EQ(parsed.extended, 0);
  const ConnectionPath& path = parsed.path;
  ASSERT_TRUE(path.key.has_value());
  EXPECT_EQ(path.key->vendor_id, 377);
  EXPECT_EQ(path.key->product_code, 32000);
  EXPECT_EQ(path.class_id, 4U);
  EXPECT_EQ(path.instance, 2U);
  ASSERT_EQ(path.point_count, 2U);
  EXPECT_EQ(path.points[0], 100U);
  EXPECT_EQ(path.points[1], 150U);
  EXPECT_TRUE(path.has_data);
  EXPECT_EQ(Of(path.data), Hex("AA BB CC DD"));
}

TEST(CipForwardOpenTest, ConnectionPathForms) {
  // Instance segments for the points, and full application paths repeating the class.
  ParsedConnectionPath parsed = ParseConnectionPath(Hex("20 04 24 01 24 64 24 96"));
  ASSERT_EQ(parsed.extended, 0);
  EXPECT_EQ(parsed.path.instance, 1U);
  EXPECT_EQ(parsed.path.point_count, 2U);
  parsed = ParseConnectionPath(Hex("20 04 24 01 20 04 2C 64 20 04 2C 96"));
  ASSERT_EQ(parsed.extended, 0);
  EXPECT_EQ(parsed.path.points[1], 150U);
  // No configuration: the first segment after the class is a connection point.
  parsed = ParseConnectionPath(Hex("20 04 2C 64 2C 96"));
  ASSERT_EQ(parsed.extended, 0);
  EXPECT_FALSE(parsed.path.instance.has_value());
  EXPECT_EQ(parsed.path.point_count, 2U);
  // 16-bit formats.
  parsed = ParseConnectionPath(Hex("21 00 04 00 25 00 01 00 2D 00 64 00 2D 00 96 00"));
  ASSERT_EQ(parsed.extended, 0);
  EXPECT_EQ(parsed.path.points[0], 100U);
  // A local route in front (port 1, slot 0), as Unconnected_Send accepts it.
  parsed = ParseConnectionPath(Hex("01 00 20 02 24 01"));
  ASSERT_EQ(parsed.extended, 0);
  EXPECT_EQ(parsed.path.class_id, 2U);
  // An empty data segment is configuration data of 0 bytes.
  const Bytes empty_data = Hex("20 04 24 01 2C 64 2C 96 80 00");
  parsed = ParseConnectionPath(empty_data);
  ASSERT_EQ(parsed.extended, 0);
  EXPECT_TRUE(parsed.path.has_data);
  EXPECT_TRUE(parsed.path.data.empty());
}

TEST(CipForwardOpenTest, ConnectionPathErrors) {
  EXPECT_EQ(ParseConnectionPath(Hex("01 05 20 04 24 01")).extended, kExtendedInvalidRouteNode);  // port 1 slot 5
  EXPECT_EQ(ParseConnectionPath(Hex("02 01 20 04 24 01")).extended, kExtendedInvalidRouteNode);  // port 2
  EXPECT_EQ(ParseConnectionPath(Hex("03 00 20 04 24 01")).extended, kExtendedInvalidRoutePort);  // port 3
  for (const char* path : {
           "",                                                                   // nothing
           "24 01 2C 64",                                                        // no class
           "20 04 24 01 2C 64 2C 96 2C 97",                                      // three points
           "20 04 24 01 2C 64 01 00",                                            // a port segment after the class
           "20 04 34 04 79 01 02 00 00 7D 01 08",                                // key after the class
           "34 04 00 00 00 00 00 00 00 00 34 04 00 00 00 00 00 00 00 00 20 04",  // two keys
           "20 04 24 01 80 00 2C 64",                                            // a segment after the data segment
           "20 04 20 02 24 01",                                                  // two classes
           "20 04 24 01 30 03",                                                  // attribute
           "20 04 24 01 2C 64 91 02 41 42",                                      // symbol
           "20 04 24 01 2C",                                                     // cut segment
           "20 04 24 01 80 04 00 00",                                            // data segment cut short
           "43 01 20 04 24 01",  // network segment (production inhibit time)
           "22 00 04 00 00 00 24 01 2C 64 2C 96",  // 32-bit class (reserved format)
       }) {
    EXPECT_EQ(ParseConnectionPath(Hex(path)).extended, kExtendedInvalidRouteSegment) << path;
  }
}

TEST(CipForwardOpenTest, ElectronicKey) {
  const DeviceKey card{377, 2, 32000, 1, 8};
  const auto key = [](std::uint16_t vendor, std::uint16_t type, std::uint16_t product, std::uint8_t major,
                      std::uint8_t minor) {
    return ElectronicKey{vendor, type, product, major, minor};
  };
  EXPECT_EQ(CheckElectronicKey(key(377, 2, 32000, 1, 8), card), 0);
  EXPECT_EQ(CheckElectronicKey(key(0, 0, 0, 0, 0), card), 0);  // zero key: anything
  EXPECT_EQ(CheckElectronicKey(key(377, 2, 32000, 1, 0), card), 0);
  EXPECT_EQ(CheckElectronicKey(key(1, 2, 32000, 1, 8), card), kExtendedVendorOrProductCode);
  EXPECT_EQ(CheckElectronicKey(key(377, 2, 32001, 1, 8), card), kExtendedVendorOrProductCode);
  EXPECT_EQ(CheckElectronicKey(key(377, 12, 32000, 1, 8), card), kExtendedDeviceType);
  EXPECT_EQ(CheckElectronicKey(key(377, 2, 32000, 2, 8), card), kExtendedRevision);
  EXPECT_EQ(CheckElectronicKey(key(377, 2, 32000, 1, 7), card), kExtendedRevision);
  EXPECT_EQ(CheckElectronicKey(key(377, 2, 32000, 0, 9), card), 0);  // major 0: any revision
  // Compatibility bit: same major, a minor from 1 up to the card's.
  EXPECT_EQ(CheckElectronicKey(key(377, 2, 32000, 0x81, 7), card), 0);
  EXPECT_EQ(CheckElectronicKey(key(377, 2, 32000, 0x81, 8), card), 0);
  EXPECT_EQ(CheckElectronicKey(key(377, 2, 32000, 0x81, 9), card), kExtendedRevision);
  EXPECT_EQ(CheckElectronicKey(key(377, 2, 32000, 0x81, 0), card), kExtendedRevision);
  EXPECT_EQ(CheckElectronicKey(key(377, 2, 32000, 0x82, 1), card), kExtendedRevision);
}

TEST(CipForwardOpenTest, SuccessReplies) {
  std::array<std::uint8_t, 64> buffer{};
  base::ByteWriter out(buffer);
  EncodeForwardOpenSuccess({0x11223344, 0x20000001, {0x1337, 0x3333, 0x12345678}, 10000, 2000}, out);
  EXPECT_EQ(Of(out.written()),
            Hex("44 33 22 11 | 01 00 00 20 | 37 13 33 33 78 56 34 12 | 10 27 00 00 | D0 07 00 00 | 00 00"));
  base::ByteWriter close(buffer);
  EncodeForwardCloseSuccess({0x1337, 0x3333, 0x12345678}, close);
  EXPECT_EQ(Of(close.written()), Hex("37 13 33 33 78 56 34 12 00 00"));
}

TEST(CipForwardOpenTest, FailureReplies) {
  const ConnectionTriad triad{0x1337, 0x3333, 0x12345678};
  std::array<std::uint8_t, 64> buffer{};
  {
    base::ByteWriter out(buffer);
    const ServiceStatus status =
        EncodeConnectionFailure(ConnectionFailure::Extended(kExtendedOwnershipConflict), triad, out);
    EXPECT_EQ(status.general, GeneralStatus::kConnectionFailure);
    EXPECT_TRUE(status.keep_reply_data);
    EXPECT_EQ(status.additional_words_in_data, 1);
    EXPECT_EQ(Of(out.written()), Hex("06 01 | 37 13 33 33 78 56 34 12 | 00 00"));
  }
  {
    base::ByteWriter out(buffer);
    const ServiceStatus status =
        EncodeConnectionFailure(ConnectionFailure::WithSize(kExtendedOtoTSize, 14), triad, out);
    EXPECT_EQ(status.additional_words_in_data, 2);
    EXPECT_EQ(Of(out.written()), Hex("27 01 0E 00 | 37 13 33 33 78 56 34 12 | 00 00"));
  }
  {
    base::ByteWriter out(buffer);
    const ServiceStatus status = EncodeConnectionFailure(
        ConnectionFailure::WithRpi(kExtendedRpiNotSupported, kRpiMinimumAcceptable, 1000, kRpiAcceptable, 10000), triad,
        out);
    EXPECT_EQ(status.additional_words_in_data, 6);
    EXPECT_EQ(Of(out.written()), Hex("11 01 | 02 00 | E8 03 00 00 | 10 27 00 00 | 37 13 33 33 78 56 34 12 | 00 00"));
  }
  {
    base::ByteWriter out(buffer);
    ConnectionFailure segment = ConnectionFailure::Extended(kExtendedInvalidRouteSegment);
    segment.remaining_path_words = 4;
    EncodeConnectionFailure(segment, triad, out);
    EXPECT_EQ(Of(out.written()), Hex("15 03 | 37 13 33 33 78 56 34 12 | 04 00"));
  }
  {
    base::ByteWriter out(buffer);
    const ServiceStatus status =
        EncodeConnectionFailure(ConnectionFailure::General(GeneralStatus::kNotEnoughData), triad, out);
    EXPECT_EQ(status.general, GeneralStatus::kNotEnoughData);
    EXPECT_EQ(status.additional_words_in_data, 0);
    EXPECT_EQ(Of(out.written()), Hex("37 13 33 33 78 56 34 12 00 00"));
  }
}

TEST(CipForwardOpenTest, IoDatagramCodecAndSequenceArithmetic) {
  std::array<std::uint8_t, 64> buffer{};
  base::ByteWriter out(buffer);
  EncodeIoDatagram(0x11223344, 7, 0x0102, Hex("01 00 00 00 AA BB"), out);
  EXPECT_EQ(Of(out.written()),
            Hex("02 00 | 02 80 08 00 44 33 22 11 07 00 00 00 | B1 00 08 00 02 01 01 00 00 00 AA BB"));
  const base::Result<ReceivedIoDatagram> parsed = ParseIoDatagram(out.written());
  ASSERT_TRUE(parsed.ok());
  EXPECT_EQ(parsed->connection_id, 0x11223344U);
  EXPECT_EQ(parsed->encapsulation_sequence, 7U);
  EXPECT_EQ(Of(parsed->data), Hex("02 01 01 00 00 00 AA BB"));
  // Connected address item instead of the sequenced one, one item, a cut item.
  EXPECT_FALSE(ParseIoDatagram(Hex("02 00 A1 00 04 00 44 33 22 11 B1 00 02 00 00 00")).ok());
  EXPECT_FALSE(ParseIoDatagram(Hex("01 00 02 80 08 00 44 33 22 11 07 00 00 00")).ok());
  EXPECT_FALSE(ParseIoDatagram(Hex("02 00 02 80 08 00 44 33 22 11 07 00 00 00 B1 00 08 00 02")).ok());

  EXPECT_TRUE(SequenceAfter16(1, 0));
  EXPECT_TRUE(SequenceAfter16(0, 0xFFFF));  // wraps
  EXPECT_FALSE(SequenceAfter16(5, 5));
  EXPECT_FALSE(SequenceAfter16(4, 5));
  EXPECT_TRUE(SequenceAfter32(0, 0xFFFFFFFFU));
  EXPECT_FALSE(SequenceAfter32(0x80000000U, 0));
  EXPECT_EQ(ConnectionTimeout(10000, 0), 40000U);
  EXPECT_EQ(ConnectionTimeout(10000, 7), 5120000U);
  EXPECT_EQ(ConnectionTimeout(0xFFFFFFFFU, 7), 0xFFFFFFFFULL * 512);
}

TEST(CipForwardOpenTest, ProductionSlots) {
  std::uint32_t missed = 0;
  EXPECT_EQ(NextProductionSlot(1000, 100, 1000, missed), 1100U);  // on time
  EXPECT_EQ(NextProductionSlot(1000, 100, 1099, missed), 1100U);  // late, but the next slot is ahead
  EXPECT_EQ(missed, 0U);
  EXPECT_EQ(NextProductionSlot(1000, 100, 1100, missed), 1200U);  // the next slot is now: skipped
  EXPECT_EQ(missed, 1U);
  EXPECT_EQ(NextProductionSlot(1000, 100, 1350, missed), 1400U);  // three slots passed
  EXPECT_EQ(missed, 4U);
}

}  // namespace
}  // namespace cip
