// FA30, the option unit fault request: the card's stand-in for the option connector's fault line
// (drive_link/drive_registers.h reg::kFa30, docs/simulator.md "Option unit fault request").
#include <gtest/gtest.h>

#include <initializer_list>

#include "inverter_model_fixture.h"

namespace sim::test {
namespace {

class InverterOptionFault : public InverterModelFixture {};

TEST_F(InverterOptionFault, Writing27TripsErr8AndReadsZero) {
  EXPECT_EQ(Try(reg::kFa30, 27), WriteOutcome::kOk);
  EXPECT_TRUE(m_.tripped());
  EXPECT_EQ(m_.trip(), 27);
  EXPECT_EQ(R(reg::kFc90), 27);
  EXPECT_EQ(R(reg::kFd01), 0x0003);  // FL + tripped (seed 003 §9.1 golden value)
  EXPECT_EQ(R(reg::kFa30), 0);
}

TEST_F(InverterOptionFault, SameStateAsTrip27) {
  InverterModel direct(Model::kVfMb1);
  direct.Advance(t_);
  direct.Trip(trip_code::kOptionCommunication);
  W(reg::kFa30, 27);
  for (std::uint16_t number : {reg::kFc90, reg::kFd01, reg::kFe10, reg::kFa30}) {
    EXPECT_EQ(R(number), *direct.Read(number)) << std::hex << number;
  }
}

TEST_F(InverterOptionFault, WritingZeroDoesNothing) {
  EXPECT_EQ(Try(reg::kFa30, 0), WriteOutcome::kOk);
  EXPECT_FALSE(m_.tripped());
  EXPECT_EQ(R(reg::kFd01), 0x4800);
  EXPECT_EQ(m_.EepromWriteCount(reg::kFa30), 0u);
}

TEST_F(InverterOptionFault, OtherValuesAreADataError) {
  for (const std::uint16_t word : std::initializer_list<std::uint16_t>{1, 26, 28, 0x1B00, 0xFFFF}) {
    EXPECT_EQ(Try(reg::kFa30, word), WriteOutcome::kOutOfRange) << word;
    EXPECT_EQ(m_.Write(reg::kFa30, word, WriteTarget::kRamAndEeprom).outcome, WriteOutcome::kOutOfRange)
        << word;
  }
  EXPECT_FALSE(m_.tripped());
}

TEST_F(InverterOptionFault, TripsWhileRunningAndCutsTheOutput) {
  P(reg::kFa07, 6000);
  P(reg::kFa06, 0xC400);
  Wait(12 * kSecond);
  ASSERT_EQ(m_.output_frequency(), 6000);
  EXPECT_EQ(Try(reg::kFa30, 27), WriteOutcome::kOk);
  EXPECT_EQ(m_.output_frequency(), 0);
  EXPECT_EQ(R(reg::kFc90), 27);
}

TEST_F(InverterOptionFault, OnlyAPowerCycleClearsIt) {
  P(reg::kFa30, 27);
  EXPECT_FALSE(m_.FaultReset());
  P(reg::kFa06, 0x2000);  // the fault-reset bit does not clear err8 either
  EXPECT_EQ(m_.trip(), 27);
  m_.PowerCycle();
  EXPECT_FALSE(m_.tripped());
  EXPECT_EQ(R(reg::kFe10), 27);  // the trip history keeps it
}

TEST_F(InverterOptionFault, FirstTripHolds) {
  m_.Trip(trip_code::kEmergencyStop);
  EXPECT_EQ(Try(reg::kFa30, 27), WriteOutcome::kOk);
  EXPECT_EQ(m_.trip(), trip_code::kEmergencyStop);
}

}  // namespace
}  // namespace sim::test
