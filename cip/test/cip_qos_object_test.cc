// QoS object 0x48 (CIP Vol. 2 §5-7) through a CipDevice on fakes: every attribute with exact bytes, the
// checks of Set_Attribute_Single, what reaches the store; the DSCP of each connection priority and the
// 802.1Q priority tag the card's output path inserts.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "cip/qos_object.h"
#include "cip_fakes.h"

namespace cip {
namespace {

using test::Bytes;
using test::Hex;

Bytes GetQos(std::uint8_t attribute) { return {0x0E, 0x03, 0x20, 0x48, 0x24, 0x01, 0x30, attribute}; }
Bytes SetQos(std::uint8_t attribute, const Bytes& value) {
  return test::Concat({0x10, 0x03, 0x20, 0x48, 0x24, 0x01, 0x30, attribute}, value);
}

const Bytes kSetOk = Hex("90 00 00 00");

class CipQosTest : public ::testing::Test {
 protected:
  CipQosTest() { EXPECT_TRUE(card_.cip.objects().Register(object_.object()).ok()); }

  test::FakeCard card_;
  test::FakeQos qos_;
  QosObject object_{qos_};
};

TEST_F(CipQosTest, EveryAttributeHasTheSpecificationsDefault) {
  const std::vector<std::uint8_t> defaults = {0, 59, 47, 55, 47, 43, 31, 27};
  for (std::uint8_t id = 1; id <= 8; ++id) {
    EXPECT_EQ(card_.Ask(GetQos(id)), test::Concat(Hex("8E 00 00 00"), {defaults[id - 1U]})) << int{id};
  }
  EXPECT_EQ(card_.Ask(Hex("01 02 20 48 24 01")), Hex("81 00 00 00 00 3B 2F 37 2F 2B 1F 1B"));
}

TEST_F(CipQosTest, ClassAttributes) {
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 48 24 00 30 01")), Hex("8E 00 00 00 01 00"));
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 48 24 00 30 04")), Hex("8E 00 00 00 03 00 01 00 02 00 03 00"));
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 48 24 00 30 07")), Hex("8E 00 00 00 08 00"));
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 48 24 00 30 08")), Hex("8E 00 14 00"));
  EXPECT_EQ(card_.Ask(Hex("01 02 20 48 24 00")),
            Hex("81 00 00 00 01 00 01 00 01 00 03 00 01 00 02 00 03 00 00 00 07 00 08 00"));
  EXPECT_EQ(card_.Ask(Hex("10 03 20 48 24 00 30 01 02 00")), Hex("90 00 08 00"));
}

TEST_F(CipQosTest, SetStoresAndGetReadsTheStoredValueBack) {
  EXPECT_EQ(card_.Ask(SetQos(8, {0x0A})), kSetOk);
  EXPECT_EQ(card_.Ask(SetQos(5, {0x14})), kSetOk);
  EXPECT_EQ(card_.Ask(SetQos(1, {0x01})), kSetOk);
  EXPECT_EQ(card_.Ask(SetQos(2, {0x3F})), kSetOk);
  EXPECT_EQ(card_.Ask(SetQos(7, {0x00})), kSetOk);
  EXPECT_EQ(qos_.stores, 5);
  EXPECT_EQ(card_.Ask(GetQos(8)), Hex("8E 00 00 00 0A"));
  EXPECT_EQ(card_.Ask(Hex("01 02 20 48 24 01")), Hex("81 00 00 00 01 3F 2F 37 14 2B 00 0A"));
}

TEST_F(CipQosTest, BadValuesAreRefusedWithExactCodesAndNothingIsStored) {
  EXPECT_EQ(card_.Ask(SetQos(4, {0x40})), Hex("90 00 09 00"));  // DSCP 64: six bits only
  EXPECT_EQ(card_.Ask(SetQos(8, {0xFF})), Hex("90 00 09 00"));
  EXPECT_EQ(card_.Ask(SetQos(1, {0x02})), Hex("90 00 09 00"));  // tag enable: 0 or 1
  EXPECT_EQ(card_.Ask(SetQos(4, {})), Hex("90 00 13 00"));
  EXPECT_EQ(card_.Ask(SetQos(4, {0x20, 0x00})), Hex("90 00 15 00"));
  EXPECT_EQ(card_.Ask(SetQos(9, {0x01})), Hex("90 00 14 00"));
  EXPECT_EQ(card_.Ask(GetQos(9)), Hex("8E 00 14 00"));
  EXPECT_EQ(card_.Ask(GetQos(0)), Hex("8E 00 14 00"));
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 48 24 02 30 01")), Hex("8E 00 16 00"));
  EXPECT_EQ(card_.Ask(Hex("4C 03 20 48 24 01 30 01")), Hex("CC 00 08 00"));
  EXPECT_EQ(qos_.stores, 0);
  EXPECT_EQ(qos_.stored, QosSettings{});
}

TEST_F(CipQosTest, AStoreFailureIsAnsweredAndTheOldValueStays) {
  qos_.store_result = base::Internal();
  EXPECT_EQ(card_.Ask(SetQos(8, {0x0A})), Hex("90 00 19 00"));
  EXPECT_EQ(card_.Ask(GetQos(8)), Hex("8E 00 00 00 1B"));
}

TEST(QosDscp, EachConnectionPriorityHasItsAttribute) {
  QosSettings settings;
  EXPECT_EQ(DscpForPriority(settings, ConnectionPriority::kUrgent), 55);
  EXPECT_EQ(DscpForPriority(settings, ConnectionPriority::kScheduled), 47);
  EXPECT_EQ(DscpForPriority(settings, ConnectionPriority::kHigh), 43);
  EXPECT_EQ(DscpForPriority(settings, ConnectionPriority::kLow), 31);
  settings.values = {0, 1, 2, 3, 4, 5, 6, 7};
  EXPECT_EQ(DscpForPriority(settings, ConnectionPriority::kUrgent), 3);
  EXPECT_EQ(DscpForPriority(settings, ConnectionPriority::kLow), 6);
  EXPECT_EQ(TosOfDscp(47), 0xBC);
  EXPECT_EQ(TosOfDscp(27), 0x6C);
}

TEST(QosTag, PriorityOfEachClassAndNoneForUnmarkedTraffic) {
  const QosSettings settings;
  EXPECT_EQ(PriorityOfDscp(settings, 59), 7);
  EXPECT_EQ(PriorityOfDscp(settings, 55), 6);
  EXPECT_EQ(PriorityOfDscp(settings, 47), 5);
  EXPECT_EQ(PriorityOfDscp(settings, 43), 5);
  EXPECT_EQ(PriorityOfDscp(settings, 31), 3);
  EXPECT_EQ(PriorityOfDscp(settings, 27), 3);
  EXPECT_EQ(PriorityOfDscp(settings, 0), -1);
  EXPECT_EQ(PriorityOfDscp(settings, 46), -1);
  QosSettings shared;
  shared.values = {1, 0, 0, 10, 0, 0, 0, 10};  // urgent and explicit share 10: urgent wins; 0 is never tagged
  EXPECT_EQ(PriorityOfDscp(shared, 10), 6);
  EXPECT_EQ(PriorityOfDscp(shared, 0), -1);
}

// An Ethernet II frame with an IPv4 header whose TOS is `tos`, in a buffer with `spare` bytes after it.
std::vector<std::uint8_t> Ipv4Frame(std::uint8_t tos, std::size_t spare = 4) {
  std::vector<std::uint8_t> frame = Hex("02 00 00 00 00 01 02 00 00 00 00 02 08 00 45");
  frame.push_back(tos);
  for (std::uint8_t b : Hex("00 20 00 00 00 00 40 11 00 00 0A FE 00 02 0A FE 00 01 AA BB")) frame.push_back(b);
  frame.resize(frame.size() + spare, 0xEE);
  return frame;
}

TEST(QosTag, TaggedFrameHasTpidPriorityAndVlanZeroBeforeTheEtherType) {
  QosSettings settings;
  settings.values[0] = 1;
  std::vector<std::uint8_t> frame = Ipv4Frame(TosOfDscp(47));
  const std::size_t length = frame.size() - 4;
  ASSERT_EQ(InsertPriorityTag(settings, frame, length), length + 4);
  EXPECT_EQ(frame, Hex("02 00 00 00 00 01 02 00 00 00 00 02 | 81 00 A0 00 | 08 00 45 BC"
                       "00 20 00 00 00 00 40 11 00 00 0A FE 00 02 0A FE 00 01 AA BB"));
  frame = Ipv4Frame(TosOfDscp(27));
  ASSERT_EQ(InsertPriorityTag(settings, frame, length), length + 4);
  EXPECT_EQ(std::vector<std::uint8_t>(frame.begin() + 12, frame.begin() + 16), Hex("81 00 60 00"));
  frame = Ipv4Frame(TosOfDscp(55));
  ASSERT_EQ(InsertPriorityTag(settings, frame, length), length + 4);
  EXPECT_EQ(std::vector<std::uint8_t>(frame.begin() + 12, frame.begin() + 16), Hex("81 00 C0 00"));
}

TEST(QosTag, FramesThatAreNotTaggedStayAsTheyWere) {
  QosSettings on;
  on.values[0] = 1;
  const std::vector<std::uint8_t> marked = Ipv4Frame(TosOfDscp(47));
  const std::size_t length = marked.size() - 4;
  std::vector<std::uint8_t> frame = marked;
  EXPECT_EQ(InsertPriorityTag(QosSettings{}, frame, length), length);  // tagging off (the default)
  EXPECT_EQ(frame, marked);
  frame = Ipv4Frame(0);  // Modbus TCP, HTTP
  EXPECT_EQ(InsertPriorityTag(on, frame, length), length);
  EXPECT_EQ(frame, Ipv4Frame(0));
  frame = marked;
  frame[12] = 0x08;
  frame[13] = 0x06;  // ARP
  EXPECT_EQ(InsertPriorityTag(on, frame, length), length);
  frame = marked;
  EXPECT_EQ(InsertPriorityTag(on, std::span(frame).first(length + 3), length), length);  // no room
  EXPECT_EQ(frame, marked);
  EXPECT_EQ(InsertPriorityTag(on, frame, 15), 15U);        // cut before the TOS byte
  EXPECT_EQ(InsertPriorityTag(on, frame, 16), 20U);        // the TOS byte is the last one
  frame = marked;
  EXPECT_EQ(InsertPriorityTag(on, frame, frame.size() + 1), frame.size() + 1);  // length past the buffer
}

}  // namespace
}  // namespace cip
