// The Control Supervisor's run/stop logic (seed 000 §4.6.1 event matrix, §4.6.2 states), the one-shot
// edges of the output assemblies, the FA06/FA07 a command writes, the feedback and the unit conversions
// (docs/drive-profile.md).
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "cip/drive/control_supervisor.h"
#include "cip/drive/drive_profile.h"
#include "cip/drive/drive_units.h"

namespace cip::drive {
namespace {

// FD01 values: standby stopped, standby + RUN on + running (forward / reverse), running with RUN off
// (decelerating), tripped, tripped while the output still runs, not ready (moff: standby bit clear).
constexpr std::uint16_t kStopped = 0x4000;
constexpr std::uint16_t kRunning = 0x6400;
constexpr std::uint16_t kRunningReverse = 0x6600;
constexpr std::uint16_t kDecelerating = 0x4400;
constexpr std::uint16_t kTripped = 0x0003;
constexpr std::uint16_t kTrippedMoving = 0x0403;
constexpr std::uint16_t kNotReady = 0x0008;

using S = SupervisorState;

// ---- §4.6.1 Run/Stop event matrix ----

struct MatrixStep {
  bool run1;
  bool run2;
  RunType expected;
};

void RunMatrix(const std::vector<MatrixStep>& steps, const char* name) {
  RunStopMatrix matrix;
  for (std::size_t i = 0; i < steps.size(); ++i) {
    EXPECT_EQ(matrix.Update(steps[i].run1, steps[i].run2), steps[i].expected) << name << " step " << i;
  }
}

TEST(CipControlSupervisorTest, EventMatrix_Row1_00_Stop) {
  RunMatrix({{false, false, RunType::kStop}, {true, false, RunType::kRun1}, {false, false, RunType::kStop}}, "00");
  RunMatrix({{false, true, RunType::kRun2}, {false, false, RunType::kStop}}, "00 from Run2");
}

TEST(CipControlSupervisorTest, EventMatrix_Row2_Run1Rising_Run1) {
  RunMatrix({{true, false, RunType::kRun1}, {true, false, RunType::kRun1}}, "0->1 0");
}

TEST(CipControlSupervisorTest, EventMatrix_Row3_Run2Rising_Run2) {
  RunMatrix({{false, true, RunType::kRun2}, {false, true, RunType::kRun2}}, "0 0->1");
}

TEST(CipControlSupervisorTest, EventMatrix_Row4_BothRising_NoAction) {
  RunMatrix({{true, true, RunType::kStop}}, "0->1 0->1 from stop");
  // Both rising after a Run1 that dropped to 0/0 is a stop, then no action.
  RunMatrix({{true, false, RunType::kRun1}, {false, false, RunType::kStop}, {true, true, RunType::kStop}}, "after stop");
}

TEST(CipControlSupervisorTest, EventMatrix_Row5_BothHeld_NoAction) {
  RunMatrix({{true, false, RunType::kRun1}, {true, true, RunType::kRun1}, {true, true, RunType::kRun1}}, "1 1 keeps Run1");
  RunMatrix({{false, true, RunType::kRun2}, {true, true, RunType::kRun2}, {true, true, RunType::kRun2}}, "1 1 keeps Run2");
}

TEST(CipControlSupervisorTest, EventMatrix_Row6_Run1Falling_Run2) {
  RunMatrix({{true, false, RunType::kRun1}, {true, true, RunType::kRun1}, {false, true, RunType::kRun2}}, "1->0 1");
}

TEST(CipControlSupervisorTest, EventMatrix_Row7_Run2Falling_Run1) {
  RunMatrix({{false, true, RunType::kRun2}, {true, true, RunType::kRun2}, {true, false, RunType::kRun1}}, "1 1->0");
}

TEST(CipControlSupervisorTest, EventMatrix_DirectSwapsAndHeldLevels) {
  RunMatrix({{true, false, RunType::kRun1}, {false, true, RunType::kRun2}, {true, false, RunType::kRun1}}, "swaps");
  RunMatrix({{true, true, RunType::kStop}, {true, false, RunType::kRun1}}, "1 1->0 from both rising");
  RunStopMatrix matrix;
  matrix.Update(true, false);
  matrix.StopKeepingLevels();
  EXPECT_EQ(matrix.Update(true, false), RunType::kStop);  // held: needs a new edge
  EXPECT_EQ(matrix.Update(false, false), RunType::kStop);
  EXPECT_EQ(matrix.Update(true, false), RunType::kRun1);
  matrix.Clear();
  EXPECT_EQ(matrix.Update(true, false), RunType::kRun1);  // after Clear a held 1 is an edge
}

// ---- §4.6.2 states ----

SupervisorOutputs Step(ControlSupervisor& cs, std::uint16_t fd01, bool run1 = false, bool run2 = false,
                       bool fault_reset = false, bool known = true) {
  return cs.Step(SupervisorInputs{run1, run2, fault_reset, DriveStatus{known, fd01}});
}

TEST(CipControlSupervisorTest, StartupUntilTheDriveIsKnownThenNotReadyOrReady) {
  ControlSupervisor cs;
  EXPECT_EQ(cs.state(), S::kStartup);
  EXPECT_EQ(Step(cs, 0, true, false, false, false).state, S::kStartup);
  EXPECT_EQ(cs.run_type(), RunType::kStop);  // a run edge during start-up is dropped
  EXPECT_EQ(Step(cs, kNotReady, true).state, S::kNotReady);
  EXPECT_EQ(Step(cs, kStopped, true).state, S::kReady);  // main power on
  EXPECT_EQ(cs.run_type(), RunType::kStop);              // the held Run1 needs a new edge
  EXPECT_EQ(Step(cs, kNotReady).state, S::kNotReady);    // main power off
}

TEST(CipControlSupervisorTest, ReadyEnabledStoppingReady) {
  ControlSupervisor cs;
  Step(cs, kStopped);
  SupervisorOutputs out = Step(cs, kStopped, true);
  EXPECT_EQ(out.state, S::kReady);
  EXPECT_EQ(out.run, RunType::kRun1);  // FA06 now carries the run
  EXPECT_EQ(Step(cs, kRunning, true).state, S::kEnabled);
  EXPECT_TRUE(cs.running1());
  EXPECT_FALSE(cs.running2());
  out = Step(cs, kRunning, false);
  EXPECT_EQ(out.run, RunType::kStop);
  EXPECT_EQ(out.state, S::kEnabled);  // the drive has not seen the stop yet
  EXPECT_EQ(Step(cs, kDecelerating).state, S::kStopping);
  EXPECT_TRUE(cs.running1());  // Stopping and Running1
  EXPECT_TRUE(cs.ready());
  EXPECT_EQ(Step(cs, kStopped).state, S::kReady);  // stop complete
  EXPECT_FALSE(cs.running1());
}

TEST(CipControlSupervisorTest, StoppingBackToEnabledOnRun) {
  ControlSupervisor cs;
  Step(cs, kStopped, false, true);
  EXPECT_EQ(cs.run_type(), RunType::kRun2);
  EXPECT_EQ(Step(cs, kRunningReverse, false, true).state, S::kEnabled);
  EXPECT_TRUE(cs.running2());
  EXPECT_EQ(Step(cs, kDecelerating | kFd01Reverse, false, false).state, S::kStopping);
  EXPECT_TRUE(cs.running2());
  EXPECT_EQ(Step(cs, kDecelerating | kFd01Reverse, false, true).run, RunType::kRun2);  // Run accepted in Stopping
  EXPECT_EQ(Step(cs, kRunningReverse, false, true).state, S::kEnabled);
}

TEST(CipControlSupervisorTest, FaultStopFaultedFaultResetNotReadyReady) {
  ControlSupervisor cs;
  Step(cs, kStopped, true);
  Step(cs, kRunning, true);
  SupervisorOutputs out = Step(cs, kTrippedMoving, true);
  EXPECT_EQ(out.state, S::kFaultStop);
  EXPECT_EQ(out.run, RunType::kStop);  // the held Run1 is dropped
  EXPECT_TRUE(cs.faulted());
  EXPECT_TRUE(cs.running1());  // Fault_Stop and Running1
  EXPECT_EQ(Step(cs, kTripped, true).state, S::kFaulted);  // fault stop complete
  EXPECT_FALSE(cs.running1());
  EXPECT_FALSE(cs.ready());
  out = Step(cs, kTripped, true, false, true);
  EXPECT_TRUE(out.send_fault_reset);
  EXPECT_EQ(out.state, S::kFaulted);  // until the drive reports the trip gone
  EXPECT_EQ(Step(cs, kStopped, true).state, S::kReady);  // Faulted -> NotReady -> Ready in one step
  EXPECT_EQ(cs.run_type(), RunType::kStop);            // Run1 still held: no restart without an edge
  EXPECT_FALSE(cs.faulted());
  Step(cs, kStopped, false);
  EXPECT_EQ(Step(cs, kStopped, true).run, RunType::kRun1);
}

TEST(CipControlSupervisorTest, FaultDetectedFromEveryStillState) {
  for (std::uint16_t before : {kStopped, kNotReady}) {
    ControlSupervisor cs;
    Step(cs, before);
    EXPECT_EQ(Step(cs, kTripped).state, S::kFaulted) << before;
    EXPECT_EQ(Step(cs, kTrippedMoving).state, S::kFaulted) << before;  // was not moving: no Fault_Stop
  }
  ControlSupervisor startup;
  EXPECT_EQ(Step(startup, kTripped).state, S::kFaulted);  // Startup -> Faulted
  ControlSupervisor stopping;
  Step(stopping, kDecelerating);
  EXPECT_EQ(Step(stopping, kTrippedMoving).state, S::kFaultStop);
}

TEST(CipControlSupervisorTest, FaultResetIsSentOnlyWhileFaulted) {
  ControlSupervisor cs;
  EXPECT_FALSE(Step(cs, kStopped, false, false, true).send_fault_reset);
  EXPECT_FALSE(Step(cs, kRunning, false, false, true).send_fault_reset);
  EXPECT_FALSE(Step(cs, kNotReady, false, false, true).send_fault_reset);
  EXPECT_TRUE(Step(cs, kTripped, false, false, true).send_fault_reset);
  Step(cs, kRunning);
  EXPECT_TRUE(Step(cs, kTrippedMoving, false, false, true).send_fault_reset);  // Fault_Stop
  EXPECT_FALSE(Step(cs, kTripped, false, false, true, false).send_fault_reset);  // link lost: cannot
}

TEST(CipControlSupervisorTest, DriveLinkLostIsAFault) {
  ControlSupervisor cs;
  Step(cs, kRunning, true);
  EXPECT_EQ(Step(cs, 0, true, false, false, false).state, S::kFaulted);  // e-23
  EXPECT_EQ(cs.run_type(), RunType::kStop);
  EXPECT_EQ(Step(cs, kStopped, true).state, S::kReady);
  EXPECT_EQ(cs.run_type(), RunType::kStop);
}

TEST(CipControlSupervisorTest, MainPowerOffWhileEnabled) {
  ControlSupervisor cs;
  Step(cs, kStopped, true);
  Step(cs, kRunning, true);
  EXPECT_EQ(Step(cs, 0x0400, true).state, S::kNotReady);  // running, standby gone (moff, LL stop)
  EXPECT_EQ(cs.run_type(), RunType::kStop);
}

TEST(CipControlSupervisorTest, ResetServiceAndPower) {
  ControlSupervisor cs;
  Step(cs, kStopped, true);
  Step(cs, kRunning, true);
  cs.Reset();
  EXPECT_EQ(cs.state(), S::kStartup);
  EXPECT_EQ(cs.run_type(), RunType::kStop);
  // The levels were forgotten: the held Run1 is an edge again once the drive is ready.
  EXPECT_EQ(Step(cs, kStopped, true).run, RunType::kRun1);
  cs.SwitchOff();
  EXPECT_EQ(cs.state(), S::kNonExistent);
  EXPECT_EQ(Step(cs, kStopped, true).state, S::kNonExistent);
  EXPECT_EQ(cs.run_type(), RunType::kStop);
  cs.SwitchOn();
  EXPECT_EQ(cs.state(), S::kStartup);
}

TEST(CipControlSupervisorTest, AttributesAndNames) {
  ControlSupervisor cs;
  EXPECT_FALSE(cs.warning());
  Step(cs, kStopped | 0x0004);
  EXPECT_TRUE(cs.warning());  // FD01 bit 2, not latched
  Step(cs, kStopped);
  EXPECT_FALSE(cs.warning());
  EXPECT_TRUE(cs.ready());
  EXPECT_STREQ(SupervisorStateName(S::kNonExistent), "NonExistent");
  EXPECT_STREQ(SupervisorStateName(S::kFaultStop), "FaultStop");
  for (std::uint8_t value = 1; value <= 7; ++value) EXPECT_EQ(static_cast<std::uint8_t>(static_cast<S>(value)), value);
  EXPECT_TRUE(AcceptsRun(S::kReady) && AcceptsRun(S::kEnabled) && AcceptsRun(S::kStopping));
  EXPECT_FALSE(AcceptsRun(S::kNotReady) || AcceptsRun(S::kFaulted) || AcceptsRun(S::kFaultStop) || AcceptsRun(S::kStartup));
}

// ---- One-shot edges ----

TEST(CipDriveEdgeTest, FaultResetLevelBecomesOneShot) {
  OutputEdgeTracker edges;
  DriveCommand command;
  command.profile = CommandProfile::kCipSpeed;
  command.fault_reset = true;
  EXPECT_TRUE(edges.Track(command).fault_reset);  // first packet: compared with 0
  EXPECT_FALSE(edges.Track(command).fault_reset);
  command.fault_reset = false;
  EXPECT_FALSE(edges.Track(command).fault_reset);
  command.fault_reset = true;
  EXPECT_TRUE(edges.Track(command).fault_reset);
  edges.Reset();  // a new connection
  EXPECT_TRUE(edges.Track(command).fault_reset);
  DriveCommand scanner;
  scanner.profile = CommandProfile::kScanner;
  EXPECT_FALSE(edges.Track(scanner).fault_reset);
  EXPECT_TRUE(edges.Track(command).fault_reset);
}

// ---- FA06/FA07 ----

DriveCommand Speed(bool net_bits, bool ctrl, bool ref, std::int16_t rpm) {
  DriveCommand command;
  command.profile = CommandProfile::kCipSpeed;
  command.has_net_bits = net_bits;
  command.net_ctrl = ctrl;
  command.net_ref = ref;
  command.speed_reference_rpm = rpm;
  return command;
}

TEST(CipDriveProfileTest, CommandRegistersOfTheSpeedProfiles) {
  DriveContext context;
  context.run = RunType::kRun1;
  CommandWrites writes = CommandRegisters(Speed(true, true, true, 1800), context);
  EXPECT_EQ(writes.fa06, 0xC400);
  EXPECT_EQ(writes.fa07, 6000);
  EXPECT_EQ(writes.scanner_mask, 0);
  context.run = RunType::kRun2;
  EXPECT_EQ(CommandRegisters(Speed(true, true, false, 0), context).fa06, 0x8600);
  context.run = RunType::kStop;
  context.fault_reset = true;
  EXPECT_EQ(CommandRegisters(Speed(true, false, true, 0), context).fa06, 0x6000);
  // 20: the attributes decide the priority bits.
  context.fault_reset = false;
  context.net_ctrl_attribute = true;
  EXPECT_EQ(CommandRegisters(Speed(false, false, false, 0), context).fa06, 0x8000);
  context.net_ref_attribute = true;
  context.net_ctrl_attribute = false;
  EXPECT_EQ(CommandRegisters(Speed(false, true, false, 0), context).fa06, 0x4000);
  // f856 = 4 (8 poles): 1800 rpm is 120.00 Hz; a negative reference is 0.
  context.pole_pairs = 4;
  EXPECT_EQ(CommandRegisters(Speed(true, true, true, 1800), context).fa07, 12000);
  EXPECT_EQ(CommandRegisters(Speed(true, true, true, -1800), context).fa07, 0);
  const CommandWrites none = CommandRegisters(DriveCommand{}, context);
  EXPECT_FALSE(none.write_fa06 || none.write_fa07 || none.scanner_mask != 0);
}

TEST(CipDriveProfileTest, NetBitsBecomeTheAttributes) {
  bool ctrl = false;
  bool ref = true;
  ApplyNetBits(Speed(false, true, false, 0), ctrl, ref);  // 20: left as they are
  EXPECT_FALSE(ctrl);
  EXPECT_TRUE(ref);
  ApplyNetBits(Speed(true, true, false, 0), ctrl, ref);
  EXPECT_TRUE(ctrl);
  EXPECT_FALSE(ref);
}

TEST(CipDriveProfileTest, ControlSourcesFromPriorityBitsOrCmodFmod) {
  ControlSources s = ControlSourcesOf(0x0000, 1, 0);
  EXPECT_FALSE(s.ctrl_from_net || s.ref_from_net);
  s = ControlSourcesOf(0x8000, 1, 0);
  EXPECT_TRUE(s.ctrl_from_net && !s.ref_from_net);
  s = ControlSourcesOf(0x4000, 1, 0);
  EXPECT_TRUE(!s.ctrl_from_net && s.ref_from_net);
  s = ControlSourcesOf(0x0000, 4, 7);
  EXPECT_TRUE(s.ctrl_from_net && s.ref_from_net);
  s = ControlSourcesOf(0x0000, 2, 4);  // RS485 is not the card's network
  EXPECT_FALSE(s.ctrl_from_net || s.ref_from_net);
}

TEST(CipDriveProfileTest, FeedbackRegistersPerInputInstance) {
  EXPECT_EQ(std::vector<std::uint16_t>(FeedbackRegisters(70).begin(), FeedbackRegisters(70).end()),
            (std::vector<std::uint16_t>{0xFD01, 0xFD00}));
  EXPECT_EQ(FeedbackRegisters(150).size(), 2u);
  EXPECT_EQ(std::vector<std::uint16_t>(FeedbackRegisters(71).begin(), FeedbackRegisters(71).end()),
            (std::vector<std::uint16_t>{0xFD01, 0xFD00, 0xFE02}));
  EXPECT_EQ(FeedbackRegisters(151).size(), 3u);
  EXPECT_TRUE(FeedbackRegisters(152).empty());
  EXPECT_TRUE(FeedbackRegisters(155).empty());
  EXPECT_TRUE(FeedbackRegisters(20).empty());
}

TEST(CipDriveProfileTest, FeedbackFromMonitors) {
  const ControlSources sources{true, false};
  DriveFeedback f = MakeFeedback(DriveMonitors{0x6404, 6000, 6000}, S::kEnabled, sources, FeedbackOptions{});
  EXPECT_TRUE(f.running_forward && !f.running_reverse && f.ready && f.at_reference && f.warning);
  EXPECT_TRUE(f.ctrl_from_net && !f.ref_from_net && !f.faulted);
  EXPECT_EQ(f.speed_actual_rpm, 1800);
  EXPECT_EQ(f.status_word, 0x6404);
  EXPECT_EQ(f.output_frequency, 6000);
  // At reference: "the same as the frequency command", in Enabled only; a tolerance widens it.
  EXPECT_FALSE(MakeFeedback(DriveMonitors{0x6400, 5999, 6000}, S::kEnabled, sources, FeedbackOptions{}).at_reference);
  EXPECT_TRUE(MakeFeedback(DriveMonitors{0x6400, 6001, 6000}, S::kEnabled, sources, FeedbackOptions{2, 1}).at_reference);
  EXPECT_FALSE(MakeFeedback(DriveMonitors{0x4400, 0, 0}, S::kStopping, sources, FeedbackOptions{}).at_reference);
  EXPECT_FALSE(MakeFeedback(DriveMonitors{0x4000, 0, 0}, S::kReady, sources, FeedbackOptions{}).at_reference);
  f = MakeFeedback(DriveMonitors{0x6600, 3000, 3000}, S::kEnabled, sources, FeedbackOptions{1, 0});
  EXPECT_TRUE(f.running_reverse && !f.running_forward);
  EXPECT_EQ(f.speed_actual_rpm, 1800);  // f856 = 1: 30 Hz x 60
  for (S state : {S::kFaultStop, S::kFaulted}) {
    f = MakeFeedback(DriveMonitors{kTripped, 0, 0}, state, sources, FeedbackOptions{});
    EXPECT_TRUE(f.faulted && !f.ready);
  }
  EXPECT_FALSE(MakeFeedback(DriveMonitors{}, S::kNotReady, sources, FeedbackOptions{}).ready);
}

// ---- Conversions ----

TEST(CipDriveUnitsTest, RpmAtEveryPolePairCount) {
  const std::uint16_t expected[] = {3600, 1800, 1200, 900, 720, 600, 514, 450};  // 60.00 Hz, f856 = 1..8
  for (std::uint16_t pairs = 1; pairs <= 8; ++pairs) {
    EXPECT_EQ(FrequencyToRpm(6000, pairs), expected[pairs - 1]) << pairs;
    EXPECT_EQ(FrequencyToRpm(0, pairs), 0);
    EXPECT_EQ(RpmToFrequency(0, pairs), 0);
  }
  EXPECT_EQ(RpmToFrequency(514, 7), 5997);  // 59.966 Hz
  EXPECT_EQ(FrequencyToRpm(6000, 0), 1800);  // out of range f856: the factory 2
  EXPECT_EQ(FrequencyToRpm(6000, 9), 1800);
  EXPECT_EQ(UsablePolePairs(8), 8);
}

TEST(CipDriveUnitsTest, RoundingAndLimits) {
  EXPECT_EQ(FrequencyToRpm(1, 2), 0);   // 0.3 rpm
  EXPECT_EQ(FrequencyToRpm(2, 2), 1);   // 0.6 rpm
  EXPECT_EQ(FrequencyToRpm(5, 2), 2);   // 1.5 rpm: halves up
  EXPECT_EQ(RpmToFrequency(1, 2), 3);   // 3.33
  EXPECT_EQ(RpmToFrequency(2, 2), 7);   // 6.67
  EXPECT_EQ(RpmToFrequency(-1, 2), 0);
  EXPECT_EQ(RpmToFrequency(-32768, 2), 0);
  EXPECT_EQ(RpmToFrequency(15000, 2), 50000);  // 500.00 Hz exactly
  EXPECT_EQ(RpmToFrequency(15001, 2), kMaxFrequencyCommand);
  EXPECT_EQ(RpmToFrequency(32767, 8), kMaxFrequencyCommand);
  EXPECT_EQ(RpmToFrequency(1000000, 1), kMaxFrequencyCommand);
  EXPECT_EQ(FrequencyToRpm(50000, 1), 30000);
  EXPECT_EQ(FrequencyToRpm(65535, 1), kMaxRpm);  // 39321 does not fit an INT
  EXPECT_EQ(FrequencyToRpm(65535, 8), 4915);
}

TEST(CipDriveUnitsTest, RpmRoundTripsAtEveryPolePairCount) {
  for (std::uint16_t pairs = 1; pairs <= 8; ++pairs) {
    for (std::int32_t rpm = 0; rpm <= kMaxRpm; ++rpm) {
      const std::uint16_t f = RpmToFrequency(rpm, pairs);
      if (f >= kMaxFrequencyCommand) break;
      ASSERT_EQ(FrequencyToRpm(f, pairs), rpm) << "f856 " << pairs;
    }
  }
}

TEST(CipDriveUnitsTest, AccelerationTimeAndCurrent) {
  EXPECT_EQ(TimeParameterToMillis(50, false), 5000);  // acc 5.0 s = 32H (§4.8)
  EXPECT_EQ(TimeParameterToMillis(50, true), 500);    // f519 = 1: 0.01 s
  EXPECT_EQ(TimeParameterToMillis(60000, false), 0xFFFF);  // 6000 s does not fit the UINT of ms
  EXPECT_EQ(MillisToTimeParameter(5000, false), 50);
  EXPECT_EQ(MillisToTimeParameter(5049, false), 50);
  EXPECT_EQ(MillisToTimeParameter(5050, false), 51);
  EXPECT_EQ(MillisToTimeParameter(5, true), 1);
  EXPECT_EQ(MillisToTimeParameter(0xFFFF, false), 655);
  EXPECT_EQ(CurrentTenthsOfAmp(5000, 48), 24);  // 50 % of a 4.8 A drive = 2.4 A (§3.2.4.9)
  EXPECT_EQ(CurrentTenthsOfAmp(0, 48), 0);
  EXPECT_EQ(CurrentTenthsOfAmp(0xFFFF, 0xFFFF), 0xFFFF);
}

}  // namespace
}  // namespace cip::drive
