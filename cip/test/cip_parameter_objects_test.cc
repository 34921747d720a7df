// The Parameter objects 0x64/0x65 and Motor Data 0x28 through the message router (seed 000 §4.5, §4.8,
// §4.9; docs/drive-objects.md): deferred replies (first pass pends with one access, a retry before the
// completion pends again without a second one, the retry after it answers exact bytes), instance
// numbering, class attributes, read-only monitors, every AccessError as a CIP status, refusals, unit
// conversions, and data sizes.
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
using drive_link::AccessResult;
using drive_link::WriteMode;
using Access = drive_link::test::ScriptedDriveRegisters::Access;

constexpr Access ReadOf(std::uint16_t number) { return Access{false, number, 0, WriteMode::kRamOnly}; }
constexpr Access WriteOf(std::uint16_t number, std::uint16_t value) {
  return Access{true, number, value, WriteMode::kRamAndEeprom};
}

class DriveObjectsTest : public ::testing::Test {
 protected:
  DriveObjectsTest() {
    auto& r = h_.drive.registers;
    r[0x0000] = 1;     // au1
    r[0x0003] = 1;     // cmod
    r[0x0004] = 2;     // fmod
    r[0x0009] = 100;   // acc 10.0 s
    r[0x0011] = 8000;  // fh 80.00 Hz (§4.8's example)
    r[0x0014] = 6000;  // vl 60.00 Hz
    r[0x0268] = 6000;  // f268
    r[0x0405] = 75;    // f405 0.75 kW
    r[0x0409] = 2000;  // vlv 200.0 V
    r[0x0415] = 34;    // f415 3.4 A
    r[0x0417] = 1710;  // f417 1710 rpm
    r[0x0856] = 2;     // f856 pole pairs
    r[0xC001] = 1;
    r[0xFA07] = 0;
    r[0xFD00] = 6000;
    r[0xFE03] = 0x1388;
  }

  cip::drive::test::DriveObjectsHarness h_;
};

// --- Deferred replies -------------------------------------------------------------------------------

TEST_F(DriveObjectsTest, FirstPassPendsWithExactlyOneAccess) {
  const Bytes get_acc = Hex("0E 04 20 64 25 00 09 40 30 03");
  const cip::drive::test::PassResult first = h_.Pass(get_acc);
  EXPECT_TRUE(first.pending);
  EXPECT_EQ(h_.drive.log, (std::vector<Access>{ReadOf(0x0009)}));
  EXPECT_FALSE(h_.journal.ReadyToRetry(1));

  // A retry before the completion pends again and starts nothing.
  const cip::drive::test::PassResult early = h_.Pass(get_acc);
  EXPECT_TRUE(early.pending);
  EXPECT_EQ(h_.drive.log.size(), 1u);

  h_.drive.CompleteAll();
  EXPECT_TRUE(h_.journal.ReadyToRetry(1));
  const cip::drive::test::PassResult retry = h_.Pass(get_acc);
  EXPECT_FALSE(retry.pending);
  EXPECT_EQ(retry.reply, Hex("8E 00 00 00 64 00"));
  EXPECT_EQ(h_.drive.log.size(), 1u);
  h_.journal.OnRequestFinished(1);
  EXPECT_EQ(h_.journal.active_requesters(), 0u);
}

TEST_F(DriveObjectsTest, FinishedRequestIsForgotten) {
  const Bytes get_acc = Hex("0E 04 20 64 25 00 09 40 30 03");
  EXPECT_TRUE(h_.Pass(get_acc).pending);
  h_.journal.OnRequestFinished(1);  // the connection went away
  h_.drive.CompleteAll();
  EXPECT_EQ(h_.journal.completions_ignored(), 1u);
  EXPECT_FALSE(h_.journal.ReadyToRetry(1));
  // The same bytes again are a new request: a new access.
  EXPECT_TRUE(h_.Pass(get_acc).pending);
  EXPECT_EQ(h_.drive.log.size(), 2u);
}

