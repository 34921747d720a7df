// The DLR object 0x47 of a ring node (cip/dlr_object.h, docs/network.md "Ring (DLR)") behind a message
// router: every attribute with exact reply bytes, Get_Attributes_All's layout with the supervisor
// attributes' placeholders, the class attributes, and the refusals (0x0E, 0x14, 0x08, 0x16).
#include "cip/dlr_object.h"

#include <gtest/gtest.h>

#include <array>
#include <string_view>

#include "cip/message_router.h"
#include "cip_test_support.h"

namespace cip {
namespace {

using test::Bytes;
using test::Hex;

class FakeDlr final : public DlrProvider {
 public:
  DlrObjectValues DlrValues() const override { return values; }
  DlrObjectValues values;
};

class CipDlrObjectTest : public ::testing::Test {
 protected:
  CipDlrObjectTest() { EXPECT_TRUE(registry_.Register(dlr_object_.object()).ok()); }

  Bytes Ask(std::string_view request) {
    const Bytes bytes = Hex(request);
    RequestContext context;
    std::array<std::uint8_t, 512> reply{};
    const std::size_t size = router_.HandleUnconnected(bytes, context, reply);
    return Bytes(reply.begin(), reply.begin() + static_cast<std::ptrdiff_t>(size));
  }
  // A ring in normal state under supervisor 192.0.2.1 / 00:00:5E:00:53:10, precedence 5.
  void Ring() {
    dlr_.values.network_topology = 1;
    dlr_.values.network_status = 0;
    dlr_.values.supervisor_ip = 0xC0000201;
    dlr_.values.supervisor_mac = base::MacAddress(0x00, 0x00, 0x5E, 0x00, 0x53, 0x10);
    dlr_.values.supervisor_precedence = 5;
  }

  FakeDlr dlr_;
  DlrObject dlr_object_{dlr_};
  ObjectRegistry registry_;
  MessageRouter router_{registry_};
};

TEST_F(CipDlrObjectTest, LinearNoSupervisor) {
  EXPECT_EQ(Ask("0E 03 20 47 24 01 30 01"), Hex("8E 00 00 00 00"));
  EXPECT_EQ(Ask("0E 03 20 47 24 01 30 02"), Hex("8E 00 00 00 00"));
  EXPECT_EQ(Ask("0E 03 20 47 24 01 30 0A"), Hex("8E 00 00 00 | 00 00 00 00 | 00 00 00 00 00 00"));
  EXPECT_EQ(Ask("0E 03 20 47 24 01 30 0C"), Hex("8E 00 00 00 82 00 00 00"));
}

TEST_F(CipDlrObjectTest, RingAttributes) {
  Ring();
  EXPECT_EQ(Ask("0E 03 20 47 24 01 30 01"), Hex("8E 00 00 00 01"));
  EXPECT_EQ(Ask("0E 03 20 47 24 01 30 0A"), Hex("8E 00 00 00 | 01 02 00 C0 | 00 00 5E 00 53 10"));
  dlr_.values.network_status = 1;
  EXPECT_EQ(Ask("0E 03 20 47 24 01 30 02"), Hex("8E 00 00 00 01"));
}

TEST_F(CipDlrObjectTest, GetAttributesAll_FiftyFourBytes) {
  Ring();
  EXPECT_EQ(Ask("01 02 20 47 24 01"),
            Hex("81 00 00 00"
                "| 01 | 00 | FF"                                  // 1 topology, 2 status, 3 supervisor status
                "| 00 00 00 00 00 00 00 00 00 00 00 00"           // 4 supervisor config
                "| 00 00"                                         // 5 ring faults count
                "| 00 00 00 00 00 00 00 00 00 00"                 // 6 last active node on port 1
                "| 00 00 00 00 00 00 00 00 00 00"                 // 7 ... on port 2
                "| FF FF"                                         // 8 participants count
                "| 01 02 00 C0 00 00 5E 00 53 10"                 // 10 active supervisor address
                "| 05"                                            // 11 active supervisor precedence
                "| 82 00 00 00"));                                // 12 capability flags
}

TEST_F(CipDlrObjectTest, SupervisorAttributes_NotImplementedByANode) {
  for (const char* attribute : {"03", "04", "05", "06", "07", "08", "09", "0B", "0D", "13"}) {
    EXPECT_EQ(Ask(std::string("0E 03 20 47 24 01 30 ") + attribute), Hex("8E 00 14 00")) << attribute;
  }
}

TEST_F(CipDlrObjectTest, SetAttributeSingle_NotSettableOrUnsupported) {
  EXPECT_EQ(Ask("10 03 20 47 24 01 30 01 01"), Hex("90 00 0E 00"));
  EXPECT_EQ(Ask("10 03 20 47 24 01 30 0C 82 00 00 00"), Hex("90 00 0E 00"));
  EXPECT_EQ(Ask("10 03 20 47 24 01 30 04 00 00 00 00 00 00 00 00 00 00 00 00"), Hex("90 00 14 00"));
  EXPECT_EQ(Ask("10 03 20 47 24 01 30 0B 05"), Hex("90 00 14 00"));
}

TEST_F(CipDlrObjectTest, SupervisorServices_NotSupported) {
  for (const char* service : {"4B", "4C", "4D", "4E"}) {
    const Bytes reply = Ask(std::string(service) + " 02 20 47 24 01");
    ASSERT_EQ(reply.size(), 4U) << service;
    EXPECT_EQ(reply[0], Hex(service)[0] | 0x80) << service;
    EXPECT_EQ(reply[2], 0x08) << service;
  }
}

TEST_F(CipDlrObjectTest, ClassAttributesAndInstances) {
  EXPECT_EQ(Ask("0E 03 20 47 24 00 30 01"), Hex("8E 00 00 00 03 00"));  // revision 3
  EXPECT_EQ(Ask("0E 03 20 47 24 00 30 02"), Hex("8E 00 00 00 01 00"));  // max instance 1
  EXPECT_EQ(Ask("0E 03 20 47 24 00 30 03"), Hex("8E 00 00 00 01 00"));  // instances 1
  EXPECT_EQ(Ask("0E 03 20 47 24 00 30 06"), Hex("8E 00 00 00 07 00"));
  EXPECT_EQ(Ask("0E 03 20 47 24 00 30 07"), Hex("8E 00 00 00 0C 00"));
  EXPECT_EQ(Ask("0E 03 20 47 24 02 30 01"), Hex("8E 00 16 00"));  // no instance 2
  EXPECT_EQ(Ask("10 03 20 47 24 00 30 01 03 00"), Hex("90 00 08 00"));  // the class has no Set
}

}  // namespace
}  // namespace cip
