// The message router and the generic attribute services, against a small test object: request and
// reply format, the order of error checks, Multiple Service Packet and Unconnected_Send.
#include "cip/message_router.h"

#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <vector>

#include "cip_test_support.h"

namespace cip {
namespace {

using test::Bytes;
using test::Hex;
using test::Of;

// Class 0x70, two instances. Attribute 1 UINT (get), 2 USINT 0-10 (get/set), 3 UDINT (get, not part of
// Get_Attributes_All). Service 0x4B is object-specific and echoes its data.
constexpr std::array<std::uint16_t, 5> kTestClassAttributes = {1, 2, 3, 6, 7};
constexpr std::array<std::uint8_t, 2> kTestClassServices = {kServiceGetAttributesAll, kServiceGetAttributeSingle};
constexpr std::array<std::uint8_t, 4> kTestInstanceServices = {kServiceGetAttributesAll, kServiceGetAttributeSingle,
                                                               kServiceSetAttributeSingle, 0x4B};
constexpr ClassSpec kTestClass = {0x70, 2, kTestClassAttributes, {}, {}, 7, 3, kTestClassServices,
                                  kTestInstanceServices};
constexpr std::array<AttributeSpec, 3> kTestAttributes = {{
    {1, Access::kGet, true},
    {2, Access::kGetSet, true},
    {3, Access::kGet, false},
}};

class TestObject final : public AttributeHandler {
 public:
  std::uint8_t setting = 4;
  AttributeObject object{kTestClass, *this};

  std::uint32_t MaxInstance() const override { return 2; }
  std::span<const AttributeSpec> InstanceAttributes(std::uint32_t) const override { return kTestAttributes; }
  void GetInstanceAttribute(std::uint32_t instance, std::uint16_t id, base::ByteWriter& out) override {
    if (id == 1) out.U16Le(static_cast<std::uint16_t>(0x1234 + instance - 1));
    if (id == 2) out.U8(setting);
    if (id == 3) out.U32Le(0xA1B2C3D4);
  }
  ServiceStatus SetInstanceAttribute(std::uint32_t, std::uint16_t, base::ByteReader& value) override {
    std::uint8_t requested = 0;
    const ServiceStatus status = ReadExactU8(value, requested);
    if (!status.ok()) return status;
    if (requested > 10) return Error(GeneralStatus::kInvalidAttributeValue);
    setting = requested;
    return Success();
  }
  ServiceStatus ExecuteOther(const ServiceRequest& request, base::ByteWriter& reply) override {
    reply.Bytes(request.data);
    return Success();
  }
};

class CipMessageRouterTest : public ::testing::Test {
 protected:
  CipMessageRouterTest() { EXPECT_TRUE(objects_.Register(object_.object).ok()); }

  Bytes Ask(const Bytes& request, std::size_t reply_capacity = 512) {
    std::vector<std::uint8_t> reply(reply_capacity);
    const std::size_t size = router_.HandleUnconnected(request, context_, reply);
    reply.resize(size);
    return reply;
  }