TEST_F(DriveObjectsTest, RequestersDoNotShareAnswers) {
  const Bytes get_cmod = Hex("0E 04 20 64 25 00 03 40 30 03");
  const Bytes get_fmod = Hex("0E 04 20 64 25 00 04 40 30 03");
  EXPECT_TRUE(h_.Pass(get_cmod, 1).pending);
  EXPECT_TRUE(h_.Pass(get_fmod, 2).pending);
  ASSERT_TRUE(h_.drive.CompleteWith(AccessResult{AccessError::kNone, 0, 1}));
  EXPECT_TRUE(h_.journal.ReadyToRetry(1));
  EXPECT_FALSE(h_.journal.ReadyToRetry(2));
  EXPECT_EQ(h_.Pass(get_cmod, 1).reply, Hex("8E 00 00 00 01 00"));
  ASSERT_TRUE(h_.drive.CompleteWith(AccessResult{AccessError::kNone, 0, 2}));
  EXPECT_EQ(h_.Pass(get_fmod, 2).reply, Hex("8E 00 00 00 02 00"));
}

TEST_F(DriveObjectsTest, MultipleServicePacketRunsEachAccessOnce) {
  // Get 4003 (cmod) and 4004 (fmod): the router stops at the first pending member, so the second
  // access starts on the first retry; the third pass answers both.
  const Bytes packet = Hex(
      "0A 02 20 02 24 01 | 02 00 06 00 10 00 | 0E 04 20 64 25 00 03 40 30 03 | 0E 04 20 64 25 00 04 40 30 03");
  int passes = 0;
  EXPECT_EQ(h_.Exchange(packet, &passes),
            Hex("8A 00 00 00 | 02 00 06 00 0C 00 | 8E 00 00 00 01 00 | 8E 00 00 00 02 00"));
  EXPECT_EQ(passes, 3);
  EXPECT_EQ(h_.drive.log, (std::vector<Access>{ReadOf(0x0003), ReadOf(0x0004)}));
}

TEST_F(DriveObjectsTest, UnconnectedSendOfAGetIsDeferredToo) {
  // Unconnected_Send, route port 1 slot 0, embedding Get 0x65/0x0009/3.
  const Bytes request = Hex("52 02 20 06 24 01 | 0A F0 | 0A 00 | 0E 04 20 65 25 00 09 00 30 03 | 01 00 01 00");
  EXPECT_EQ(h_.Exchange(request), Hex("8E 00 00 00 64 00"));
  EXPECT_EQ(h_.drive.log, (std::vector<Access>{ReadOf(0x0009)}));
}

// --- Parameter object 0x64 ----------------------------------------------------------------------------

TEST_F(DriveObjectsTest, Parameter64ClassAttributes) {
  EXPECT_EQ(h_.Exchange(Hex("0E 03 20 64 24 00 30 01")), Hex("8E 00 00 00 01 00"));
  EXPECT_EQ(h_.Exchange(Hex("0E 03 20 64 24 00 30 02")), Hex("8E 00 00 00 FF 7F"));  // 32767
  EXPECT_EQ(h_.Exchange(Hex("0E 03 20 64 24 00 30 03")), Hex("8E 00 00 00 FE 1F"));  // 8190
  EXPECT_EQ(h_.Exchange(Hex("0E 03 20 64 24 00 30 06")), Hex("8E 00 00 00 07 00"));
  EXPECT_EQ(h_.Exchange(Hex("0E 03 20 64 24 00 30 07")), Hex("8E 00 00 00 03 00"));
  EXPECT_EQ(h_.Exchange(Hex("0E 03 20 64 24 00 30 04")), Hex("8E 00 14 00"));
  EXPECT_EQ(h_.Exchange(Hex("0E 03 20 64 24 00 30 05")), Hex("8E 00 14 00"));
  EXPECT_EQ(h_.Exchange(Hex("10 03 20 64 24 00 30 01 02 00")), Hex("90 00 08 00"));  // class: Get only
  EXPECT_EQ(h_.Exchange(Hex("01 02 20 64 24 00")), Hex("81 00 08 00"));
  EXPECT_TRUE(h_.drive.log.empty());
}

