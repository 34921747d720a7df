// The simulated inverter's drive behaviour: status words against the manuals' worked examples, command
// and frequency sources, ramps, limits, the motor's monitors, communication loss.
#include <gtest/gtest.h>

#include <cstdint>

#include "inverter_model_fixture.h"

namespace sim::test {
namespace {

using InverterDrive = InverterModelFixture;

// ---- Status words: seed 000 §5.1.6 (Instance 100/150 = FA06/FA07 -> FD01/FD00) and seed 003 ---------

TEST_F(InverterDrive, Seed000Example1StopReads4800) {
  P(reg::kFa06, 0x0000);
  Wait(kSecond);
  EXPECT_EQ(R(reg::kFd01), 0x4800);  // standby + ST off: FA06 = 0 does not give the option control
  EXPECT_EQ(R(reg::kFd00), 0x0000);
}

TEST_F(InverterDrive, Seed000Example2ForwardRunning60HzReads6400) {
  P(reg::kFa07, 0x1770);
  P(reg::kFa06, 0xC400);
  EXPECT_EQ(R(reg::kFd01), 0x6400);  // run state at once; the output ramps
  Wait(8 * kSecond);                 // 60 Hz of 80 Hz in 10 s
  EXPECT_EQ(R(reg::kFd01), 0x6400);
  EXPECT_EQ(R(reg::kFd00), 0x1770);
  EXPECT_EQ(m_.command().command_source, CommandSource::kOption);
  EXPECT_EQ(m_.command().frequency_source, FrequencySource::kOption);
  // Instance 20/70 and 21/71: 60 Hz is 1800 min-1 with f856 = 2 pole pairs (a 4-pole motor), no load.
  EXPECT_EQ(m_.motor_speed_rpm(), 1800);
}

TEST_F(InverterDrive, Seed000Example3ReverseRunning60HzReads6600) {
  P(reg::kFa07, 0x1770);
  P(reg::kFa06, 0xC600);
  Wait(8 * kSecond);
  EXPECT_EQ(R(reg::kFd01), 0x6600);
  EXPECT_EQ(R(reg::kFd00), 0x1770);
  EXPECT_LT(m_.output_frequency_signed(), 0.0);
}

TEST_F(InverterDrive, Seed000Example4PresetSpeed1WithCommandPriorityOnly) {
  P(reg::kSr1, 0x01F4);  // sr1 = 5 Hz
  P(reg::kFa06, 0x8401);
  Wait(2 * kSecond);
  EXPECT_EQ(R(reg::kFd01), 0x6400);
  EXPECT_EQ(R(reg::kFd00), 0x01F4);
}

TEST_F(InverterDrive, Seed000Example5FaultResetGetsNoReplyAndClearsTheTrip) {
  P(reg::kFa06, 0xC400);
  m_.Trip(trip_code::kEmergencyStop);
  const WriteResult w = m_.Write(reg::kFa06, 0x2000, WriteTarget::kRamOnly);
  EXPECT_TRUE(w.ok());
  EXPECT_TRUE(w.no_reply);
  EXPECT_FALSE(m_.tripped());
  EXPECT_EQ(R(reg::kFa06), 0x0000);  // RAM-only command registers are back to 0: priorities re-asserted
}

TEST_F(InverterDrive, Seed003GoldenValues) {
  P(reg::kFa06, 0x8000);  // command priority, stopped, ST on
  EXPECT_EQ(R(reg::kFd01), 0x4000);  // stopped and ready
  P(reg::kFa07, 0x1770);
  P(reg::kFa06, 0xC400);
  Wait(8 * kSecond);
  EXPECT_EQ(R(reg::kFd01), 0x6400);  // running forward at 60 Hz
  P(reg::kFa06, 0xC000);
  Wait(8 * kSecond);
  m_.Trip(trip_code::kOptionFault);
  EXPECT_EQ(R(reg::kFd01), 0x0003);  // tripped, FL on
}

TEST_F(InverterDrive, StandbyFromTheTerminalBoardWithoutPriority) {
  EXPECT_EQ(R(reg::kFd01), 0x4800);
  ASSERT_TRUE(m_.SetTerminal("st", true));
  EXPECT_EQ(R(reg::kFd01), 0x4000);
  EXPECT_FALSE(m_.SetTerminal("XX", true));
}

TEST_F(InverterDrive, AlarmBitFollowsFc91) {
  P(reg::kFa07, 0x1770);
  P(reg::kFa06, 0xC400);
  Wait(8 * kSecond);
  m_.SetAlarm(7, true);  // undercurrent, as in the VF-S15 trace E404H (bit 15 there is undefined)
  EXPECT_EQ(R(reg::kFc91), 0x0080);
  EXPECT_EQ(R(reg::kFd01), 0x6404);
}

// ---- Ramps -----------------------------------------------------------------------------------------

TEST_F(InverterDrive, AccelerationTimeRunsFrom0HzToFh) {
  W(reg::kUl, 8000);
  P(reg::kFa07, 8000);
  P(reg::kFa06, 0xC400);  // acc = 10.0 s from 0 to fh = 80 Hz
  Wait(5 * kSecond);
  EXPECT_NEAR(R(reg::kFd00), 4000, 1);
  Wait(5 * kSecond);
  EXPECT_EQ(R(reg::kFd00), 8000);
  P(reg::kDec, 50);  // 5.0 s from fh to 0
  P(reg::kFa06, 0xC000);
  Wait(2500 * kMilli);
  EXPECT_NEAR(R(reg::kFd00), 4000, 1);
  EXPECT_EQ(R(reg::kFd01), 0x4400);  // decelerating: run state without RUN = ON
  Wait(2500 * kMilli);
  EXPECT_EQ(R(reg::kFd00), 0);
  EXPECT_EQ(R(reg::kFd01), 0x4000);
}

TEST_F(InverterDrive, TimingDoesNotDependOnTheStepSize) {
  P(reg::kFa07, 6000);
  P(reg::kFa06, 0xC400);
  Wait(3 * kSecond, 3 * kSecond);  // one step
  EXPECT_EQ(R(reg::kFd00), 2400);  // 8 Hz/s
  Wait(3 * kSecond, 7 * kMilli);
  EXPECT_EQ(R(reg::kFd00), 4800);
}

TEST_F(InverterDrive, AccDecPatternsAd2AndAd3) {
  P(reg::kF500, 20);  // AD2: 2.0 s
  P(reg::kF510, 40);  // AD3: 4.0 s
  P(reg::kFa07, 8000);
  W(reg::kUl, 8000);
  P(reg::kFa06, 0xC440);  // bit 6: AD2
  Wait(kSecond);
  EXPECT_EQ(R(reg::kFd00), 4000);
  EXPECT_EQ(R(reg::kFd01) & status_bit::kAd2, status_bit::kAd2);
  Wait(kSecond);
  P(reg::kFa06, 0xC000);
  Wait(3 * kSecond);  // back to AD1, dec = 10 s: 3 s bring 80 -> 56 Hz
  EXPECT_EQ(R(reg::kFd00), 5600);
  P(reg::kFa23, 0x0200);  // bits 9:8 = 10: AD3
  P(reg::kFa06, 0xC400);
  Wait(kSecond);  // f510 = 4 s: +20 Hz
  EXPECT_EQ(R(reg::kFd00), 7600);
  EXPECT_EQ(m_.command().pattern, AccDecPattern::kAd3);
}

TEST_F(InverterDrive, Acc001SecondUnitWithF519) {
  W(reg::kF519, 1);  // acc/dec in 0.01 s
  P(reg::kAcc, 100);  // 1.00 s
  P(reg::kFa07, 8000);
  W(reg::kUl, 8000);
  P(reg::kFa06, 0xC400);
  Wait(500 * kMilli);
  EXPECT_EQ(R(reg::kFd00), 4000);
}

TEST_F(InverterDrive, ReversingPassesThroughZero) {
  P(reg::kFa07, 4000);
  P(reg::kFa06, 0xC400);
  Wait(6 * kSecond);
  EXPECT_EQ(R(reg::kFd00), 4000);
  P(reg::kFa06, 0xC600);
  Wait(5 * kSecond);  // 40 Hz -> 0 in 5 s
  EXPECT_EQ(R(reg::kFd00), 0);
  Wait(2500 * kMilli);
  EXPECT_EQ(R(reg::kFd00), 2000);
  EXPECT_EQ(R(reg::kFd01), 0x6600);
}

TEST_F(InverterDrive, MaximumDecelerationForcedStop) {
  P(reg::kFa07, 6000);
  P(reg::kFa06, 0xC400);
  Wait(8 * kSecond);
  P(reg::kFa23, 0x0080);
  Wait(100 * kMilli);  // fh -> 0 in 0.1 s
  EXPECT_EQ(R(reg::kFd00), 0);
  EXPECT_EQ(R(reg::kFd01), 0x4000);
}

// ---- Limits ----------------------------------------------------------------------------------------

TEST_F(InverterDrive, UpperAndLowerLimits) {
  P(reg::kFa07, 0x1F40);  // 80 Hz accepted; ul = 60 Hz limits the output
  P(reg::kFa06, 0xC400);
  Wait(12 * kSecond);
  EXPECT_EQ(R(reg::kFd00), 6000);
  EXPECT_EQ(R(reg::kFa07), 0x1F40);
  P(reg::kLl, 1000);
  P(reg::kFa07, 500);
  Wait(12 * kSecond);
  EXPECT_EQ(R(reg::kFd00), 1000);  // running below ll is not possible
  EXPECT_EQ(Try(reg::kUl, 8001), WriteOutcome::kOutOfRange);  // above fh
  EXPECT_EQ(Try(reg::kLl, 6001), WriteOutcome::kOutOfRange);  // above ul
  EXPECT_EQ(Try(reg::kFa01, 8001), WriteOutcome::kOutOfRange);  // FA01: 0..fh
  EXPECT_EQ(Try(reg::kSr1, 8001), WriteOutcome::kOutOfRange);
  EXPECT_EQ(Try(reg::kFa07, 50000), WriteOutcome::kOk);  // FA07 above fh is accepted
}

// ---- Sources and priorities ------------------------------------------------------------------------

TEST_F(InverterDrive, WithoutPriorityCmodAndFmodDecide) {
  P(reg::kFa07, 3000);
  P(reg::kFa06, 0x0400);  // run, no priority, cmod = 1 (panel)
  Wait(5 * kSecond);
  EXPECT_EQ(R(reg::kFd00), 0);
  EXPECT_EQ(m_.command().command_source, CommandSource::kPanel);
  W(reg::kFmod, 7);
  W(reg::kCmod, 4);  // communication option: FA06 runs the drive at once
  EXPECT_EQ(Try(reg::kFmod, 0), WriteOutcome::kNotWritableWhileRunning);
  Wait(5 * kSecond);
  EXPECT_EQ(R(reg::kFd00), 3000);
  EXPECT_EQ(m_.command().frequency_source, FrequencySource::kOption);
}

TEST_F(InverterDrive, FrequencyPriorityAloneWithThePanelInCommand) {
  m_.SetTerminal(Terminal::kSt, true);
  m_.SetPanelFrequency(1000);
  m_.SetPanelRun(true, false);
  Wait(5 * kSecond);
  EXPECT_EQ(R(reg::kFd00), 1000);  // fmod = 0: the panel's setting
  P(reg::kFa07, 3000);
  P(reg::kFa06, 0x4000);  // frequency priority only
  Wait(5 * kSecond);
  EXPECT_EQ(R(reg::kFd00), 3000);
  EXPECT_EQ(m_.command().command_source, CommandSource::kPanel);
  EXPECT_EQ(m_.command().frequency_source, FrequencySource::kOption);
}

TEST_F(InverterDrive, Rs485PathFa00Fa01) {
  P(reg::kFa01, 2000);
  P(reg::kFa00, 0xC400);
  Wait(5 * kSecond);
  EXPECT_EQ(R(reg::kFd00), 2000);
  EXPECT_EQ(m_.command().command_source, CommandSource::kRs485);
  P(reg::kFa07, 3000);
  P(reg::kFa06, 0xC400);  // the option's priority wins (assumed order)
  Wait(5 * kSecond);
  EXPECT_EQ(R(reg::kFd00), 3000);
}

TEST_F(InverterDrive, ForcedLocalTerminalOverridesThePriorities) {
  // Seed 000 §11 example: cmod = 0, fmod = 1, f112 = 48 (R = SC/LC).
  W(reg::kCmod, 0);
  W(reg::kFmod, 1);
  W(0x0112, 48);
  P(reg::kFa07, 6000);
  P(reg::kFa06, 0xC400);
  Wait(8 * kSecond);
  EXPECT_EQ(R(reg::kFd00), 6000);  // R open: the network drives
  m_.SetTerminal(Terminal::kR, true);  // local
  EXPECT_EQ(m_.command().command_source, CommandSource::kTerminal);
  EXPECT_EQ(m_.command().frequency_source, FrequencySource::kVia);
  Wait(8 * kSecond);
  EXPECT_EQ(R(reg::kFd00), 0);  // F open: stop
  m_.SetTerminal(Terminal::kSt, true);
  m_.SetTerminal(Terminal::kF, true);
  m_.SetAnalogInput(AnalogInput::kVia, 5000);  // 50 % of fh
  Wait(8 * kSecond);
  EXPECT_EQ(R(reg::kFd00), 4000);
  EXPECT_EQ(R(reg::kFe35), 5000);
  EXPECT_EQ(R(reg::kFd06), 0x0003);  // F and R on
}

TEST_F(InverterDrive, TerminalPresetSpeedsAndHighPresetsFromFa06) {
  W(reg::kCmod, 0);
  P(reg::PresetSpeed(3), 1500);
  P(reg::PresetSpeed(15), 2500);
  m_.SetTerminal(Terminal::kSt, true);
  m_.SetTerminal(Terminal::kF, true);
  m_.SetTerminal(Terminal::kS1, true);
  m_.SetTerminal(Terminal::kS2, true);  // SS1 + SS2 = preset 3
  Wait(5 * kSecond);
  EXPECT_EQ(R(reg::kFd00), 1500);
  P(reg::kFa06, 0x840F);  // option, preset 15 = f294
  Wait(5 * kSecond);
  EXPECT_EQ(R(reg::kFd00), 2500);
}

TEST_F(InverterDrive, CoastStopJogAndDcBraking) {
  P(reg::kFa07, 6000);
  P(reg::kFa06, 0xC400);
  Wait(8 * kSecond);
  P(reg::kFa06, 0xCC00);  // coast stop: output cut at once
  EXPECT_EQ(R(reg::kFd00), 0);
  EXPECT_EQ(R(reg::kFd01), 0x4800);
  P(reg::kFa06, 0xC500);  // jog run: 5.00 Hz
  Wait(2 * kSecond);
  EXPECT_EQ(R(reg::kFd00), kJogFrequency);
  EXPECT_EQ(R(reg::kFd01), 0x6500);
  P(reg::kFa06, 0xC080);  // forced DC braking
  EXPECT_EQ(R(reg::kFd00), 0);
  EXPECT_EQ(R(reg::kFd01), 0x4080);
  EXPECT_GT(R(reg::kFd03), 0);  // DC current
}

TEST_F(InverterDrive, EmergencyStopIsAlwaysEffective) {
  W(reg::kCmod, 0);  // terminal board in command, no priority
  m_.SetTerminal(Terminal::kSt, true);
  m_.SetTerminal(Terminal::kF, true);
  m_.SetPanelFrequency(3000);
  Wait(5 * kSecond);
  EXPECT_EQ(R(reg::kFd00), 3000);
  P(reg::kFa06, 0x1000);
  EXPECT_TRUE(m_.tripped());
  EXPECT_EQ(R(reg::kFc90), trip_code::kEmergencyStop);
  EXPECT_EQ(R(reg::kFd00), 0);
  EXPECT_EQ(R(reg::kFd01), 0x1003);
  EXPECT_EQ(R(reg::kFe00), 3000);  // held from just before the trip
}

// ---- Motor monitors --------------------------------------------------------------------------------

TEST_F(InverterDrive, NoLoadAndRatedLoadAt60Hz) {
  P(reg::kFa07, 6000);
  P(reg::kFa06, 0xC400);
  Wait(8 * kSecond);
  EXPECT_EQ(R(reg::kFd05), 10000);        // vlv = 200 V of 200 V at vl = 60 Hz
  EXPECT_NEAR(R(reg::kFd03), 2833, 1);    // magnetising current 0.4 x 3.4 A of 4.8 A
  EXPECT_EQ(R(reg::kFd18), 0);
  EXPECT_EQ(R(reg::kFd16), 6000);
  m_.SetLoadTorque(10000);  // rated torque
  EXPECT_NEAR(R(reg::kFd03), 7083, 1);    // motor rated current 3.4 A of 4.8 A
  EXPECT_EQ(R(reg::kFd18), 10000);
  EXPECT_EQ(R(reg::kFd16), 5700);         // rated slip: 1710 min-1 = 57 Hz
  EXPECT_EQ(m_.motor_speed_rpm(), 1710);
  EXPECT_EQ(R(reg::kFd26), 100);          // motor load factor
  EXPECT_EQ(R(reg::kFd27), 71);           // drive load factor
  EXPECT_NEAR(R(reg::kFd30), 114, 1);     // sqrt(3) 200 V (3.12 + 0.17) A
  EXPECT_GT(R(reg::kFd29), R(reg::kFd30));
  P(reg::kFa07, 3000);
  Wait(10 * kSecond);
  EXPECT_EQ(R(reg::kFd05), 5300);  // V/f with 6 % boost at 30 Hz: 106 V
}

TEST_F(InverterDrive, DecelerationRegenerates) {
  P(reg::kFa07, 6000);
  P(reg::kFa06, 0xC400);
  Wait(8 * kSecond);
  P(reg::kFa06, 0xC000);
  Wait(kSecond);
  const auto torque = static_cast<std::int16_t>(R(reg::kFd18));
  EXPECT_LT(torque, 0);
  EXPECT_GT(R(reg::kFd16), R(reg::kFd00));  // the rotor runs ahead of the output
  EXPECT_EQ(R(reg::kFd30), 0);
}

TEST_F(InverterDrive, EnergyCountersAndTheirReset) {
  P(reg::kFa07, 6000);
  P(reg::kFa06, 0xC400);
  m_.SetLoadTorque(10000);
  Wait(3600 * kSecond, kSecond);
  EXPECT_EQ(R(reg::kFe77), 11);  // 1.14 kW for an hour, 0.1 kWh steps
  EXPECT_EQ(R(reg::kFe76), 11);  // 1.20 kW
  P(reg::kFa23, 0x0002);
  Wait(kSecond);
  EXPECT_EQ(R(reg::kFe76), 0);
  EXPECT_EQ(R(reg::kFe77), 0);
}

TEST_F(InverterDrive, TerminalBoardMonitors) {
  m_.SetTerminal(Terminal::kF, true);
  m_.SetTerminal(Terminal::kRes, true);
  EXPECT_EQ(R(reg::kFd06), 0x0005);  // seed 000 §3.2.4.14 example
  EXPECT_EQ(R(reg::kFe06), 0x0005);
  m_.SetTerminal(Terminal::kVia, true);
  EXPECT_EQ(R(reg::kFd06), 0x0005);  // VIA is analog while f109 = 0
  W(reg::kF130, 92);  // RY = specified data output 1
  P(reg::kFa50, 0x0001);
  EXPECT_EQ(R(reg::kFd07), 0x0001);
  m_.Trip(trip_code::kOptionFault);
  EXPECT_EQ(R(reg::kFd07), 0x0005);  // RY + FL: seed 000 §3.2.4.15 example
}

TEST_F(InverterDrive, FmTerminalOutputMonitor) {
  W(reg::kFmsl, 18);
  P(reg::kFa51, 500);
  EXPECT_EQ(R(reg::kFe40), 5000);  // 50.00 %
}

// ---- Communication loss (c100-c103) ----------------------------------------------------------------

TEST_F(InverterDrive, LossWithDefaultC101TripsErr8) {
  P(reg::kFa07, 6000);
  P(reg::kFa06, 0xC400);
  Wait(8 * kSecond);
  m_.OptionCommunicationLost();  // c100 = 0, c101 = 4, c103 = 0
  EXPECT_TRUE(m_.tripped());
  EXPECT_EQ(R(reg::kFc90), 27);
  EXPECT_EQ(R(reg::kFc91) & 0x0800, 0x0800);
  m_.OptionCommunicationRestored();
  EXPECT_TRUE(m_.tripped());
}

TEST_F(InverterDrive, LossDecelerationStopAfterTheDelay) {
  W(reg::kC100, 10);  // 1.0 s
  W(reg::kC101, 2);
  P(reg::kFa07, 6000);
  P(reg::kFa06, 0xC400);
  Wait(8 * kSecond);
  m_.OptionCommunicationLost();
  Wait(900 * kMilli);
  EXPECT_EQ(R(reg::kFd00), 6000);  // still within c100
  Wait(1100 * kMilli);
  EXPECT_EQ(R(reg::kFd00), 5200);  // decelerating for 1 s at 8 Hz/s
  EXPECT_FALSE(m_.tripped());
  m_.OptionCommunicationRestored();
  EXPECT_EQ(R(reg::kFc91), 0);
}

TEST_F(InverterDrive, LossConditionC103NeedsNetworkModes) {
  W(reg::kC103, 1);  // only when cmod and fmod are both the network
  m_.OptionCommunicationLost();
  EXPECT_FALSE(m_.tripped());
  m_.OptionCommunicationRestored();
  W(reg::kCmod, 4);
  W(reg::kFmod, 7);
  m_.OptionCommunicationLost();
  EXPECT_TRUE(m_.tripped());
}

TEST_F(InverterDrive, LossPresetSpeed) {
  W(reg::kC101, 5);
  W(reg::kC102, 2);
  P(reg::PresetSpeed(2), 1000);
  P(reg::kFa07, 3000);
  P(reg::kFa06, 0xC400);
  Wait(5 * kSecond);
  m_.OptionCommunicationLost();
  Wait(5 * kSecond);
  EXPECT_EQ(R(reg::kFd00), 1000);
  m_.OptionCommunicationRestored();
  Wait(5 * kSecond);
  EXPECT_EQ(R(reg::kFd00), 3000);
}

}  // namespace
}  // namespace sim::test
