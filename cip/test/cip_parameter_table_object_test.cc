// The CIP Parameter object 0x0F (cip/drive/include/cip/drive/cip_parameter_object.h, docs/eds.md)
// through the message router on the scripted register fake: exact request and reply bytes for the
// value (deferred, as 0x64/0x65), the table's descriptive attributes, the detected model's limits, the
// range check before anything is sent, class attributes and every refusal.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "cip_test_support.h"
#include "drive_objects_harness.h"

namespace cip::drive {
namespace {

using cip::test::Bytes;
using cip::test::Hex;
using drive_link::AccessError;
using drive_link::WriteMode;
using Access = drive_link::test::ScriptedDriveRegisters::Access;

// Instances (rows of drive_link/registers/registers.csv's rw and monitor registers, in number order, from 1):
// au1 1, cmod 2, fmod 3, acc 6, fh 8, c101 118 (0x76), fd00 153 (0x99), fe36 178 (0xB2); 186 in all.
class ParameterTableObjectTest : public ::testing::Test {
 protected:
  ParameterTableObjectTest() {
    auto& r = h_.drive.registers;
    r[0x0000] = 0;
    r[0x0004] = 0;
    r[0x0009] = 100;  // acc 10.0 s
    r[0x0011] = 8000;
    r[0xC101] = 4;
    r[0xFD00] = 6000;
    r[0xFE36] = 0xFC18;  // -1000 = -10.00 %
  }

  Bytes Exchange(const Bytes& request) { return h_.Exchange(request); }
  static Bytes ErrorReply(std::uint8_t service, std::uint8_t general) {
    return Bytes{static_cast<std::uint8_t>(service | 0x80), 0x00, general, 0x00};
  }