TEST_F(DriveObjectsTest, Parameter64InstanceNumbering) {
  // §4.8's examples: cmod 0003 -> 4003, f268 0268 -> 4268, fe03 FE03 -> 7E03; au1 0000 -> 4000.
  EXPECT_EQ(h_.Exchange(Hex("0E 04 20 64 25 00 03 40 30 03")), Hex("8E 00 00 00 01 00"));
  EXPECT_EQ(h_.Exchange(Hex("0E 04 20 64 25 00 68 42 30 03")), Hex("8E 00 00 00 70 17"));
  EXPECT_EQ(h_.Exchange(Hex("0E 04 20 64 25 00 03 7E 30 03")), Hex("8E 00 00 00 88 13"));
  EXPECT_EQ(h_.Exchange(Hex("0E 04 20 64 25 00 00 40 30 03")), Hex("8E 00 00 00 01 00"));
  // §4.8: the highest frequency reads 1F40h (80 Hz).
  EXPECT_EQ(h_.Exchange(Hex("0E 04 20 64 25 00 11 40 30 03")), Hex("8E 00 00 00 40 1F"));
  EXPECT_EQ(h_.drive.log, (std::vector<Access>{ReadOf(0x0003), ReadOf(0x0268), ReadOf(0xFE03), ReadOf(0x0000),
                                               ReadOf(0x0011)}));
  EXPECT_EQ(ParameterInstance(ParameterClass::k64, 0xFE03), 0x7E03u);
  EXPECT_EQ(ParameterInstance(ParameterClass::k64, 0x0268), 0x4268u);
  EXPECT_EQ(ParameterInstance(ParameterClass::k64, 0xC001), std::nullopt);
  EXPECT_EQ(ParameterInstance(ParameterClass::k64, 0x000A), std::nullopt);
  EXPECT_EQ(ParameterNumber(ParameterClass::k64, 0x7000), 0xF000);
  EXPECT_EQ(ParameterNumber(ParameterClass::k64, 0x4999), 0x0999);
}

TEST_F(DriveObjectsTest, Parameter64SetWritesRamAndEeprom) {
  // §4.8: acc = 5 s is 50 = 32h at 4009.
  EXPECT_EQ(h_.Exchange(Hex("10 04 20 64 25 00 09 40 30 03 32 00")), Hex("90 00 00 00"));
  EXPECT_EQ(h_.drive.log, (std::vector<Access>{WriteOf(0x0009, 50)}));
  EXPECT_EQ(h_.drive.registers[0x0009], 50);
  EXPECT_EQ(h_.Exchange(Hex("0E 04 20 64 25 00 09 40 30 03")), Hex("8E 00 00 00 32 00"));
}

TEST_F(DriveObjectsTest, Parameter64InstancesThatDoNotExist) {
  for (const char* instance : {"FF 3F", "00 50", "FF 6F", "00 80", "0A 40", "0F 40", "FA 4F", "0B 7E", "FF FF"}) {
    EXPECT_EQ(h_.Exchange(Hex(std::string("0E 04 20 64 25 00 ") + instance + " 30 03")), Hex("8E 00 16 00"))
        << instance;
  }
  // 32-bit instance segment beyond 16 bits.
  EXPECT_EQ(h_.Exchange(Hex("0E 05 20 64 26 00 03 40 01 00 30 03")), Hex("8E 00 16 00"));
  EXPECT_TRUE(h_.drive.log.empty());
}

TEST_F(DriveObjectsTest, MonitorsAreReadOnly) {
  // §4.8: "Monitor parameter can access Get only": FC00-FEFF in both classes, refused without an access.
  EXPECT_EQ(h_.Exchange(Hex("10 04 20 64 25 00 03 7E 30 03 00 00")), Hex("90 00 0E 00"));
  EXPECT_EQ(h_.Exchange(Hex("10 04 20 64 25 00 00 7C 30 03 00 00")), Hex("90 00 0E 00"));
  EXPECT_EQ(h_.Exchange(Hex("10 04 20 65 25 00 00 FD 30 03 00 00")), Hex("90 00 0E 00"));
  EXPECT_EQ(h_.Exchange(Hex("10 04 20 65 25 00 99 FE 30 03 00 00")), Hex("90 00 0E 00"));
  EXPECT_TRUE(h_.drive.log.empty());
  // ... and readable.
  EXPECT_EQ(h_.Exchange(Hex("0E 04 20 65 25 00 00 FD 30 03")), Hex("8E 00 00 00 70 17"));
  // A command register (FA07) is not a monitor: settable, RAM and EEPROM as any explicit write.
  EXPECT_EQ(h_.Exchange(Hex("10 04 20 64 25 00 07 7A 30 03 70 17")), Hex("90 00 00 00"));
  EXPECT_EQ(h_.drive.log, (std::vector<Access>{ReadOf(0xFD00), WriteOf(0xFA07, 6000)}));
}

