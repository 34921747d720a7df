// The simulated inverter's registers, trips, resets, power cycles and EEPROM image.
#include <gtest/gtest.h>

#include <cstdint>
#include <initializer_list>
#include <string>

#include "inverter_model_fixture.h"

namespace sim::test {
namespace {

using InverterModelTest = InverterModelFixture;

void RunAt60Hz(InverterModel& m) {
  m.Write(reg::kFa07, 6000, WriteTarget::kRamOnly);
  m.Write(reg::kFa06, 0xC400, WriteTarget::kRamOnly);
}

// ---- Registers -------------------------------------------------------------------------------------

TEST_F(InverterModelTest, DefaultsFromTheTable) {
  EXPECT_EQ(R(reg::kCmod), 1);
  EXPECT_EQ(R(reg::kAcc), 100);
  EXPECT_EQ(R(reg::kFh), 0x1F40);
  EXPECT_EQ(R(reg::kFe70), 48);  // VF-MB1: 4.8 A
  EXPECT_EQ(R(0xC001), 1);
  InverterModel s15(Model::kVfS15);
  EXPECT_EQ(*s15.Read(reg::kFe70), 166);
  EXPECT_EQ(*s15.Read(reg::kVb), 30);
}

TEST_F(InverterModelTest, NonExistentNumbers) {
  for (const std::uint16_t number : std::initializer_list<std::uint16_t>{0x0001, 0x000A, 0xFE0A, 0xFFFF, 0xFA52}) {
    EXPECT_EQ(m_.Read(number).status(), base::NotFound()) << std::hex << number;
    EXPECT_EQ(Try(number, 0), WriteOutcome::kNoSuchRegister) << std::hex << number;
  }
  // fmod 12-14 exist on VF-S15 only.
  EXPECT_EQ(Try(reg::kFmod, 14), WriteOutcome::kOutOfRange);
  InverterModel s15(Model::kVfS15);
  EXPECT_TRUE(s15.Write(reg::kFmod, 14, WriteTarget::kRamOnly).ok());
}

TEST_F(InverterModelTest, MonitorsAreReadOnlyAndOptionRegistersWritable) {
  EXPECT_EQ(Try(reg::kFd01, 0), WriteOutcome::kReadOnly);
  EXPECT_EQ(Try(0xFE36, 0), WriteOutcome::kReadOnly);
  EXPECT_EQ(Try(reg::kFc90, 0), WriteOutcome::kReadOnly);
  EXPECT_EQ(Try(reg::kFe10, 0), WriteOutcome::kReadOnly);
  // The option writes its actual IP address, drive status and version through the drive link.
  P(0xC524, 192);
  EXPECT_EQ(R(0xC524), 192);
  P(0xFD67, 0x0101);
  EXPECT_EQ(R(0xFD67), 0x0101);
}

TEST_F(InverterModelTest, RangesIncludingRunTimeChecks) {
  EXPECT_EQ(Try(reg::kAcc, 0), WriteOutcome::kOutOfRange);
  EXPECT_EQ(Try(reg::kAcc, 60001), WriteOutcome::kOutOfRange);
  EXPECT_EQ(Try(reg::kFh, 2999), WriteOutcome::kOutOfRange);
  EXPECT_EQ(Try(0x0130, 256), WriteOutcome::kOutOfRange);  // seed 004 §9: f130 = 256 refused
  EXPECT_EQ(Try(0x0130, 7), WriteOutcome::kOk);
  EXPECT_EQ(Try(reg::kFa23, 0x0001), WriteOutcome::kOutOfRange);  // reserved bit
  EXPECT_EQ(Try(reg::kFa23, 0x1382), WriteOutcome::kOk);
  EXPECT_EQ(Try(reg::kC523, 3), WriteOutcome::kOutOfRange);  // 0.1-0.4 s
  EXPECT_EQ(Try(reg::kC523, 5), WriteOutcome::kOk);
  EXPECT_EQ(Try(reg::kC523, 0), WriteOutcome::kOk);
  EXPECT_EQ(Try(reg::kC001, 4), WriteOutcome::kOutOfRange);  // reserved menu entry
  EXPECT_EQ(Try(reg::kC021, 24), WriteOutcome::kOutOfRange);
  EXPECT_EQ(Try(reg::kC021, 35), WriteOutcome::kOk);
}

TEST_F(InverterModelTest, WrittenValuesReadBackExactly) {
  int written = 0;
  for (const RegisterInfo& r : AllRegisters()) {
    // Actions that read back 0 (typ, f899, FA30's trip request) and the command words are tested apart.
    if (r.access == Access::kReadOnly || r.storage == StorageClass::kMonitor || r.number == reg::kTyp ||
        r.number == reg::kF899 || r.number == reg::kFa06 || r.number == reg::kFa00 || r.number == reg::kFa30) {
      continue;
    }
    const std::int32_t value = r.max(Model::kVfMb1);
    const WriteResult w = m_.Write(r.number, r.ToWord(value), WriteTarget::kRamOnly);
    if (!w.ok()) continue;  // run-time limits (ll above ul and the like)
    ++written;
    EXPECT_EQ(R(r.number), r.ToWord(value)) << r.title;
  }
  EXPECT_GT(written, 150);
}

TEST_F(InverterModelTest, WriteDuringRunRefusal) {
  RunAt60Hz(m_);
  Wait(kSecond);
  EXPECT_TRUE(m_.running());
  EXPECT_EQ(Try(reg::kFh, 6000), WriteOutcome::kNotWritableWhileRunning);
  EXPECT_EQ(Try(reg::kCmod, 4), WriteOutcome::kNotWritableWhileRunning);
  EXPECT_EQ(Try(reg::kAcc, 50), WriteOutcome::kOk);  // write during run enabled
  EXPECT_EQ(Try(reg::kFh, 2000), WriteOutcome::kOutOfRange);  // the range check comes first
  P(reg::kFa06, 0xC000);
  Wait(500 * kMilli);
  EXPECT_EQ(Try(reg::kFh, 6000), WriteOutcome::kNotWritableWhileRunning);  // still decelerating
  Wait(10 * kSecond);
  EXPECT_FALSE(m_.running());
  EXPECT_EQ(Try(reg::kFh, 6000), WriteOutcome::kOk);
}

// ---- W vs P, EEPROM, power cycle -------------------------------------------------------------------

TEST_F(InverterModelTest, WWritesEepromAndCountsPWritesRamOnly) {
  W(reg::kAcc, 50);
  EXPECT_EQ(m_.EepromValue(reg::kAcc), 50);
  EXPECT_EQ(m_.EepromWriteCount(reg::kAcc), 1u);
  P(reg::kAcc, 70);
  EXPECT_EQ(R(reg::kAcc), 70);
  EXPECT_EQ(m_.EepromValue(reg::kAcc), 50);
  EXPECT_EQ(m_.EepromWriteCount(reg::kAcc), 1u);
  W(reg::kAcc, 50);
  EXPECT_EQ(m_.EepromWriteCount(reg::kAcc), 2u);
  W(reg::kFa07, 1000);  // RAM-only: W is P
  EXPECT_EQ(m_.EepromWriteCount(reg::kFa07), 0u);
  EXPECT_EQ(m_.EepromValue(reg::kFa07), 0);

  P(reg::kAcc, 70);
  m_.PowerCycle();
  EXPECT_EQ(R(reg::kAcc), 50);  // the EEPROM value returns
  EXPECT_EQ(R(reg::kFa07), 0);
}

TEST_F(InverterModelTest, PowerCycleSemantics) {
  RunAt60Hz(m_);
  Wait(8 * kSecond);
  m_.Trip(trip_code::kOptionCommunication);
  P(0xC524, 10);
  const std::uint64_t hours_before = m_.operation_micros();
  m_.PowerCycle();
  EXPECT_FALSE(m_.tripped());
  EXPECT_EQ(R(reg::kFd00), 0);
  EXPECT_EQ(R(reg::kFa06), 0);
  EXPECT_EQ(R(0xC524), 0);  // option-written RAM registers too
  EXPECT_EQ(R(reg::kFe10), trip_code::kOptionCommunication);  // the history stays
  EXPECT_EQ(m_.operation_micros(), hours_before);
  EXPECT_TRUE(m_.in_reset(t_));
  EXPECT_EQ(m_.ResetInProgressUntil(), t_ + kSecond);
  EXPECT_FALSE(m_.in_reset(t_ + kSecond));
}

TEST_F(InverterModelTest, PowerOnSilenceStartsAtTheFirstAdvance) {
  InverterModel m(Model::kVfMb1);
  m.Advance(5 * kSecond);
  EXPECT_TRUE(m.in_reset(5 * kSecond));
  EXPECT_TRUE(m.in_reset(6 * kSecond - 1));
  EXPECT_FALSE(m.in_reset(6 * kSecond));
}

TEST_F(InverterModelTest, EffectiveAfterResetValues) {
  W(0xC500, 1);  // protocol: EtherNet/IP, (*3)
  EXPECT_EQ(R(0xC500), 1);
  EXPECT_EQ(m_.ActiveValue(0xC500), 0);
  m_.PowerCycle();
  EXPECT_EQ(m_.ActiveValue(0xC500), 1);
  W(0xC500, 0);
  W(reg::kF899, 1);  // communication function reset
  EXPECT_EQ(m_.ActiveValue(0xC500), 0);
  EXPECT_EQ(R(reg::kF899), 0);
  EXPECT_TRUE(m_.in_reset(t_));
  EXPECT_EQ(m_.ActiveValue(reg::kAcc), 100);  // immediate registers: the current value
}

TEST_F(InverterModelTest, TypResetsParametersAndReadsZero) {
  W(reg::kAcc, 30);
  W(reg::kUl, 5000);
  W(reg::kTyp, 2);  // 60 Hz default setting
  EXPECT_EQ(R(reg::kUl), 6000);
  EXPECT_EQ(R(reg::kAcc), 30);
  EXPECT_EQ(R(reg::kTyp), 0);
  W(reg::kTyp, 3);  // default setting 1
  EXPECT_EQ(R(reg::kAcc), 100);
  EXPECT_EQ(m_.EepromValue(reg::kAcc), 100);
  EXPECT_EQ(m_.EepromWriteCount(reg::kTyp), 0u);
}

TEST_F(InverterModelTest, EepromImageRoundTrip) {
  W(reg::kAcc, 55);
  W(reg::kAcc, 56);
  P(reg::kDec, 77);  // RAM only: not in the image
  W(0xC505, 192);
  RunAt60Hz(m_);
  Wait(7200 * kSecond, kSecond);
  m_.Trip(trip_code::kEmergencyStop);
  const std::string image = m_.SerializeEeprom();

  InverterModel copy(Model::kVfMb1);
  ASSERT_TRUE(copy.LoadEeprom(image));
  EXPECT_EQ(*copy.Read(reg::kAcc), 56);
  EXPECT_EQ(copy.EepromWriteCount(reg::kAcc), 2u);
  EXPECT_EQ(*copy.Read(reg::kDec), 100);
  EXPECT_EQ(*copy.Read(0xC505), 192);
  EXPECT_EQ(*copy.Read(reg::kFe14), 2);
  EXPECT_EQ(*copy.Read(reg::kFe10), trip_code::kEmergencyStop);
  EXPECT_EQ(*copy.Read(reg::kFe77), *m_.Read(reg::kFe77));
  EXPECT_EQ(copy.SerializeEeprom(), image);
}

TEST_F(InverterModelTest, EepromImageRejectsGarbageAndTheOtherModel) {
  const std::string image = m_.SerializeEeprom();
  InverterModel s15(Model::kVfS15);
  EXPECT_FALSE(s15.LoadEeprom(image));
  EXPECT_FALSE(m_.LoadEeprom("format 1\nmodel vf-mb1\nreg 0009 x 1\n"));
  EXPECT_FALSE(m_.LoadEeprom("format 1\nmodel vf-mb1\nbogus 1\n"));
  EXPECT_FALSE(m_.LoadEeprom("model vf-mb1\n"));  // no format line
  W(reg::kAcc, 42);
  EXPECT_FALSE(m_.LoadEeprom("format 1\nmodel vf-mb1\nreg 0009 7\n"));
  EXPECT_EQ(R(reg::kAcc), 42);  // unchanged after a failed load
  // Unknown numbers and values out of range are skipped; missing registers get their defaults.
  ASSERT_TRUE(m_.LoadEeprom("format 1\nmodel vf-mb1\nreg 0001 5 1\nreg 0011 1 1\nreg 0010 33 4\n"));
  EXPECT_EQ(R(reg::kFh), 8000);
  EXPECT_EQ(R(reg::kDec), 33);
  EXPECT_EQ(R(reg::kAcc), 100);
}

// ---- Trips -----------------------------------------------------------------------------------------

TEST_F(InverterModelTest, TripHoldsMonitorsAndHistoryShifts) {
  RunAt60Hz(m_);
  Wait(8 * kSecond);
  const std::uint16_t current = R(reg::kFd03);
  m_.Trip(trip_code::kOptionFault);
  EXPECT_TRUE(m_.tripped());
  EXPECT_EQ(R(reg::kFc90), 55);
  EXPECT_EQ(R(reg::kFd00), 0);
  EXPECT_EQ(R(reg::kFe00), 6000);
  EXPECT_EQ(R(reg::kFe01), 0x6400);
  EXPECT_EQ(R(reg::kFe02), 6000);
  EXPECT_EQ(R(reg::kFe03), current);
  EXPECT_EQ(R(reg::kFe05), 10000);
  EXPECT_EQ(R(reg::kFe10), 55);
  m_.Trip(trip_code::kEmergencyStop);  // the first trip holds
  EXPECT_EQ(R(reg::kFc90), 55);
  EXPECT_FALSE(m_.FaultReset());  // e-23 needs a power cycle (assumed as err8)
  m_.PowerCycle();
  EXPECT_EQ(R(reg::kFe00), 0);  // live again
  for (std::uint8_t code : {std::uint8_t{1}, std::uint8_t{2}, std::uint8_t{3}, std::uint8_t{4}}) {
    m_.Trip(code);
    ASSERT_TRUE(m_.FaultReset());
  }
  EXPECT_EQ(R(reg::kFe10), 4);
  EXPECT_EQ(R(0xFE11), 3);
  EXPECT_EQ(R(0xFE12), 2);
  EXPECT_EQ(R(reg::kFe13), 1);
  EXPECT_EQ(R(reg::kFc90), 0);
}

TEST_F(InverterModelTest, FaultResetOnlyOnTheRisingEdge) {
  m_.Trip(trip_code::kEmergencyStop);
  P(reg::kFa06, 0x0000);
  EXPECT_TRUE(m_.Write(reg::kFa06, 0x2000, WriteTarget::kRamOnly).no_reply);
  EXPECT_FALSE(m_.tripped());
  EXPECT_TRUE(m_.in_reset(t_));
  Wait(2 * kSecond);
  EXPECT_FALSE(m_.in_reset(t_));
  // Not tripped: the edge still gets no reply, and the bit stays set.
  EXPECT_TRUE(m_.Write(reg::kFa06, 0x2000, WriteTarget::kRamOnly).no_reply);
  EXPECT_EQ(R(reg::kFa06), 0x2000);
  m_.Trip(trip_code::kEmergencyStop);
  const WriteResult again = m_.Write(reg::kFa06, 0x2000, WriteTarget::kRamOnly);
  EXPECT_FALSE(again.no_reply);  // 1 -> 1 is no edge
  EXPECT_TRUE(m_.tripped());
  P(reg::kFa06, 0x0000);
  P(reg::kFa06, 0x2000);
  EXPECT_FALSE(m_.tripped());
}

TEST_F(InverterModelTest, ResetTerminalEdge) {
  m_.Trip(trip_code::kEmergencyStop);
  m_.SetTerminal(Terminal::kRes, true);  // f113 = 8: RES
  EXPECT_FALSE(m_.tripped());
  m_.Trip(trip_code::kEmergencyStop);
  m_.SetTerminal(Terminal::kRes, true);  // already on: no edge
  EXPECT_TRUE(m_.tripped());
}

TEST_F(InverterModelTest, Err8ClearsOnlyWithPowerCycleOrF899) {
  m_.Trip(trip_code::kOptionCommunication);
  P(reg::kFa06, 0x2000);
  EXPECT_TRUE(m_.tripped());
  W(reg::kF899, 1);
  EXPECT_FALSE(m_.tripped());
}

// ---- Time counters ---------------------------------------------------------------------------------

TEST_F(InverterModelTest, CumulativeOperationHoursCountRunTimeOnly) {
  const std::uint16_t on_before = R(reg::kFe80);
  RunAt60Hz(m_);
  Wait(9000 * kSecond, kSecond);  // 2.5 h running
  EXPECT_EQ(R(reg::kFe14), 2);
  P(reg::kFa06, 0xC000);
  Wait(3600 * kSecond, kSecond);  // stopped (after a 7.5 s deceleration)
  EXPECT_EQ(R(reg::kFe14), 2);
  RunAt60Hz(m_);
  Wait(1800 * kSecond, kSecond);
  EXPECT_EQ(R(reg::kFe14), 3);
  EXPECT_EQ(R(reg::kFe80), on_before + 4);
}

TEST_F(InverterModelTest, DeterministicForTheSameCalls) {
  auto run = [](InverterModel& m) {
    hal::Micros t = 0;
    m.Advance(t);
    m.Write(reg::kFa07, 4321, WriteTarget::kRamOnly);
    m.Write(reg::kFa06, 0xC400, WriteTarget::kRamOnly);
    m.SetLoadTorque(5000);
    for (int i = 0; i < 1000; ++i) m.Advance(t += 3 * kMilli + static_cast<hal::Micros>(i % 7));
    m.Write(reg::kFa06, 0xC600, WriteTarget::kRamOnly);
    for (int i = 0; i < 1000; ++i) m.Advance(t += 11 * kMilli);
  };
  InverterModel a(Model::kVfS15);
  InverterModel b(Model::kVfS15);
  run(a);
  run(b);
  for (const RegisterInfo& r : AllRegisters()) {
    EXPECT_EQ(*a.Read(r.number), *b.Read(r.number)) << r.title;
  }
}

}  // namespace
}  // namespace sim::test