  cip::drive::test::DriveObjectsHarness h_;
  drive_link::test::ScriptedDriveRegisters& drive_ = h_.drive;
  cip::test::FakeDeviceInfo& device_ = h_.device;
};

constexpr Access ReadOf(std::uint16_t number) { return Access{false, number, 0, WriteMode::kRamOnly}; }
constexpr Access WriteOf(std::uint16_t number, std::uint16_t value) {
  return Access{true, number, value, WriteMode::kRamAndEeprom};
}

TEST_F(ParameterTableObjectTest, ValueIsReadOverTheDriveLink) {
  EXPECT_EQ(Exchange(Hex("0E 03 20 0F 24 06 30 01")), Hex("8E 00 00 00 64 00"));  // acc = 100
  EXPECT_EQ(Exchange(Hex("0E 03 20 0F 24 76 30 01")), Hex("8E 00 00 00 04 00"));  // c101 = 4
  EXPECT_EQ(Exchange(Hex("0E 03 20 0F 24 B2 30 01")), Hex("8E 00 00 00 18 FC"));  // fe36 = -1000
  EXPECT_EQ(drive_.log, (std::vector<Access>{ReadOf(0x0009), ReadOf(0xC101), ReadOf(0xFE36)}));
}

TEST_F(ParameterTableObjectTest, SetWritesRamAndEepromWithinTheLimits) {
  EXPECT_EQ(Exchange(Hex("10 03 20 0F 24 06 30 01 32 00")), Hex("90 00 00 00"));  // acc = 5.0 s
  EXPECT_EQ(drive_.log, (std::vector<Access>{WriteOf(0x0009, 50)}));
  EXPECT_EQ(drive_.registers[0x0009], 50);
}

TEST_F(ParameterTableObjectTest, OutOfRangeIsRefusedBeforeAnythingIsSent) {
  EXPECT_EQ(Exchange(Hex("10 03 20 0F 24 06 30 01 00 00")), ErrorReply(0x10, 0x09));  // acc 0 < 1
  EXPECT_EQ(Exchange(Hex("10 03 20 0F 24 08 30 01 51 C3")), ErrorReply(0x10, 0x09));  // fh 50001 > 50000
  EXPECT_EQ(Exchange(Hex("10 03 20 0F 24 08 30 01 B7 0B")), ErrorReply(0x10, 0x09));  // fh 2999 < 3000
  EXPECT_EQ(Exchange(Hex("10 03 20 0F 24 03 30 01 0C 00")), ErrorReply(0x10, 0x09));  // fmod 12 on VF-MB1
  EXPECT_TRUE(drive_.log.empty());
}

TEST_F(ParameterTableObjectTest, LimitsFollowTheDetectedModel) {
  EXPECT_EQ(Exchange(Hex("0E 03 20 0F 24 03 30 0B")), Hex("8E 00 00 00 0B 00"));  // fmod max 11
  device_.model = DriveModel::kVfS15;
  EXPECT_EQ(Exchange(Hex("0E 03 20 0F 24 03 30 0B")), Hex("8E 00 00 00 0E 00"));  // fmod max 14
  EXPECT_EQ(Exchange(Hex("10 03 20 0F 24 03 30 01 0C 00")), Hex("90 00 00 00"));
  EXPECT_EQ(drive_.log, (std::vector<Access>{WriteOf(0x0004, 12)}));
}

TEST_F(ParameterTableObjectTest, DescriptiveAttributesOfAcc) {
  const auto get = [this](std::uint8_t attribute) {
    return Exchange(Bytes{0x0E, 0x03, 0x20, 0x0F, 0x24, 0x06, 0x30, attribute});
  };
  EXPECT_EQ(get(2), Hex("8E 00 00 00 08"));
  EXPECT_EQ(get(3), Hex("8E 00 00 00 20 65 25 00 09 00 30 03"));
  EXPECT_EQ(get(4), Hex("8E 00 00 00 04 00"));  // scaling
  EXPECT_EQ(get(5), Hex("8E 00 00 00 C7"));
  EXPECT_EQ(get(6), Hex("8E 00 00 00 02"));
  EXPECT_EQ(get(7), Hex("8E 00 00 00 03 61 63 63"));  // "acc"
  EXPECT_EQ(get(8), Hex("8E 00 00 00 01 73"));        // "s"
  EXPECT_EQ(get(9).size(), 4u + 1 + 35);              // "Acceleration time 1 (unit per f519)"
  EXPECT_EQ(get(10), Hex("8E 00 00 00 01 00"));
  EXPECT_EQ(get(11), Hex("8E 00 00 00 60 EA"));  // 60000
  EXPECT_EQ(get(12), Hex("8E 00 00 00 64 00"));
  EXPECT_EQ(get(13), Hex("8E 00 00 00 01 00"));
  EXPECT_EQ(get(14), Hex("8E 00 00 00 0A 00"));
  EXPECT_EQ(get(15), Hex("8E 00 00 00 01 00"));
  EXPECT_EQ(get(16), Hex("8E 00 00 00 00 00"));
  EXPECT_EQ(get(21), Hex("8E 00 00 00 01"));
  EXPECT_TRUE(drive_.log.empty());  // none of these asks the inverter
}

TEST_F(ParameterTableObjectTest, Au1MonitorsAndSignedParameters) {
  EXPECT_EQ(Exchange(Hex("0E 03 20 0F 24 01 30 03")), Hex("8E 00 00 00 20 64 25 00 00 40 30 03"));
  EXPECT_EQ(Exchange(Hex("0E 03 20 0F 24 99 30 04")), Hex("8E 00 00 00 34 00"));  // fd00: scaling, RO, monitor
  EXPECT_EQ(Exchange(Hex("0E 03 20 0F 24 76 30 04")), Hex("8E 00 00 00 00 00"));  // c101: a plain code
  EXPECT_EQ(Exchange(Hex("0E 03 20 0F 24 B2 30 05")), Hex("8E 00 00 00 C3"));     // fe36: INT
  EXPECT_EQ(Exchange(Hex("0E 03 20 0F 24 B2 30 0A")), Hex("8E 00 00 00 F0 D8"));  // -10000
  EXPECT_EQ(Exchange(Hex("10 03 20 0F 24 99 30 01 00 00")), ErrorReply(0x10, 0x0E));
  EXPECT_TRUE(drive_.log.empty());
}

TEST_F(ParameterTableObjectTest, ClassAttributes) {
  EXPECT_EQ(Exchange(Hex("0E 03 20 0F 24 00 30 01")), Hex("8E 00 00 00 01 00"));
  EXPECT_EQ(Exchange(Hex("0E 03 20 0F 24 00 30 02")), Hex("8E 00 00 00 BA 00"));  // 186
  EXPECT_EQ(Exchange(Hex("0E 03 20 0F 24 00 30 03")), Hex("8E 00 00 00 BA 00"));
  EXPECT_EQ(Exchange(Hex("0E 03 20 0F 24 00 30 08")), Hex("8E 00 00 00 0B 00"));
  EXPECT_EQ(Exchange(Hex("0E 03 20 0F 24 00 30 09")), Hex("8E 00 00 00 00 00"));
  EXPECT_EQ(Exchange(Hex("0E 03 20 0F 24 00 30 0A")), Hex("8E 00 00 00 00"));
  EXPECT_EQ(Exchange(Hex("0E 03 20 0F 24 00 30 04")), ErrorReply(0x0E, 0x14));
  EXPECT_EQ(Exchange(Hex("10 03 20 0F 24 00 30 02 01 00")), ErrorReply(0x10, 0x08));  // no class Set service
}

TEST_F(ParameterTableObjectTest, Refusals) {
  EXPECT_EQ(Exchange(Hex("0E 03 20 0F 24 BB 30 01")), ErrorReply(0x0E, 0x16));        // instance 187
  EXPECT_EQ(Exchange(Hex("0E 04 20 0F 25 00 00 01 30 01")), ErrorReply(0x0E, 0x16));  // instance 256
  EXPECT_EQ(Exchange(Hex("01 02 20 0F 24 06")), ErrorReply(0x01, 0x08));              // no Get_Attributes_All
  EXPECT_EQ(Exchange(Hex("0E 03 20 0F 24 06 30 11")), ErrorReply(0x0E, 0x14));        // attribute 17
  EXPECT_EQ(Exchange(Hex("10 03 20 0F 24 06 30 07 01 61")), ErrorReply(0x10, 0x0E));  // the name
  EXPECT_EQ(Exchange(Hex("10 03 20 0F 24 06 30 01 32")), ErrorReply(0x10, 0x13));
  EXPECT_EQ(Exchange(Hex("10 03 20 0F 24 06 30 01 32 00 00")), ErrorReply(0x10, 0x15));
  EXPECT_EQ(Exchange(Hex("0E 03 20 0F 24 06 30 01 00")), ErrorReply(0x0E, 0x15));
  EXPECT_TRUE(drive_.log.empty());
}

TEST_F(ParameterTableObjectTest, AccessErrorsMapAsFor0x64) {
  drive_.errors[0x0011] = AccessError::kOutOfRange;  // the inverter's own refusal
  EXPECT_EQ(Exchange(Hex("10 03 20 0F 24 08 30 01 40 1F")), ErrorReply(0x10, 0x09));
  drive_.errors[0x0011] = AccessError::kNotWritableWhileRunning;
  EXPECT_EQ(Exchange(Hex("10 03 20 0F 24 08 30 01 40 1F")), ErrorReply(0x10, 0x10));
  drive_.registers.erase(0x0009);  // a register the inverter lacks: the instance exists, its value not
  EXPECT_EQ(Exchange(Hex("0E 03 20 0F 24 06 30 01")), ErrorReply(0x0E, 0x14));
  drive_.link_down = true;
  EXPECT_EQ(Exchange(Hex("0E 03 20 0F 24 76 30 01")), ErrorReply(0x0E, 0x10));
}

}  // namespace
}  // namespace cip::drive