TEST_F(DriveObjectsTest, OnlyAttributeThree) {
  for (const char* attribute : {"01", "02", "04", "64"}) {
    EXPECT_EQ(h_.Exchange(Hex(std::string("0E 04 20 64 25 00 09 40 30 ") + attribute)), Hex("8E 00 14 00"));
    EXPECT_EQ(h_.Exchange(Hex(std::string("10 04 20 65 25 00 09 00 30 ") + attribute + " 00 00")),
              Hex("90 00 14 00"));
  }
  EXPECT_EQ(h_.Exchange(Hex("0E 03 20 64 25 00 09 40")), Hex("8E 00 14 00"));  // no attribute
  EXPECT_EQ(h_.Exchange(Hex("01 03 20 64 25 00 09 40")), Hex("81 00 08 00"));  // no Get_Attributes_All
  EXPECT_EQ(h_.Exchange(Hex("05 03 20 65 25 00 09 00")), Hex("85 00 08 00"));
  EXPECT_TRUE(h_.drive.log.empty());
}

// --- Parameter object 0x65 ----------------------------------------------------------------------------

TEST_F(DriveObjectsTest, Parameter65ClassAttributes) {
  EXPECT_EQ(h_.Exchange(Hex("0E 03 20 65 24 00 30 01")), Hex("8E 00 00 00 01 00"));
  EXPECT_EQ(h_.Exchange(Hex("0E 03 20 65 24 00 30 02")), Hex("8E 00 00 00 FF FF"));
  EXPECT_EQ(h_.Exchange(Hex("0E 03 20 65 24 00 30 03")), Hex("8E 00 00 00 FF FF"));
  EXPECT_EQ(h_.Exchange(Hex("0E 03 20 65 24 00 30 06")), Hex("8E 00 00 00 07 00"));
  EXPECT_EQ(h_.Exchange(Hex("0E 03 20 65 24 00 30 07")), Hex("8E 00 00 00 03 00"));
}

TEST_F(DriveObjectsTest, Parameter65InstanceIsTheCommunicationNumber) {
  EXPECT_EQ(h_.Exchange(Hex("0E 03 20 65 24 09 30 03")), Hex("8E 00 00 00 64 00"));        // 8-bit instance
  EXPECT_EQ(h_.Exchange(Hex("0E 04 20 65 25 00 01 C0 30 03")), Hex("8E 00 00 00 01 00"));  // c001
  EXPECT_EQ(h_.Exchange(Hex("0E 04 20 65 25 00 03 FE 30 03")), Hex("8E 00 00 00 88 13"));  // fe03
  // §4.9: acc = 5 s writes 32h at instance 0009.
  EXPECT_EQ(h_.Exchange(Hex("10 03 20 65 24 09 30 03 32 00")), Hex("90 00 00 00"));
  EXPECT_EQ(h_.drive.log,
            (std::vector<Access>{ReadOf(0x0009), ReadOf(0xC001), ReadOf(0xFE03), WriteOf(0x0009, 50)}));
}

