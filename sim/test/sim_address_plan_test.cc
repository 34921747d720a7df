// The card's address as keyed into the simulated inverter (sim/host/address_plan.h): the --ip text both
// ipe002z-host and ipe002z-inverter take, and c504 = 0 with c505-c516 written and stored.
#include "address_plan.h"

#include <gtest/gtest.h>

#include "host_sim_fixture.h"

namespace host::test {
namespace {

TEST(AddressPlan, Ipv4DottedQuads) {
  std::uint32_t v = 0;
  ASSERT_TRUE(sim::ParseIpv4("192.168.1.20", v));
  EXPECT_EQ(v, 0xC0A80114u);
  ASSERT_TRUE(sim::ParseIpv4("0.0.0.0", v));
  EXPECT_EQ(v, 0u);
  ASSERT_TRUE(sim::ParseIpv4("010.000.002.015", v));  // leading zeros: decimal, as before
  EXPECT_EQ(v, 0x0A00020Fu);
  EXPECT_EQ(sim::FormatIpv4(0xC0A80114u), "192.168.1.20");
  for (const char* bad : {"", "1.2.3", "1.2.3.4.5", " 1.2.3.4", "1.2.3.4 ", "1.2.3.256", "1..2.3", "1.2.3.-4",
                          "+1.2.3.4", "1111.2.3.4", "a.b.c.d", "1.2.3.4/24"}) {
    v = 7;
    EXPECT_FALSE(sim::ParseIpv4(bad, v)) << bad;
    EXPECT_EQ(v, 7u) << bad;  // untouched
  }
}

TEST(AddressPlan, IpWithPrefixAndOptionalGateway) {
  sim::AddressPlan plan;
  ASSERT_TRUE(sim::ParseAddressPlan("10.0.2.15/24", plan));
  EXPECT_EQ(plan.ip, 0x0A00020Fu);
  EXPECT_EQ(plan.netmask, 0xFFFFFF00u);
  EXPECT_EQ(plan.gateway, 0u);  // none unless given
  ASSERT_TRUE(sim::ParseAddressPlan("192.168.1.20/16,192.168.0.1", plan));
  EXPECT_EQ(plan.ip, 0xC0A80114u);
  EXPECT_EQ(plan.netmask, 0xFFFF0000u);
  EXPECT_EQ(plan.gateway, 0xC0A80001u);
  ASSERT_TRUE(sim::ParseAddressPlan("10.1.2.3/30", plan));
  EXPECT_EQ(plan.netmask, 0xFFFFFFFCu);
  ASSERT_TRUE(sim::ParseAddressPlan("10.1.2.3/1", plan));
  EXPECT_EQ(plan.netmask, 0x80000000u);
  for (const char* bad : {"10.0.2.15", "10.0.2.15/", "10.0.2.15/0", "10.0.2.15/31", "10.0.2.15/100", "10.0.2.15/2x",
                          "10.0.2.15/24,", "10.0.2.15/24,10.0.2", "10.0.2/24", "/24", "10.0.2.15/24,1.2.3.4,5"}) {
    sim::AddressPlan untouched{1, 2, 3};
    EXPECT_FALSE(sim::ParseAddressPlan(bad, untouched)) << bad;
    EXPECT_EQ(untouched.ip, 1u) << bad;
    EXPECT_EQ(untouched.gateway, 3u) << bad;
  }
}

class AddressKeying : public SimInverterFixture {};

TEST_F(AddressKeying, ManualModeAndOneOctetPerParameterStored) {
  ASSERT_TRUE(Start()) << error_;
  ASSERT_TRUE(inverter_->model().Write(0xC504, 2, sim::WriteTarget::kRamAndEeprom).ok());  // DHCP before
  std::string error;
  ASSERT_TRUE(sim::KeyManualAddress(*inverter_, {0xC0A80114u, 0xFFFFFF00u, 0xC0A80101u}, error)) << error;
  const std::uint16_t expected[][2] = {{0xC504, 0},   {0xC505, 192}, {0xC506, 168}, {0xC507, 1},   {0xC508, 20},
                                       {0xC509, 255}, {0xC510, 255}, {0xC511, 255}, {0xC512, 0},   {0xC513, 192},
                                       {0xC514, 168}, {0xC515, 1},   {0xC516, 1}};
  const std::string image = ReadText(FilePath());
  for (const auto& [number, value] : expected) {
    EXPECT_EQ(Read(number), value) << std::hex << number;
    EXPECT_EQ(inverter_->model().EepromValue(number), value) << std::hex << number;
    char line[32];
    std::snprintf(line, sizeof line, "\nreg %04X %u ", number, value);
    EXPECT_NE(image.find(line), std::string::npos) << line;  // stored at once
  }
  EXPECT_EQ(error, "");
}

}  // namespace
}  // namespace host::test