  TestObject object_;
  ObjectRegistry objects_;
  MessageRouter router_{objects_};
  RequestContext context_;
};

TEST_F(CipMessageRouterTest, RequestAndReplyCodecs) {
  const Bytes bytes = Hex("10 03 20 70 24 01 30 02 05");
  const base::Result<MessageRouterRequest> request = DecodeMessageRouterRequest(bytes);
  ASSERT_TRUE(request.ok());
  EXPECT_EQ(request->service, 0x10);
  EXPECT_EQ(Of(request->path), Hex("20 70 24 01 30 02"));
  EXPECT_EQ(Of(request->data), Hex("05"));
  std::array<std::uint8_t, 16> buffer{};
  base::ByteWriter out(buffer);
  EncodeMessageRouterRequest(*request, out);
  EXPECT_EQ(Of(out.written()), bytes);

  EXPECT_EQ(DecodeMessageRouterRequest(Hex("0E")).status(), base::OutOfRange());
  EXPECT_EQ(DecodeMessageRouterRequest(Hex("0E 02 20 01 24")).status(), base::OutOfRange());

  const Bytes reply_bytes = Hex("D2 00 01 01 11 03 01");
  const base::Result<MessageRouterReply> reply = DecodeMessageRouterReply(reply_bytes);
  ASSERT_TRUE(reply.ok());
  EXPECT_EQ(reply->service, 0xD2);
  EXPECT_EQ(reply->general, GeneralStatus::kConnectionFailure);
  EXPECT_EQ(Of(reply->additional_status), Hex("11 03"));
  EXPECT_EQ(Of(reply->data), Hex("01"));
  EXPECT_EQ(DecodeMessageRouterReply(Hex("8E 00 00 02 00 00")).status(), base::OutOfRange());
}

TEST_F(CipMessageRouterTest, GetAttributeSingle) {
  EXPECT_EQ(Ask(Hex("0E 03 20 70 24 01 30 01")), Hex("8E 00 00 00 34 12"));
  EXPECT_EQ(Ask(Hex("0E 03 20 70 24 02 30 01")), Hex("8E 00 00 00 35 12"));
  EXPECT_EQ(Ask(Hex("0E 03 20 70 24 01 30 03")), Hex("8E 00 00 00 D4 C3 B2 A1"));
  // 16-bit class and instance segments address the same attribute.
  EXPECT_EQ(Ask(Hex("0E 05 21 00 70 00 25 00 01 00 30 01")), Hex("8E 00 00 00 34 12"));
}

TEST_F(CipMessageRouterTest, ClassAttributes) {
  EXPECT_EQ(Ask(Hex("0E 03 20 70 24 00 30 01")), Hex("8E 00 00 00 02 00"));  // revision
  EXPECT_EQ(Ask(Hex("0E 03 20 70 24 00 30 02")), Hex("8E 00 00 00 02 00"));  // max instance
  EXPECT_EQ(Ask(Hex("0E 03 20 70 24 00 30 03")), Hex("8E 00 00 00 02 00"));  // number of instances
  EXPECT_EQ(Ask(Hex("0E 03 20 70 24 00 30 06")), Hex("8E 00 00 00 07 00"));
  EXPECT_EQ(Ask(Hex("0E 03 20 70 24 00 30 07")), Hex("8E 00 00 00 03 00"));
  EXPECT_EQ(Ask(Hex("0E 03 20 70 24 00 30 04")), Hex("8E 00 14 00"));  // not in this class's list
  EXPECT_EQ(Ask(Hex("10 03 20 70 24 00 30 01 01 00")), Hex("90 00 08 00"));  // no SAS at class level
  EXPECT_EQ(Ask(Hex("01 02 20 70 24 00")), Hex("81 00 00 00 02 00 02 00 02 00 07 00 03 00"));
}

TEST_F(CipMessageRouterTest, GetAttributesAllSkipsAttributesNotInIt) {
  EXPECT_EQ(Ask(Hex("01 02 20 70 24 01")), Hex("81 00 00 00 34 12 04"));
  EXPECT_EQ(Ask(Hex("01 02 20 70 24 01 00")), Hex("81 00 15 00"));  // data after the path
}

TEST_F(CipMessageRouterTest, SetAttributeSingle) {
  EXPECT_EQ(Ask(Hex("10 03 20 70 24 01 30 02 09")), Hex("90 00 00 00"));
  EXPECT_EQ(object_.setting, 9);
  EXPECT_EQ(Ask(Hex("10 03 20 70 24 01 30 02 0B")), Hex("90 00 09 00"));     // invalid value
  EXPECT_EQ(Ask(Hex("10 03 20 70 24 01 30 02")), Hex("90 00 13 00"));        // not enough data
  EXPECT_EQ(Ask(Hex("10 03 20 70 24 01 30 02 01 02")), Hex("90 00 15 00"));  // too much data
  EXPECT_EQ(Ask(Hex("10 03 20 70 24 01 30 01 01 00")), Hex("90 00 0E 00"));  // read-only
  EXPECT_EQ(Ask(Hex("10 03 20 70 24 01 30 09 01")), Hex("90 00 14 00"));     // no such attribute
  EXPECT_EQ(object_.setting, 9);
}

TEST_F(CipMessageRouterTest, ErrorOrder) {
  EXPECT_EQ(Ask(Hex("0E 03 20 71 24 01 30 01")), Hex("8E 00 05 00"));  // no such class
  EXPECT_EQ(Ask(Hex("0E 03 20 70 24 03 30 01")), Hex("8E 00 16 00"));  // no such instance
  // An unsupported service is reported before the member segment, the attribute and the data.
  EXPECT_EQ(Ask(Hex("18 04 20 70 24 01 30 09 28 01 FF")), Hex("98 00 08 00"));
  EXPECT_EQ(Ask(Hex("4C 02 20 70 24 00")), Hex("CC 00 08 00"));  // class level lacks 0x4C
  EXPECT_EQ(Ask(Hex("0E 04 20 70 24 01 30 01 28 01")), Hex("8E 00 05 00"));  // member
  EXPECT_EQ(Ask(Hex("0E 03 20 70 24 01 30 09")), Hex("8E 00 14 00"));        // no such attribute
  EXPECT_EQ(Ask(Hex("0E 02 20 70 24 01")), Hex("8E 00 14 00"));              // no attribute at all
  EXPECT_EQ(Ask(Hex("0E 03 20 70 24 01 30 01 00")), Hex("8E 00 15 00"));     // data with a Get
  EXPECT_EQ(Ask(Hex("4B 02 20 70 24 01 AA BB")), Hex("CB 00 00 00 AA BB"));  // object-specific
}

TEST_F(CipMessageRouterTest, BadPaths) {
  EXPECT_EQ(Ask(Hex("0E 03 20 70 24")), Hex("8E 00 04 00"));              // path runs past the request
  EXPECT_EQ(Ask(Hex("0E 02 20 70 25 00")), Hex("8E 00 04 00"));           // 16-bit instance cut short
  EXPECT_EQ(Ask(Hex("0E 03 43 01 20 70 24 01")), Hex("8E 00 04 00"));     // unknown segment type
  EXPECT_EQ(Ask(Hex("0E 01 20 70")), Hex("8E 00 04 00"));                 // no instance
  EXPECT_EQ(Ask(Hex("0E 04 91 03 61 62 63 00")), Hex("8E 00 04 00"));     // symbolic
  EXPECT_EQ(Ask(Hex("0E")), Hex("8E 00 04 00"));                          // no path size
  EXPECT_EQ(Ask(Hex("")), Hex("80 00 04 00"));
  EXPECT_EQ(Ask(Hex("8E 03 20 70 24 01 30 01")), Hex("8E 00 08 00"));     // a reply is not a request
  // The 32-bit format is reserved for class and attribute IDs: a path error, not class 0x70 or attribute 1.
  EXPECT_EQ(Ask(Hex("0E 05 22 00 70 00 00 00 24 01 30 01")), Hex("8E 00 04 00"));
  EXPECT_EQ(Ask(Hex("0E 05 20 70 24 01 32 00 01 00 00 00")), Hex("8E 00 04 00"));
}

TEST_F(CipMessageRouterTest, ReplyTooLargeForTheBuffer) {
  EXPECT_EQ(Ask(Hex("0E 03 20 70 24 01 30 03"), 7), Hex("8E 00 11 00"));
  EXPECT_TRUE(Ask(Hex("0E 03 20 70 24 01 30 03"), 3).empty());
}

const Bytes kGetAttribute1 = Hex("0E 03 20 70 24 01 30 01");
const Bytes kGetAttribute9 = Hex("0E 03 20 70 24 01 30 09");

TEST_F(CipMessageRouterTest, MultipleServicePacket) {
  const Bytes request = test::Concat(Hex("0A 02 20 02 24 01 | 02 00 06 00 0E 00"), test::Concat(kGetAttribute1, kGetAttribute1));
  EXPECT_EQ(Ask(request), Hex("8A 00 00 00 | 02 00 06 00 0C 00 | 8E 00 00 00 34 12 | 8E 00 00 00 34 12"));
}

TEST_F(CipMessageRouterTest, MultipleServicePacketWithAFailingMember) {
  const Bytes request = test::Concat(Hex("0A 02 20 02 24 01 | 02 00 06 00 0E 00"), test::Concat(kGetAttribute1, kGetAttribute9));
  EXPECT_EQ(Ask(request), Hex("8A 00 1E 00 | 02 00 06 00 0C 00 | 8E 00 00 00 34 12 | 8E 00 14 00"));
}

TEST_F(CipMessageRouterTest, MultipleServicePacketOffsetsAreChecked) {
  EXPECT_EQ(Ask(Hex("0A 02 20 02 24 01")), Hex("8A 00 13 00"));                  // no count
  EXPECT_EQ(Ask(Hex("0A 02 20 02 24 01 02 00 06 00")), Hex("8A 00 13 00"));      // table cut short
  EXPECT_EQ(Ask(test::Concat(Hex("0A 02 20 02 24 01 01 00 02 00"), kGetAttribute1)), Hex("8A 00 13 00"));  // in table
  EXPECT_EQ(Ask(test::Concat(Hex("0A 02 20 02 24 01 01 00 0C 00"), kGetAttribute1)), Hex("8A 00 13 00"));  // past end
  EXPECT_EQ(Ask(test::Concat(Hex("0A 02 20 02 24 01 02 00 0E 00 06 00"), test::Concat(kGetAttribute1, kGetAttribute1))),
            Hex("8A 00 20 00"));  // offsets going down
  EXPECT_EQ(Ask(Hex("0A 02 20 02 24 01 00 00")), Hex("8A 00 00 00 00 00"));  // nothing to do
  // An MSP to another object is an ordinary (unsupported) service.
  EXPECT_EQ(Ask(test::Concat(Hex("0A 02 20 70 24 01 01 00 04 00"), kGetAttribute1)), Hex("8A 00 08 00"));
}

TEST_F(CipMessageRouterTest, MultipleServicePacketReplyTooLarge) {
  const Bytes request = test::Concat(Hex("0A 02 20 02 24 01 | 02 00 06 00 0E 00"), test::Concat(kGetAttribute1, kGetAttribute1));
  // The second member's reply does not fit: that member says 0x11 ...
  EXPECT_EQ(Ask(request, 20), Hex("8A 00 1E 00 02 00 06 00 0C 00 8E 00 00 00 34 12 8E 00 11 00"));
  // ... and when not even that fits, the whole packet does.
  EXPECT_EQ(Ask(request, 19), Hex("8A 00 11 00"));
}

// An Unconnected_Send to the Connection Manager carrying `embedded` over `route` (hex, even length).
Bytes UnconnectedSend(const Bytes& embedded, const Bytes& route) {
  Bytes request = Hex("52 02 20 06 24 01 0A F0");
  request.push_back(static_cast<std::uint8_t>(embedded.size()));
  request.push_back(0);
  request.insert(request.end(), embedded.begin(), embedded.end());
  if (embedded.size() % 2 != 0) request.push_back(0);
  request.push_back(static_cast<std::uint8_t>(route.size() / 2));
  request.push_back(0);
  request.insert(request.end(), route.begin(), route.end());
  return request;
}

TEST_F(CipMessageRouterTest, UnconnectedSendWithALocalRouteAnswersTheEmbeddedRequest) {
  EXPECT_EQ(Ask(UnconnectedSend(kGetAttribute1, Hex(""))), Hex("8E 00 00 00 34 12"));
  EXPECT_EQ(Ask(UnconnectedSend(kGetAttribute1, Hex("01 00"))), Hex("8E 00 00 00 34 12"));
  EXPECT_EQ(Ask(UnconnectedSend(kGetAttribute9, Hex("01 00"))), Hex("8E 00 14 00"));
  // An odd-sized embedded request is followed by a pad byte.
  EXPECT_EQ(Ask(UnconnectedSend(Hex("4B 02 20 70 24 01 AA"), Hex("01 00"))), Hex("CB 00 00 00 AA"));
}

// Routing errors: 0x01 with extended status, then the remaining path size and a reserved byte.
TEST_F(CipMessageRouterTest, UnconnectedSendToAnotherNode) {
  EXPECT_EQ(Ask(UnconnectedSend(kGetAttribute1, Hex("01 03"))), Hex("D2 00 01 01 12 03 01 00"));  // slot 3
  EXPECT_EQ(Ask(UnconnectedSend(kGetAttribute1, Hex("02 05"))), Hex("D2 00 01 01 12 03 01 00"));  // out on Ethernet
  EXPECT_EQ(Ask(UnconnectedSend(kGetAttribute1, Hex("01 00 03 01"))), Hex("D2 00 01 01 11 03 02 00"));  // port 3
  EXPECT_EQ(Ask(UnconnectedSend(kGetAttribute1, Hex("20 01"))), Hex("D2 00 01 01 15 03 01 00"));  // not a port
  EXPECT_EQ(Ask(UnconnectedSend(kGetAttribute1, Hex("12 05 31 2E 32 2E"))), Hex("D2 00 01 01 15 03 03 00"));  // cut
}

TEST_F(CipMessageRouterTest, UnconnectedSendMalformed) {
  EXPECT_EQ(Ask(Hex("52 02 20 06 24 01 0A F0 08")), Hex("D2 00 13 00"));
  Bytes too_long = UnconnectedSend(kGetAttribute1, Hex("01 00"));
  too_long.push_back(0);
  EXPECT_EQ(Ask(too_long), Hex("D2 00 15 00"));
  Bytes route_cut = UnconnectedSend(kGetAttribute1, Hex("01 00"));
  route_cut.pop_back();
  EXPECT_EQ(Ask(route_cut), Hex("D2 00 13 00"));
  EXPECT_EQ(Ask(UnconnectedSend(Hex(""), Hex(""))), Hex("D2 00 13 00"));
  // Not to the Connection Manager instance 1: an ordinary request to a class that is not there.
  EXPECT_EQ(Ask(Hex("52 02 20 06 24 02 0A F0 00 00 00 00")), Hex("D2 00 05 00"));
}

TEST_F(CipMessageRouterTest, NestingIsBounded) {
  // Unconnected_Send carrying a Multiple Service Packet: two levels, answered.
  const Bytes msp = test::Concat(Hex("0A 02 20 02 24 01 01 00 04 00"), kGetAttribute1);
  EXPECT_EQ(Ask(UnconnectedSend(msp, Hex(""))), Hex("8A 00 00 00 01 00 04 00 8E 00 00 00 34 12"));
  // One more level is refused where it starts.
  EXPECT_EQ(Ask(UnconnectedSend(UnconnectedSend(msp, Hex("")), Hex(""))), Hex("8A 00 02 00"));
  // An MSP in an MSP is fine; a third level is refused and fails both packets around it.
  const Bytes two_levels = test::Concat(Hex("0A 02 20 02 24 01 01 00 04 00"), msp);
  EXPECT_EQ(Ask(two_levels), Hex("8A 00 00 00 01 00 04 00 8A 00 00 00 01 00 04 00 8E 00 00 00 34 12"));
  const Bytes three_levels = test::Concat(Hex("0A 02 20 02 24 01 01 00 04 00"), two_levels);
  EXPECT_EQ(Ask(three_levels),
            Hex("8A 00 1E 00 01 00 04 00 | 8A 00 1E 00 01 00 04 00 | 8A 00 02 00"));
}

}  // namespace
}  // namespace cip