TEST_F(DriveObjectsTest, Parameter65InstancesThatDoNotExist) {
  // A-F endings (§8.9 (5)) and anything above FFFF; 0000 (au1) is the class, reached only through 0x64.
  EXPECT_EQ(h_.Exchange(Hex("0E 03 20 65 24 0A 30 03")), Hex("8E 00 16 00"));
  EXPECT_EQ(h_.Exchange(Hex("0E 04 20 65 25 00 0F C0 30 03")), Hex("8E 00 16 00"));
  EXPECT_EQ(h_.Exchange(Hex("0E 05 20 65 26 00 00 00 01 00 30 03")), Hex("8E 00 16 00"));
  // §4.9: "Refer to Class Attributes when the instance is 0": attribute 3 there is the instance count.
  EXPECT_EQ(h_.Exchange(Hex("0E 03 20 65 24 00 30 03")), Hex("8E 00 00 00 FF FF"));
  EXPECT_TRUE(h_.drive.log.empty());
}

// --- Errors -------------------------------------------------------------------------------------------

struct ErrorCase {
  AccessError error;
  std::uint8_t parameter_get;
  std::uint8_t parameter_set;
  std::uint8_t motor_get;
  std::uint8_t motor_set;
};

// docs/drive-objects.md "Access errors".
constexpr ErrorCase kErrorCases[] = {
    {AccessError::kNoSuchRegister, 0x16, 0x16, 0x14, 0x14},
    {AccessError::kOutOfRange, 0x09, 0x09, 0x09, 0x09},
    {AccessError::kNotWritableWhileRunning, 0x10, 0x10, 0x10, 0x10},
    {AccessError::kReadOnly, 0x0E, 0x0E, 0x0E, 0x0E},
    {AccessError::kReservedForScanner, 0x10, 0x10, 0x10, 0x10},
    {AccessError::kRefused, 0x0C, 0x19, 0x0C, 0x19},
    {AccessError::kLinkDown, 0x10, 0x10, 0x10, 0x10},
    {AccessError::kTimeout, 0x02, 0x02, 0x02, 0x02},
    {AccessError::kNetworkLost, 0x10, 0x10, 0x10, 0x10},
};

Bytes ErrorReply(std::uint8_t service, std::uint8_t general) {
  return Bytes{static_cast<std::uint8_t>(service | 0x80), 0x00, general, 0x00};
}

TEST_F(DriveObjectsTest, EveryAccessErrorHasItsStatus) {
  for (const ErrorCase& c : kErrorCases) {
    SCOPED_TRACE(drive_link::AccessErrorName(c.error));
    h_.drive.errors = {{0x0009, c.error}, {0x0415, c.error}};
    EXPECT_EQ(h_.Exchange(Hex("0E 04 20 64 25 00 09 40 30 03")), ErrorReply(0x0E, c.parameter_get));
    EXPECT_EQ(h_.Exchange(Hex("10 03 20 65 24 09 30 03 32 00")), ErrorReply(0x10, c.parameter_set));
    EXPECT_EQ(h_.Exchange(Hex("0E 03 20 28 24 01 30 06")), ErrorReply(0x0E, c.motor_get));
    EXPECT_EQ(h_.Exchange(Hex("10 03 20 28 24 01 30 06 22 00")), ErrorReply(0x10, c.motor_set));
  }
}

TEST_F(DriveObjectsTest, ErrorStatusTable) {
  for (const ErrorCase& c : kErrorCases) {
    EXPECT_EQ(AccessErrorStatus(c.error, AccessKind::kGet, MissingRegister::kNoSuchInstance),
              Error(static_cast<GeneralStatus>(c.parameter_get)));
    EXPECT_EQ(AccessErrorStatus(c.error, AccessKind::kSet, MissingRegister::kNoSuchAttribute),
              Error(static_cast<GeneralStatus>(c.motor_set)));
  }
  EXPECT_EQ(AccessErrorStatus(AccessError::kNone, AccessKind::kGet, MissingRegister::kNoSuchInstance), Success());
  EXPECT_EQ(RefusalStatus(base::StatusCode::kResourceExhausted), Error(GeneralStatus::kResourceUnavailable));
  EXPECT_EQ(RefusalStatus(base::StatusCode::kFailedPrecondition), Error(GeneralStatus::kDeviceStateConflict));
  EXPECT_EQ(RefusalStatus(base::StatusCode::kInternal), Error(kVendorSpecificError));
}

