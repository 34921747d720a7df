// Identity, Message Router, Port and Assembly objects through the message router of a CipDevice built
// on fakes: every class and instance attribute and service of the manual's §4.1, §4.2, §4.3 and §4.10,
// with exact reply bytes.
#include <gtest/gtest.h>

#include <array>
#include <cstdint>

#include "cip/identity_object.h"
#include "cip/port_object.h"
#include "cip_fakes.h"

namespace cip {
namespace {

using test::Bytes;
using test::FakeCard;
using test::Hex;
using test::Of;

class CipIdentityTest : public ::testing::Test {
 protected:
  FakeCard card_;
};

TEST_F(CipIdentityTest, VendorIdIs377) { EXPECT_EQ(card_.Ask(Hex("0E 03 20 01 24 01 30 01")), Hex("8E 00 00 00 79 01")); }

TEST_F(CipIdentityTest, InstanceAttributes) {
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 01 24 01 30 02")), Hex("8E 00 00 00 02 00"));
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 01 24 01 30 03")), Hex("8E 00 00 00 00 7D"));  // 32000
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 01 24 01 30 04")), Hex("8E 00 00 00 01 08"));
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 01 24 01 30 05")), Hex("8E 00 00 00 30 00"));
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 01 24 01 30 06")), Hex("8E 00 00 00 C0 02 7D F4"));
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 01 24 01 30 07")), Hex("8E 00 00 00 06 56 46 2D 4D 42 31"));
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 01 24 01 30 08")), Hex("8E 00 14 00"));
}

TEST_F(CipIdentityTest, ProductCodeAndNameFollowTheDrive) {
  card_.device.model = DriveModel::kVfS15;
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 01 24 01 30 03")), Hex("8E 00 00 00 01 7D"));  // 32001
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 01 24 01 30 07")), Hex("8E 00 00 00 06 56 46 2D 53 31 35"));
}

TEST_F(CipIdentityTest, StatusWordBits) {
  card_.device.status.configured = true;
  card_.device.status.extended = ExtendedDeviceStatus::kIoConnectionInRunMode;
  card_.device.status.minor_recoverable_fault = true;
  card_.device.status.major_unrecoverable_fault = true;
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 01 24 01 30 05")), Hex("8E 00 00 00 64 09"));
  EXPECT_EQ(EncodeStatusWord(DeviceStatus{false, ExtendedDeviceStatus::kIoConnectionsIdle, false, true, true, false}),
            0x0670);
}

TEST_F(CipIdentityTest, SerialNumberIsTheMacsTail) {
  EXPECT_EQ(SerialNumberFromMac({0x00, 0x80, 0xF4, 0x7D, 0x02, 0xC0}), 0xF47D02C0U);
  EXPECT_EQ(SerialNumberFromMac({0x02, 0x11, 0x22, 0x33, 0x44, 0x55}), 0x22334455U);
}

TEST_F(CipIdentityTest, GetAttributesAll) {
  EXPECT_EQ(card_.Ask(Hex("01 02 20 01 24 01")),
            Hex("81 00 00 00 | 79 01 | 02 00 | 00 7D | 01 08 | 30 00 | C0 02 7D F4 | 06 56 46 2D 4D 42 31"));
  EXPECT_EQ(card_.Ask(Hex("01 02 20 01 24 00")), Hex("81 00 00 00 | 01 00 | 01 00 | 01 00 | 00 00 | 07 00 | 07 00"));
}

TEST_F(CipIdentityTest, ClassAttributes) {
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 01 24 00 30 01")), Hex("8E 00 00 00 01 00"));
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 01 24 00 30 02")), Hex("8E 00 00 00 01 00"));
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 01 24 00 30 03")), Hex("8E 00 00 00 01 00"));
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 01 24 00 30 04")), Hex("8E 00 00 00 00 00"));
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 01 24 00 30 05")), Hex("8E 00 14 00"));
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 01 24 00 30 06")), Hex("8E 00 00 00 07 00"));
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 01 24 00 30 07")), Hex("8E 00 00 00 07 00"));
}

TEST_F(CipIdentityTest, ErrorsOfTheIdentityObject) {
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 01 24 02 30 01")), Hex("8E 00 16 00"));          // instance 2
  EXPECT_EQ(card_.Ask(Hex("10 03 20 01 24 01 30 01 79 01")), Hex("90 00 08 00"));    // no Set service
  EXPECT_EQ(card_.Ask(Hex("05 02 20 01 24 00")), Hex("85 00 08 00"));                // no class Reset
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 01 24 01 30 01 00")), Hex("8E 00 15 00"));       // data with a Get
}

TEST_F(CipIdentityTest, ResetTypes) {
  EXPECT_EQ(card_.Ask(Hex("05 02 20 01 24 01")), Hex("85 00 00 00"));
  EXPECT_EQ(card_.Ask(Hex("05 02 20 01 24 01 00")), Hex("85 00 00 00"));
  EXPECT_EQ(card_.Ask(Hex("05 02 20 01 24 01 01")), Hex("85 00 00 00"));
  EXPECT_EQ(card_.reset.requests, (std::vector<hal::ResetKind>{hal::ResetKind::kRestart, hal::ResetKind::kRestart,
                                                               hal::ResetKind::kFactoryDefaults}));
  EXPECT_EQ(card_.Ask(Hex("05 02 20 01 24 01 02")), Hex("85 00 20 00"));
  EXPECT_EQ(card_.Ask(Hex("05 02 20 01 24 01 64")), Hex("85 00 20 00"));
  EXPECT_EQ(card_.Ask(Hex("05 02 20 01 24 01 00 00")), Hex("85 00 15 00"));
  EXPECT_EQ(card_.reset.requests.size(), 3U);
}

TEST_F(CipIdentityTest, ListIdentityCarriesTheActiveAddress) {
  const IdentityItem item = card_.cip.ListIdentity();
  EXPECT_EQ(item.socket_address, (SocketAddress{2, 44818, 0x0A00020F}));
  EXPECT_EQ(item.vendor_id, 377);
  EXPECT_EQ(item.product_code, 32000);
  EXPECT_EQ(item.serial_number, 0xF47D02C0U);
  EXPECT_EQ(item.state, 0xFF);
}

TEST(CipMessageRouterObject, Attributes) {
  FakeCard card;
  EXPECT_EQ(card.Ask(Hex("0E 03 20 02 24 01 30 02")), Hex("8E 00 00 00 10 00"));  // 16 connections
  EXPECT_EQ(card.Ask(Hex("0E 03 20 02 24 01 30 03")), Hex("8E 00 00 00 00 00"));
  EXPECT_EQ(card.Ask(Hex("0E 03 20 02 24 01 30 01")), Hex("8E 00 14 00"));
  EXPECT_EQ(card.Ask(Hex("01 02 20 02 24 01")), Hex("81 00 08 00"));
  EXPECT_EQ(card.Ask(Hex("0E 03 20 02 24 00 30 01")), Hex("8E 00 00 00 01 00"));
  EXPECT_EQ(card.Ask(Hex("0E 03 20 02 24 00 30 04")), Hex("8E 00 00 00 02 00 02 00 03 00"));
  EXPECT_EQ(card.Ask(Hex("0E 03 20 02 24 00 30 06")), Hex("8E 00 00 00 07 00"));
  EXPECT_EQ(card.Ask(Hex("0E 03 20 02 24 00 30 07")), Hex("8E 00 00 00 03 00"));
  EXPECT_EQ(card.Ask(Hex("01 02 20 02 24 00")), Hex("81 00 08 00"));

  struct Counter final : ConnectionCountProvider {
    std::uint16_t ActiveConnections() const override { return 3; }
  } counter;
  card.cip.message_router_object().set_connection_counter(&counter);
  EXPECT_EQ(card.Ask(Hex("0E 03 20 02 24 01 30 03")), Hex("8E 00 00 00 03 00"));
}

TEST(CipPortObject, InstanceAttributes) {
  FakeCard card;
  EXPECT_EQ(card.Ask(Hex("0E 03 20 F4 24 01 30 01")), Hex("8E 00 00 00 00 00"));
  EXPECT_EQ(card.Ask(Hex("0E 03 20 F4 24 01 30 02")), Hex("8E 00 00 00 02 00"));
  EXPECT_EQ(card.Ask(Hex("0E 03 20 F4 24 01 30 03")), Hex("8E 00 00 00 02 00 20 F5 24 01"));
  EXPECT_EQ(card.Ask(Hex("0E 03 20 F4 24 01 30 04")), Hex("8E 00 00 00 0B 45 74 68 65 72 4E 65 74 2F 49 50"));
  EXPECT_EQ(card.Ask(Hex("0E 03 20 F4 24 01 30 07")), Hex("8E 00 00 00 12 09 31 30 2E 30 2E 32 2E 31 35 00"));
  EXPECT_EQ(card.Ask(Hex("0E 03 20 F4 24 01 30 05")), Hex("8E 00 14 00"));
  EXPECT_EQ(card.Ask(Hex("01 02 20 F4 24 01")),
            Hex("81 00 00 00 | 00 00 | 02 00 | 02 00 20 F5 24 01 | 0B 45 74 68 65 72 4E 65 74 2F 49 50"
                "| 12 09 31 30 2E 30 2E 32 2E 31 35 00"));
  card.tcpip.active.ip_address = 0xC0A8640A;  // 192.168.100.10: 14 characters, no pad
  EXPECT_EQ(card.Ask(Hex("0E 03 20 F4 24 01 30 07")),
            Hex("8E 00 00 00 12 0E 31 39 32 2E 31 36 38 2E 31 30 30 2E 31 30"));
}

TEST(CipPortObject, ClassAttributes) {
  FakeCard card;
  EXPECT_EQ(card.Ask(Hex("0E 03 20 F4 24 00 30 01")), Hex("8E 00 00 00 01 00"));
  EXPECT_EQ(card.Ask(Hex("0E 03 20 F4 24 00 30 02")), Hex("8E 00 00 00 01 00"));
  EXPECT_EQ(card.Ask(Hex("0E 03 20 F4 24 00 30 03")), Hex("8E 00 00 00 01 00"));
  EXPECT_EQ(card.Ask(Hex("0E 03 20 F4 24 00 30 06")), Hex("8E 00 00 00 09 00"));
  EXPECT_EQ(card.Ask(Hex("0E 03 20 F4 24 00 30 07")), Hex("8E 00 00 00 07 00"));
  EXPECT_EQ(card.Ask(Hex("0E 03 20 F4 24 00 30 08")), Hex("8E 00 00 00 01 00"));
  EXPECT_EQ(card.Ask(Hex("0E 03 20 F4 24 00 30 09")), Hex("8E 00 00 00 00 00 00 00 00 00 02 00"));
  EXPECT_EQ(card.Ask(Hex("0E 03 20 F4 24 00 30 04")), Hex("8E 00 14 00"));
  EXPECT_EQ(card.Ask(Hex("01 02 20 F4 24 00")),
            Hex("81 00 00 00 01 00 01 00 01 00 09 00 07 00 01 00 00 00 00 00 00 00 02 00"));
}

TEST(CipPortObject, FormatsAddresses) {
  std::array<std::uint8_t, 15> text{};
  EXPECT_EQ(Of(std::span(text).first(FormatIpv4(0, text))), Hex("30 2E 30 2E 30 2E 30"));
  const std::size_t size = FormatIpv4(0xFFFFFFFF, text);
  EXPECT_EQ(std::string(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(size)), "255.255.255.255");
}

class RefusingHandler final : public AssemblyWriteHandler {
 public:
  ServiceStatus OnExplicitWrite(std::uint32_t instance, std::span<const std::uint8_t> data) override {
    last_instance = instance;
    last_data = Of(data);
    return refuse ? Error(GeneralStatus::kDeviceStateConflict) : Success();
  }
  bool refuse = false;
  std::uint32_t last_instance = 0;
  Bytes last_data;
};

class CipAssemblyTest : public ::testing::Test {
 protected:
  CipAssemblyTest() {
    EXPECT_TRUE(card_.cip.assemblies().Register(150, AssemblyDirection::kInput, input_).ok());
    EXPECT_TRUE(card_.cip.assemblies().Register(100, AssemblyDirection::kOutput, output_, &handler_).ok());
  }
  FakeCard card_;
  std::array<std::uint8_t, 4> input_ = {1, 2, 3, 4};
  std::array<std::uint8_t, 4> output_ = {};
  RefusingHandler handler_;
};

TEST_F(CipAssemblyTest, ClassAttributesFollowTheRegistry) {
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 04 24 00 30 01")), Hex("8E 00 00 00 02 00"));
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 04 24 00 30 02")), Hex("8E 00 00 00 96 00"));  // 150
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 04 24 00 30 03")), Hex("8E 00 00 00 02 00"));
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 04 24 00 30 06")), Hex("8E 00 00 00 07 00"));
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 04 24 00 30 07")), Hex("8E 00 00 00 04 00"));
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 04 24 00 30 04")), Hex("8E 00 14 00"));
  EXPECT_EQ(card_.Ask(Hex("01 02 20 04 24 00")), Hex("81 00 08 00"));
}

TEST_F(CipAssemblyTest, DataAndSize) {
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 04 24 96 30 03")), Hex("8E 00 00 00 01 02 03 04"));
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 04 24 96 30 04")), Hex("8E 00 00 00 04 00"));
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 04 24 64 30 03")), Hex("8E 00 00 00 00 00 00 00"));
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 04 24 63 30 03")), Hex("8E 00 16 00"));  // instance 99
  EXPECT_EQ(card_.Ask(Hex("01 02 20 04 24 96")), Hex("81 00 08 00"));
}

TEST_F(CipAssemblyTest, OnlyOutputsAreSettableAndOnlyWithTheirExactSize) {
  EXPECT_EQ(card_.Ask(Hex("10 03 20 04 24 96 30 03 09 09 09 09")), Hex("90 00 0E 00"));
  EXPECT_EQ(card_.Ask(Hex("10 03 20 04 24 64 30 04 04 00")), Hex("90 00 0E 00"));
  EXPECT_EQ(card_.Ask(Hex("10 03 20 04 24 64 30 03 01 02 03")), Hex("90 00 13 00"));
  EXPECT_EQ(card_.Ask(Hex("10 03 20 04 24 64 30 03 01 02 03 04 05")), Hex("90 00 15 00"));
  EXPECT_EQ(output_, (std::array<std::uint8_t, 4>{}));
  EXPECT_EQ(card_.Ask(Hex("10 03 20 04 24 64 30 03 0A 0B 0C 0D")), Hex("90 00 00 00"));
  EXPECT_EQ(output_, (std::array<std::uint8_t, 4>{0x0A, 0x0B, 0x0C, 0x0D}));
  EXPECT_EQ(handler_.last_instance, 100U);
  EXPECT_EQ(handler_.last_data, Hex("0A 0B 0C 0D"));
  handler_.refuse = true;
  EXPECT_EQ(card_.Ask(Hex("10 03 20 04 24 64 30 03 01 01 01 01")), Hex("90 00 10 00"));
  EXPECT_EQ(output_, (std::array<std::uint8_t, 4>{0x0A, 0x0B, 0x0C, 0x0D}));
}

TEST_F(CipAssemblyTest, RegistryLimits) {
  AssemblyObject& assemblies = card_.cip.assemblies();
  std::array<std::uint8_t, 2> data{};
  EXPECT_EQ(assemblies.Register(150, AssemblyDirection::kInput, data), base::InvalidArgument());
  EXPECT_EQ(assemblies.Register(0, AssemblyDirection::kInput, data), base::InvalidArgument());
  for (std::uint32_t instance = 1; instance <= kMaxAssemblies - 2; ++instance) {
    EXPECT_TRUE(assemblies.Register(instance, AssemblyDirection::kInput, data).ok());
  }
  EXPECT_EQ(assemblies.Register(199, AssemblyDirection::kInput, data), base::ResourceExhausted());
  EXPECT_EQ(assemblies.Data(100).data(), output_.data());
  EXPECT_TRUE(assemblies.Data(199).empty());
}

}  // namespace
}  // namespace cip
