// DLR frames (net/dlr_frame.h, docs/network.md "Ring (DLR)"): exact bytes of what a node sends, the
// parser on real layouts (tagged and untagged), and its refusals: not DLR, every truncation, wrong
// subtype/version/frame type/ring state, a Sign_On list longer than the frame.
#include "net/dlr_frame.h"

#include <gtest/gtest.h>

#include <array>
#include <vector>

namespace net {
namespace {

using Bytes = std::vector<std::uint8_t>;

// Documentation values: MAC 00-00-5E-00-53-xx (RFC 7042), addresses from 192.0.2.0/24 (RFC 5737).
constexpr base::MacAddress kOwnMac = {0x00, 0x00, 0x5E, 0x00, 0x53, 0x01};
constexpr base::MacAddress kSupervisorMac = {0x00, 0x00, 0x5E, 0x00, 0x53, 0x10};
constexpr base::Ipv4Address kOwnIp(192, 0, 2, 10);

Bytes Padded(Bytes bytes, std::size_t size = 60) {
  bytes.resize(size, 0x00);
  return bytes;
}

// A beacon of supervisor 192.0.2.1 (precedence 5, interval 400 µs, timeout 1800 µs, sequence 42) sent
// out of its port 1, tagged with priority 7 as supervisors send them: 18 + 42 = 60 bytes.
const Bytes kBeacon = Padded({
    0x01, 0x21, 0x6C, 0x00, 0x00, 0x01, 0x00, 0x00, 0x5E, 0x00, 0x53, 0x10,  // group 01, supervisor
    0x81, 0x00, 0xE0, 0x00, 0x80, 0xE1,                                      // tag PCP 7 VID 0, 0x80E1
    0x02, 0x01, 0x01, 0x01, 0xC0, 0x00, 0x02, 0x01, 0x00, 0x00, 0x00, 0x2A,  // common header
    0x01, 0x05, 0x00, 0x00, 0x01, 0x90, 0x00, 0x00, 0x07, 0x08,              // normal, 5, 400, 1800
});

TEST(DlrFrame, TaggedBeacon_AllFields) {
  const auto frame = ParseDlrFrame(kBeacon);
  ASSERT_TRUE(frame.ok());
  EXPECT_EQ(frame->destination, kDlrBeaconMac);
  EXPECT_EQ(frame->source, kSupervisorMac);
  EXPECT_TRUE(frame->tagged);
  EXPECT_EQ(frame->tag_control, 0xE000);
  EXPECT_EQ(frame->pdu_offset, 18U);
  EXPECT_EQ(frame->type, DlrFrameType::kBeacon);
  EXPECT_EQ(frame->source_port, 1);
  EXPECT_EQ(frame->source_ip, base::Ipv4Address(192, 0, 2, 1));
  EXPECT_EQ(frame->sequence_id, 42U);
  EXPECT_EQ(frame->ring_state, DlrRingState::kNormal);
  EXPECT_EQ(frame->precedence, 5);
  EXPECT_EQ(frame->interval_us, 400U);
  EXPECT_EQ(frame->timeout_us, 1800U);
}

TEST(DlrFrame, UntaggedBeacon_SameFields) {
  Bytes untagged(kBeacon.begin(), kBeacon.begin() + 12);
  untagged.insert(untagged.end(), kBeacon.begin() + 16, kBeacon.end());
  const auto frame = ParseDlrFrame(untagged);
  ASSERT_TRUE(frame.ok());
  EXPECT_FALSE(frame->tagged);
  EXPECT_EQ(frame->pdu_offset, 14U);
  EXPECT_EQ(frame->ring_state, DlrRingState::kNormal);
  EXPECT_EQ(frame->timeout_us, 1800U);
}

TEST(DlrFrame, OtherEtherType_NotFound) {
  Bytes ipv4 = kBeacon;
  ipv4[16] = 0x08;
  ipv4[17] = 0x00;
  EXPECT_EQ(ParseDlrFrame(ipv4).status(), base::NotFound());
  EXPECT_EQ(ParseDlrFrame(Bytes(13, 0)).status(), base::NotFound());
}

TEST(DlrFrame, EveryTruncationOfABeacon_Refused) {
  // Before the EtherType is complete the frame is not known to be DLR; after it, it is short.
  for (std::size_t size = 0; size < 18; ++size) {
    EXPECT_EQ(ParseDlrFrame(std::span(kBeacon).first(size)).status(), base::NotFound()) << size;
  }
  for (std::size_t size = 18; size < 18 + 22; ++size) {
    EXPECT_EQ(ParseDlrFrame(std::span(kBeacon).first(size)).status(), base::OutOfRange()) << size;
  }
  // The reserved tail is not required (a TAP delivers frames unpadded).
  EXPECT_TRUE(ParseDlrFrame(std::span(kBeacon).first(18 + 22)).ok());
}

TEST(DlrFrame, WrongSubtypeVersionTypeOrRingState_InvalidArgument) {
  for (const auto& [offset, value] : std::array<std::pair<std::size_t, std::uint8_t>, 7>{{
           {18, 0x01},  // subtype
           {19, 0x00},  // version 0
           {19, 0x02},  // version 2
           {20, 0x00},  // frame type 0
           {20, 0x0B},  // frame type 11
           {30, 0x00},  // ring state 0
           {30, 0x03},  // ring state 3
       }}) {
    Bytes bad = kBeacon;
    bad[offset] = value;
    EXPECT_EQ(ParseDlrFrame(bad).status(), base::InvalidArgument()) << offset << " " << int{value};
  }
}

// A Sign_On from the supervisor with itself as the first entry.
const Bytes kSignOn = Padded({
    0x01, 0x21, 0x6C, 0x00, 0x00, 0x02, 0x00, 0x00, 0x5E, 0x00, 0x53, 0x10, 0x81, 0x00, 0xE0, 0x00, 0x80, 0xE1,
    0x02, 0x01, 0x07, 0x01, 0xC0, 0x00, 0x02, 0x01, 0x00, 0x00, 0x00, 0x07,  // Sign_On, seq 7
    0x00, 0x01,                                                              // 1 node
    0x00, 0x00, 0x5E, 0x00, 0x53, 0x10, 0xC0, 0x00, 0x02, 0x01,              // supervisor
});

TEST(DlrFrame, SignOn_ListRead) {
  const auto frame = ParseDlrFrame(kSignOn);
  ASSERT_TRUE(frame.ok());
  EXPECT_EQ(frame->type, DlrFrameType::kSignOn);
  EXPECT_EQ(frame->sign_on_nodes, 1);
  const DlrNode node = SignOnNode(kSignOn, *frame, 0);
  EXPECT_EQ(node.mac, kSupervisorMac);
  EXPECT_EQ(node.ip, base::Ipv4Address(192, 0, 2, 1));
}

TEST(DlrFrame, SignOnCountBeyondTheFrame_OutOfRange) {
  Bytes bad = kSignOn;
  bad[31] = 0x05;  // 5 nodes = 50 bytes, 28 remain
  EXPECT_EQ(ParseDlrFrame(bad).status(), base::OutOfRange());
  bad[30] = 0xFF;
  bad[31] = 0xFF;
  EXPECT_EQ(ParseDlrFrame(bad).status(), base::OutOfRange());
}

TEST(DlrFrame, OtherTypes_Fields) {
  Bytes flush = kBeacon;
  flush[0x05] = 0x03;
  flush[20] = 0x09;  // Flush_Tables
  flush[30] = 0x01;  // learning update enable
  auto frame = ParseDlrFrame(flush);
  ASSERT_TRUE(frame.ok());
  EXPECT_EQ(frame->type, DlrFrameType::kFlushTables);
  EXPECT_TRUE(frame->learning_update_enable);

  Bytes status = kBeacon;
  status[20] = 0x04;
  status[30] = 0x82;  // Neighbor_Status, port 2 active
  frame = ParseDlrFrame(status);
  ASSERT_TRUE(frame.ok());
  EXPECT_EQ(frame->link_status, (DlrLinkStatus{false, true, true}));

  Bytes response = kBeacon;
  response[20] = 0x03;
  response[30] = 0x02;
  frame = ParseDlrFrame(response);
  ASSERT_TRUE(frame.ok());
  EXPECT_EQ(frame->request_source_port, 2);

  Bytes advertise = kBeacon;
  advertise[20] = 0x08;
  advertise[30] = 0x02;  // active normal
  advertise[40] = 0x01;  // learning update enable
  frame = ParseDlrFrame(advertise);
  ASSERT_TRUE(frame.ok());
  EXPECT_EQ(frame->gateway_state, 2);
  EXPECT_EQ(frame->precedence, 5);
  EXPECT_EQ(frame->interval_us, 400U);
  EXPECT_TRUE(frame->learning_update_enable);
}

DlrOrigin Origin(const base::MacAddress& destination, std::uint8_t port, std::uint32_t sequence) {
  DlrOrigin origin;
  origin.destination = destination;
  origin.source = kOwnMac;
  origin.source_port = port;
  origin.source_ip = kOwnIp;
  origin.sequence_id = sequence;
  return origin;
}

Bytes Built(base::Result<std::size_t> length, const std::array<std::uint8_t, 1518>& buffer) {
  EXPECT_TRUE(length.ok());
  return Bytes(buffer.begin(), buffer.begin() + static_cast<std::ptrdiff_t>(*length));
}

TEST(DlrFrame, NeighborCheckResponse_ExactBytes) {
  std::array<std::uint8_t, 1518> buffer{};
  const Bytes frame =
      Built(BuildNeighborCheckResponse(Origin(kDlrNeighborCheckMac, 2, 0x01020304), 1, buffer), buffer);
  EXPECT_EQ(frame, Padded({
                       0x01, 0x21, 0x6C, 0x00, 0x00, 0x02, 0x00, 0x00, 0x5E, 0x00, 0x53, 0x01,
                       0x81, 0x00, 0xE0, 0x00, 0x80, 0xE1,
                       0x02, 0x01, 0x03, 0x02, 0xC0, 0x00, 0x02, 0x0A, 0x01, 0x02, 0x03, 0x04,
                       0x01,  // request source port
                   }));
}

TEST(DlrFrame, NeighborCheckRequest_ExactBytes) {
  std::array<std::uint8_t, 1518> buffer{};
  const Bytes frame = Built(BuildNeighborCheckRequest(Origin(kDlrNeighborCheckMac, 1, 9), buffer), buffer);
  EXPECT_EQ(frame, Padded({
                       0x01, 0x21, 0x6C, 0x00, 0x00, 0x02, 0x00, 0x00, 0x5E, 0x00, 0x53, 0x01,
                       0x81, 0x00, 0xE0, 0x00, 0x80, 0xE1,
                       0x02, 0x01, 0x02, 0x01, 0xC0, 0x00, 0x02, 0x0A, 0x00, 0x00, 0x00, 0x09,
                   }));
}

TEST(DlrFrame, LinkStatus_ExactBytes) {
  std::array<std::uint8_t, 1518> buffer{};
  const Bytes frame =
      Built(BuildLinkStatus(Origin(kSupervisorMac, 0, 3), DlrLinkStatus{true, false, false}, buffer), buffer);
  EXPECT_EQ(frame, Padded({
                       0x00, 0x00, 0x5E, 0x00, 0x53, 0x10, 0x00, 0x00, 0x5E, 0x00, 0x53, 0x01,
                       0x81, 0x00, 0xE0, 0x00, 0x80, 0xE1,
                       0x02, 0x01, 0x04, 0x00, 0xC0, 0x00, 0x02, 0x0A, 0x00, 0x00, 0x00, 0x03,
                       0x01,  // Link_Status, port 1 active, port 2 not
                   }));
}

TEST(DlrFrame, LearningUpdate_UntaggedSixtyBytes) {
  std::array<std::uint8_t, 1518> buffer{};
  const Bytes frame = Built(BuildLearningUpdate(Origin(kDlrLearningUpdateMac, 0, 5), buffer), buffer);
  EXPECT_EQ(frame, Padded({
                       0x01, 0x21, 0x6C, 0x00, 0x00, 0x05, 0x00, 0x00, 0x5E, 0x00, 0x53, 0x01, 0x80, 0xE1,
                       0x02, 0x01, 0x0A, 0x00, 0xC0, 0x00, 0x02, 0x0A, 0x00, 0x00, 0x00, 0x05,
                   }));
}

TEST(DlrFrame, BuilderBufferTooSmall_ResourceExhausted) {
  std::array<std::uint8_t, 59> small{};
  EXPECT_EQ(BuildNeighborCheckRequest(Origin(kDlrNeighborCheckMac, 1, 1), small).status(),
            base::ResourceExhausted());
  EXPECT_EQ(BuildLearningUpdate(Origin(kDlrLearningUpdateMac, 0, 1), small).status(), base::ResourceExhausted());
}

TEST(DlrFrame, SignOnAppended_ExactBytes) {
  const auto parsed = ParseDlrFrame(kSignOn);
  ASSERT_TRUE(parsed.ok());
  std::array<std::uint8_t, 1518> buffer{};
  const Bytes frame =
      Built(BuildSignOn(kSignOn, *parsed, kDlrNeighborCheckMac, DlrNode{kOwnMac, kOwnIp}, true, buffer), buffer);
  EXPECT_EQ(frame, Padded({
                       0x01, 0x21, 0x6C, 0x00, 0x00, 0x02, 0x00, 0x00, 0x5E, 0x00, 0x53, 0x01,  // from us
                       0x81, 0x00, 0xE0, 0x00, 0x80, 0xE1,
                       0x02, 0x01, 0x07, 0x01, 0xC0, 0x00, 0x02, 0x01, 0x00, 0x00, 0x00, 0x07,  // as received
                       0x00, 0x02,                                                              // 2 nodes
                       0x00, 0x00, 0x5E, 0x00, 0x53, 0x10, 0xC0, 0x00, 0x02, 0x01,
                       0x00, 0x00, 0x5E, 0x00, 0x53, 0x01, 0xC0, 0x00, 0x02, 0x0A,              // us
                   }));
  const auto again = ParseDlrFrame(frame);
  ASSERT_TRUE(again.ok());
  EXPECT_EQ(again->sign_on_nodes, 2);
  EXPECT_EQ(SignOnNode(frame, *again, 1).mac, kOwnMac);
}

TEST(DlrFrame, SignOnList_FullAtTheMtu) {
  // 148 entries fill 12 + 2 + 1480 = 1494 bytes of the 1500: a 149th (1504) does not fit.
  EXPECT_TRUE(SignOnHasRoom(147));
  EXPECT_FALSE(SignOnHasRoom(148));
  Bytes full(18 + 14 + 148 * 10, 0x00);
  std::copy(kSignOn.begin(), kSignOn.begin() + 30, full.begin());
  full[30] = 0x00;
  full[31] = 148;
  const auto parsed = ParseDlrFrame(full);
  ASSERT_TRUE(parsed.ok());
  std::array<std::uint8_t, 1518> buffer{};
  EXPECT_EQ(BuildSignOn(full, *parsed, kDlrNeighborCheckMac, DlrNode{kOwnMac, kOwnIp}, true, buffer).status(),
            base::ResourceExhausted());
  const auto as_is = BuildSignOn(full, *parsed, kSupervisorMac, DlrNode{kOwnMac, kOwnIp}, false, buffer);
  ASSERT_TRUE(as_is.ok());
  EXPECT_EQ(*as_is, full.size());
  EXPECT_EQ(Bytes(buffer.begin(), buffer.begin() + 6), Bytes(kSupervisorMac.begin(), kSupervisorMac.end()));
}

}  // namespace
}  // namespace net