TEST_F(DriveObjectsTest, LinkDownAnswersAtOnce) {
  h_.drive.link_down = true;
  const cip::drive::test::PassResult get = h_.Pass(Hex("0E 04 20 64 25 00 09 40 30 03"));
  EXPECT_FALSE(get.pending);
  EXPECT_EQ(get.reply, Hex("8E 00 10 00"));
  h_.journal.OnRequestFinished(1);
  const cip::drive::test::PassResult set = h_.Pass(Hex("10 03 20 28 24 01 30 0F AE 06"));
  EXPECT_FALSE(set.pending);
  EXPECT_EQ(set.reply, Hex("90 00 10 00"));
  h_.journal.OnRequestFinished(1);
  EXPECT_TRUE(h_.drive.log.empty());
}

TEST_F(DriveObjectsTest, PoolFullAnswersResourceUnavailableAtOnce) {
  h_.drive.busy_next = 1;
  const cip::drive::test::PassResult get = h_.Pass(Hex("0E 04 20 65 25 00 09 00 30 03"));
  EXPECT_FALSE(get.pending);
  EXPECT_EQ(get.reply, Hex("8E 00 02 00"));
  h_.journal.OnRequestFinished(1);
  EXPECT_EQ(h_.Exchange(Hex("0E 04 20 65 25 00 09 00 30 03")), Hex("8E 00 00 00 64 00"));  // room again
}

TEST_F(DriveObjectsTest, AFailedMemberDoesNotStopThePacket) {
  // MSP: the first Get fails (no such register), the second answers; 0x1E with both replies.
  h_.drive.errors = {{0x0003, AccessError::kNoSuchRegister}};
  const Bytes packet = Hex(
      "0A 02 20 02 24 01 | 02 00 06 00 10 00 | 0E 04 20 64 25 00 03 40 30 03 | 0E 04 20 64 25 00 04 40 30 03");
  EXPECT_EQ(h_.Exchange(packet), Hex("8A 00 1E 00 | 02 00 06 00 0A 00 | 8E 00 16 00 | 8E 00 00 00 02 00"));
}

// --- Motor Data 0x28 ----------------------------------------------------------------------------------

TEST_F(DriveObjectsTest, MotorDataClassAttributes) {
  EXPECT_EQ(h_.Exchange(Hex("0E 03 20 28 24 00 30 01")), Hex("8E 00 00 00 01 00"));
  EXPECT_EQ(h_.Exchange(Hex("0E 03 20 28 24 00 30 02")), Hex("8E 00 00 00 01 00"));
  EXPECT_EQ(h_.Exchange(Hex("0E 03 20 28 24 00 30 03")), Hex("8E 00 00 00 01 00"));
  EXPECT_EQ(h_.Exchange(Hex("0E 03 20 28 24 00 30 06")), Hex("8E 00 00 00 07 00"));
  EXPECT_EQ(h_.Exchange(Hex("0E 03 20 28 24 00 30 07")), Hex("8E 00 00 00 0F 00"));
  EXPECT_EQ(h_.Exchange(Hex("0E 03 20 28 24 00 30 04")), Hex("8E 00 14 00"));
  EXPECT_EQ(h_.Exchange(Hex("0E 03 20 28 24 02 30 01")), Hex("8E 00 16 00"));
  EXPECT_EQ(h_.Exchange(Hex("01 02 20 28 24 01")), Hex("81 00 08 00"));
}

TEST_F(DriveObjectsTest, MotorDataConstantAttributesNeedNoAccess) {
  EXPECT_EQ(h_.Exchange(Hex("0E 03 20 28 24 01 30 01")), Hex("8E 00 00 00 09 00"));
  EXPECT_EQ(h_.Exchange(Hex("0E 03 20 28 24 01 30 02")), Hex("8E 00 00 00 01 02 03 06 07 08 09 0C 0F"));
  EXPECT_EQ(h_.Exchange(Hex("0E 03 20 28 24 01 30 03")), Hex("8E 00 00 00 07"));
  EXPECT_TRUE(h_.drive.log.empty());
  for (const char* attribute : {"04", "05", "0A", "0B", "0D", "0E", "10"}) {
    EXPECT_EQ(h_.Exchange(Hex(std::string("0E 03 20 28 24 01 30 ") + attribute)), Hex("8E 00 14 00"));
  }
}

TEST_F(DriveObjectsTest, MotorDataReadsConvertUnits) {
  EXPECT_EQ(h_.Exchange(Hex("0E 03 20 28 24 01 30 06")), Hex("8E 00 00 00 22 00"));        // 3.4 A = 34 x 100 mA
  EXPECT_EQ(h_.Exchange(Hex("0E 03 20 28 24 01 30 07")), Hex("8E 00 00 00 C8 00"));        // 200.0 V -> 200 V
  EXPECT_EQ(h_.Exchange(Hex("0E 03 20 28 24 01 30 08")), Hex("8E 00 00 00 EE 02 00 00"));  // 0.75 kW = 750 W
  EXPECT_EQ(h_.Exchange(Hex("0E 03 20 28 24 01 30 09")), Hex("8E 00 00 00 3C 00"));        // 60.00 Hz -> 60
  EXPECT_EQ(h_.Exchange(Hex("0E 03 20 28 24 01 30 0C")), Hex("8E 00 00 00 04 00"));        // f856 2 -> 4 poles
  EXPECT_EQ(h_.Exchange(Hex("0E 03 20 28 24 01 30 0F")), Hex("8E 00 00 00 AE 06"));        // 1710 rpm
  EXPECT_EQ(h_.drive.log, (std::vector<Access>{ReadOf(0x0415), ReadOf(0x0409), ReadOf(0x0405), ReadOf(0x0014),
                                               ReadOf(0x0856), ReadOf(0x0417)}));
  // Rounding: 200.5 V -> 201 V, 50.49 Hz -> 50 Hz, 50.50 Hz -> 51 Hz.
  h_.drive.registers[0x0409] = 2005;
  EXPECT_EQ(h_.Exchange(Hex("0E 03 20 28 24 01 30 07")), Hex("8E 00 00 00 C9 00"));
  h_.drive.registers[0x0014] = 5049;
  EXPECT_EQ(h_.Exchange(Hex("0E 03 20 28 24 01 30 09")), Hex("8E 00 00 00 32 00"));
  h_.drive.registers[0x0014] = 5050;
  EXPECT_EQ(h_.Exchange(Hex("0E 03 20 28 24 01 30 09")), Hex("8E 00 00 00 33 00"));
}

TEST_F(DriveObjectsTest, MotorDataSetsConvertUnits) {
  EXPECT_EQ(h_.Exchange(Hex("10 03 20 28 24 01 30 06 2D 00")), Hex("90 00 00 00"));        // 4.5 A
  EXPECT_EQ(h_.Exchange(Hex("10 03 20 28 24 01 30 07 E6 00")), Hex("90 00 00 00"));        // 230 V
  EXPECT_EQ(h_.Exchange(Hex("10 03 20 28 24 01 30 08 F3 02 00 00")), Hex("90 00 00 00"));  // 755 W -> 76
  EXPECT_EQ(h_.Exchange(Hex("10 03 20 28 24 01 30 09 32 00")), Hex("90 00 00 00"));        // 50 Hz
  EXPECT_EQ(h_.Exchange(Hex("10 03 20 28 24 01 30 0F 72 06")), Hex("90 00 00 00"));        // 1650 rpm
  EXPECT_EQ(h_.drive.log, (std::vector<Access>{WriteOf(0x0415, 45), WriteOf(0x0409, 2300), WriteOf(0x0405, 76),
                                               WriteOf(0x0014, 5000), WriteOf(0x0417, 1650)}));
}

TEST_F(DriveObjectsTest, MotorDataRefusalsBeforeAnyAccess) {
  EXPECT_EQ(h_.Exchange(Hex("10 03 20 28 24 01 30 0C 04 00")), Hex("90 00 0E 00"));  // PoleCount
  EXPECT_EQ(h_.Exchange(Hex("10 03 20 28 24 01 30 01 09 00")), Hex("90 00 0E 00"));
  EXPECT_EQ(h_.Exchange(Hex("10 03 20 28 24 01 30 03 07")), Hex("90 00 0E 00"));
  EXPECT_EQ(h_.Exchange(Hex("10 03 20 28 24 01 30 04 00 00")), Hex("90 00 14 00"));
  // Values the parameter cannot hold: 6554 V, 656 Hz, 655355 W.
  EXPECT_EQ(h_.Exchange(Hex("10 03 20 28 24 01 30 07 9A 19")), Hex("90 00 09 00"));
  EXPECT_EQ(h_.Exchange(Hex("10 03 20 28 24 01 30 09 90 02")), Hex("90 00 09 00"));
  EXPECT_EQ(h_.Exchange(Hex("10 03 20 28 24 01 30 08 FB FF 09 00")), Hex("90 00 09 00"));
  EXPECT_EQ(h_.Exchange(Hex("10 03 20 28 24 01 30 08 FF FF FF FF")), Hex("90 00 09 00"));
  EXPECT_TRUE(h_.drive.log.empty());
  // The largest ones that fit.
  EXPECT_EQ(h_.Exchange(Hex("10 03 20 28 24 01 30 07 99 19")), Hex("90 00 00 00"));         // 6553 V
  EXPECT_EQ(h_.Exchange(Hex("10 03 20 28 24 01 30 08 FA FF 09 00")), Hex("90 00 00 00"));   // 655354 W
  EXPECT_EQ(h_.drive.log, (std::vector<Access>{WriteOf(0x0409, 65530), WriteOf(0x0405, 65535)}));
}

TEST(MotorDataUnitsTest, Conversions) {
  static_assert(VoltsFromVlv(2000) == 200);
  static_assert(VoltsFromVlv(2004) == 200);
  static_assert(VoltsFromVlv(65535) == 6554);
  static_assert(*VlvFromVolts(6553) == 65530);
  static_assert(!VlvFromVolts(6554).has_value());
  static_assert(WattsFromF405(65535) == 655350);
  static_assert(*F405FromWatts(754) == 75);
  static_assert(*F405FromWatts(755) == 76);
  static_assert(!F405FromWatts(0xFFFFFFFF).has_value());
  static_assert(HertzFromVl(65535) == 655);
  static_assert(*VlFromHertz(655) == 65500);
  static_assert(!VlFromHertz(656).has_value());
  static_assert(PoleCountFromF856(8) == 16);
  static_assert(PoleCountFromF856(0xFFFF) == 0xFFFF);
  SUCCEED();
}

// --- Data sizes (fuzz-like) ---------------------------------------------------------------------------

TEST_F(DriveObjectsTest, WrongDataSizesAreRefusedWithoutAnAccess) {
  struct Target {
    const char* path;  // class, instance, attribute
    std::size_t size;  // the value's size
  };
  const Target targets[] = {
      {"20 64 25 00 09 40 30 03", 2}, {"20 65 25 00 09 00 30 03", 2}, {"20 28 24 01 30 06", 2},
      {"20 28 24 01 30 07", 2},       {"20 28 24 01 30 08", 4},       {"20 28 24 01 30 09", 2},
      {"20 28 24 01 30 0F", 2},
  };
  for (const Target& target : targets) {
    const Bytes path = Hex(target.path);
    for (std::size_t size = 0; size <= 9; ++size) {
      if (size == target.size) continue;
      Bytes set = {0x10, static_cast<std::uint8_t>(path.size() / 2)};
      set.insert(set.end(), path.begin(), path.end());
      for (std::size_t i = 0; i < size; ++i) set.push_back(static_cast<std::uint8_t>(0xA5 ^ i));
      EXPECT_EQ(h_.Exchange(set), ErrorReply(0x10, size < target.size ? 0x13 : 0x15))
          << target.path << " size " << size;
      if (size == 0) continue;
      // A Get carrying data.
      Bytes get = set;
      get[0] = 0x0E;
      EXPECT_EQ(h_.Exchange(get), ErrorReply(0x0E, 0x15)) << target.path << " size " << size;
    }
  }
  EXPECT_TRUE(h_.drive.log.empty());
}

}  // namespace
}  // namespace cip::drive
