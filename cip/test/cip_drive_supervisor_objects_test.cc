// Control Supervisor 0x29 and AC/DC Drive 0x2A through the message router (cip/drive/
// control_supervisor_object.h, ac_dc_drive_object.h): every attribute's bytes, the explicit commands and
// their ownership rule, the Reset service, and the register-backed attributes over the deferred-reply
// journal with their conversions and errors.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "drive_channel_fake.h"

namespace cip::drive {
namespace {

using drive_link::DriveCommandWords;
using Access = drive_link::test::ScriptedDriveRegisters::Access;
using test::DriveCard;
using test::Hex;
using test::kRunningForward;
using test::kStandby;
using test::kTripped;

using Commands = std::vector<DriveCommandWords>;
using Accesses = std::vector<Access>;

constexpr Access Read(std::uint16_t number) { return Access{false, number, 0, drive_link::WriteMode::kRamOnly}; }
constexpr Access WriteW(std::uint16_t number, std::uint16_t value) {
  return Access{true, number, value, drive_link::WriteMode::kRamAndEeprom};
}

class ControlSupervisorObjectTest : public ::testing::Test {
 protected:
  DriveCard card_;
};

TEST_F(ControlSupervisorObjectTest, ClassAttributes) {
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 29 24 00 30 01")), Hex("8E 00 00 00 01 00"));
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 29 24 00 30 02")), Hex("8E 00 00 00 01 00"));
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 29 24 00 30 03")), Hex("8E 00 00 00 01 00"));
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 29 24 00 30 06")), Hex("8E 00 00 00 07 00"));
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 29 24 00 30 07")), Hex("8E 00 00 00 0F 00"));
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 29 24 00 30 04")), Hex("8E 00 14 00"));
}

TEST_F(ControlSupervisorObjectTest, AttributesOfAStoppedDrive) {
  card_.Drive(kStandby);
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 29 24 01 30 01")), Hex("8E 00 00 00 0D 00"));
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 29 24 01 30 02")), Hex("8E 00 00 00 01 02 03 04 05 06 07 08 09 0A 0B 0C 0F"));
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 29 24 01 30 03")), Hex("8E 00 00 00 00"));
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 29 24 01 30 04")), Hex("8E 00 00 00 00"));
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 29 24 01 30 05")), Hex("8E 00 00 00 00"));
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 29 24 01 30 06")), Hex("8E 00 00 00 03"));  // Ready
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 29 24 01 30 07")), Hex("8E 00 00 00 00"));
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 29 24 01 30 08")), Hex("8E 00 00 00 00"));
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 29 24 01 30 09")), Hex("8E 00 00 00 01"));
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 29 24 01 30 0A")), Hex("8E 00 00 00 00"));
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 29 24 01 30 0B")), Hex("8E 00 00 00 00"));
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 29 24 01 30 0C")), Hex("8E 00 00 00 00"));
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 29 24 01 30 0F")), Hex("8E 00 00 00 00"));
}

TEST_F(ControlSupervisorObjectTest, StartupUntilTheDriveIsKnownThenFaultedWhenTheLinkIsLost) {
  card_.status.status = DriveStatus{false, 0};
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 29 24 01 30 06")), Hex("8E 00 00 00 01"));  // Startup
  card_.Drive(kStandby | 0x0004);  // alarm
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 29 24 01 30 06")), Hex("8E 00 00 00 03"));
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 29 24 01 30 0B")), Hex("8E 00 00 00 01"));  // Warning
  card_.status.status = DriveStatus{false, 0};  // e-23
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 29 24 01 30 06")), Hex("8E 00 00 00 07"));
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 29 24 01 30 0A")), Hex("8E 00 00 00 01"));
}

TEST_F(ControlSupervisorObjectTest, ExplicitRunNetCtrlAndSpeedReference) {
  card_.Drive(kStandby);
  EXPECT_EQ(card_.Ask(Hex("10 03 20 29 24 01 30 03 01")), Hex("90 00 00 00"));  // Run1
  EXPECT_EQ(card_.channel.commands, (Commands{{0x0400, 0x0000}}));
  EXPECT_EQ(card_.Ask(Hex("10 03 20 29 24 01 30 05 01")), Hex("90 00 00 00"));  // NetCtrl
  EXPECT_EQ(card_.Ask(Hex("10 03 20 2A 24 01 30 04 01")), Hex("90 00 00 00"));  // NetRef
  EXPECT_EQ(card_.Ask(Hex("10 03 20 2A 24 01 30 08 08 07")), Hex("90 00 00 00"));  // 1800 rpm
  EXPECT_EQ(card_.channel.commands, (Commands{{0x0400, 0}, {0x8400, 0}, {0xC400, 0}, {0xC400, 0x1770}}));
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 29 24 01 30 03")), Hex("8E 00 00 00 01"));
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 29 24 01 30 05")), Hex("8E 00 00 00 01"));
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 29 24 01 30 0F")), Hex("8E 00 00 00 01"));  // CtrlFromNet
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 2A 24 01 30 04")), Hex("8E 00 00 00 01"));
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 2A 24 01 30 08")), Hex("8E 00 00 00 08 07"));
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 2A 24 01 30 1D")), Hex("8E 00 00 00 01"));  // RefFromNet
  card_.Drive(kRunningForward, 0x1770, 0x1770);
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 29 24 01 30 06")), Hex("8E 00 00 00 04"));  // Enabled
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 29 24 01 30 07")), Hex("8E 00 00 00 01"));  // Running1
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 29 24 01 30 08")), Hex("8E 00 00 00 00"));
  // Run2 while Run1 is held: the "1 1" row, no change; Run1 released: Run2 (reverse).
  EXPECT_EQ(card_.Ask(Hex("10 03 20 29 24 01 30 04 01")), Hex("90 00 00 00"));
  EXPECT_EQ(card_.channel.commands.back(), (DriveCommandWords{0xC400, 0x1770}));
  EXPECT_EQ(card_.Ask(Hex("10 03 20 29 24 01 30 03 00")), Hex("90 00 00 00"));
  EXPECT_EQ(card_.channel.commands.back(), (DriveCommandWords{0xC600, 0x1770}));
  EXPECT_EQ(card_.Ask(Hex("10 03 20 29 24 01 30 04 00")), Hex("90 00 00 00"));  // stop
  EXPECT_EQ(card_.channel.commands.back(), (DriveCommandWords{0xC000, 0x1770}));
}

// docs/drive-control.md: while a network loss holds the drive, a run, a control-source change, a fault
// reset or a speed is refused with 0x10 and hands nothing to the drive link; Run1/Run2 = 0 and the Reset
// service are taken and held as the stop the loss action writes.
TEST_F(ControlSupervisorObjectTest, WhileALossHoldsTheDriveOnlyStopsAreTaken) {
  card_.Drive(kStandby);
  card_.channel.held_by_loss = true;
  EXPECT_EQ(card_.Ask(Hex("10 03 20 29 24 01 30 05 01")), Hex("90 00 10 00"));  // NetCtrl
  EXPECT_EQ(card_.Ask(Hex("10 03 20 2A 24 01 30 04 01")), Hex("90 00 10 00"));  // NetRef
  EXPECT_EQ(card_.Ask(Hex("10 03 20 2A 24 01 30 08 08 07")), Hex("90 00 10 00"));  // 1800 rpm
  EXPECT_EQ(card_.Ask(Hex("10 03 20 29 24 01 30 03 01")), Hex("90 00 10 00"));  // Run1
  EXPECT_EQ(card_.Ask(Hex("10 03 20 29 24 01 30 04 01")), Hex("90 00 10 00"));  // Run2
  EXPECT_EQ(card_.Ask(Hex("10 03 20 29 24 01 30 0C 01")), Hex("90 00 10 00"));  // FaultRst
  EXPECT_TRUE(card_.channel.commands.empty());
  EXPECT_TRUE(card_.channel.held_stops.empty());
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 29 24 01 30 03")), Hex("8E 00 00 00 00"));  // Run1 unchanged
  EXPECT_EQ(card_.Ask(Hex("10 03 20 29 24 01 30 03 00")), Hex("90 00 00 00"));  // Run1 = 0: a stop
  EXPECT_EQ(card_.channel.commands, (Commands{{0x0000, 0x0000}}));
  EXPECT_EQ(card_.channel.held_stops, (std::vector<std::uint16_t>{0x0000}));
  EXPECT_EQ(card_.Ask(Hex("05 02 20 29 24 01")), Hex("85 00 00 00"));  // Reset: a stop too
  card_.channel.held_by_loss = false;  // restored: commands are taken again
  EXPECT_EQ(card_.Ask(Hex("10 03 20 29 24 01 30 03 01")), Hex("90 00 00 00"));
  EXPECT_EQ(card_.channel.commands.back(), (DriveCommandWords{0x0400, 0x0000}));
}

TEST_F(ControlSupervisorObjectTest, RunWhileTrippedIsADeviceStateConflict) {
  card_.Drive(kTripped);
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 29 24 01 30 06")), Hex("8E 00 00 00 07"));  // Faulted
  EXPECT_EQ(card_.Ask(Hex("10 03 20 29 24 01 30 03 01")), Hex("90 00 10 00"));
  EXPECT_EQ(card_.Ask(Hex("10 03 20 29 24 01 30 04 01")), Hex("90 00 10 00"));
  EXPECT_TRUE(card_.channel.commands.empty());
  EXPECT_EQ(card_.Ask(Hex("10 03 20 29 24 01 30 03 00")), Hex("90 00 00 00"));  // a stop is taken
}

TEST_F(ControlSupervisorObjectTest, FaultResetActsOnItsRisingEdgeWhileTripped) {
  card_.Drive(kTripped);
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 29 24 01 30 0A")), Hex("8E 00 00 00 01"));  // Faulted
  EXPECT_EQ(card_.Ask(Hex("10 03 20 29 24 01 30 0C 01")), Hex("90 00 00 00"));
  // Held at 1: no second reset (bit 13 is in FA06 for the command that raised it only).
  EXPECT_EQ(card_.Ask(Hex("10 03 20 29 24 01 30 0C 01")), Hex("90 00 00 00"));
  EXPECT_EQ(card_.channel.commands, (Commands{{0x2000, 0x0000}, {0x0000, 0x0000}}));
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 29 24 01 30 0C")), Hex("8E 00 00 00 01"));
  EXPECT_EQ(card_.Ask(Hex("10 03 20 29 24 01 30 0C 00")), Hex("90 00 00 00"));
  EXPECT_EQ(card_.Ask(Hex("10 03 20 29 24 01 30 0C 01")), Hex("90 00 00 00"));
  EXPECT_EQ(card_.channel.commands, (Commands{{0x2000, 0}, {0x0000, 0}, {0x2000, 0}}));
}

TEST_F(ControlSupervisorObjectTest, CommandsAreRefusedWhileAConnectionOwnsTheCommandAssemblies) {
  card_.Drive(kStandby);
  for (std::uint32_t point : {20u, 21u, 100u, 101u}) {
    card_.ownership.owned = {point};
    EXPECT_EQ(card_.Ask(Hex("10 03 20 29 24 01 30 03 01")), Hex("90 00 10 00")) << point;
    EXPECT_EQ(card_.Ask(Hex("10 03 20 29 24 01 30 0C 01")), Hex("90 00 10 00")) << point;
    EXPECT_EQ(card_.Ask(Hex("10 03 20 2A 24 01 30 08 08 07")), Hex("90 00 10 00")) << point;
    EXPECT_EQ(card_.Ask(Hex("10 03 20 2A 24 01 30 04 01")), Hex("90 00 10 00")) << point;
    EXPECT_EQ(card_.Ask(Hex("05 02 20 29 24 01")), Hex("85 00 10 00")) << point;
  }
  // 102 owned: its scanner word 1 is FA06 with the factory c001 = 1.
  card_.ownership.owned = {102};
  EXPECT_EQ(card_.Ask(Hex("10 03 20 29 24 01 30 03 01")), Hex("90 00 10 00"));
  config::CardConfig config;
  config.command_menus = {13, 14, 0, 0, 0, 0};
  card_.runtime.SetCardConfig(config);
  EXPECT_EQ(card_.Ask(Hex("10 03 20 29 24 01 30 03 01")), Hex("90 00 00 00"));
  EXPECT_EQ(card_.channel.commands, (Commands{{0x0400, 0x0000}}));
  // Reading is always allowed.
  card_.ownership.owned = {21};
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 29 24 01 30 03")), Hex("8E 00 00 00 01"));
}

TEST_F(ControlSupervisorObjectTest, AConnectionsScannerWordsTakeFa06BackFromExplicitMessaging) {
  card_.Drive(kStandby);
  EXPECT_EQ(card_.Ask(Hex("10 03 20 29 24 01 30 03 01")), Hex("90 00 00 00"));
  EXPECT_TRUE(card_.runtime.drive_command_held());
  card_.ownership.owned = {102};
  card_.assemblies.OnConnectionsChanged();
  card_.assemblies.Consume(102, Hex("00 C4 70 17 00 00 00 00 00 00 00 00"), true);
  EXPECT_EQ(card_.channel.releases, 1);
  EXPECT_FALSE(card_.runtime.drive_command_held());
  EXPECT_FALSE(card_.runtime.run1());
}

// A card reset (f899 = 1) gives FA06/FA07 back (RegisterProxy::BeginLoad(card_reset = true)): an explicit
// hold ends with it instead of being taken over again by the next refresh (which kept FA06/FA07 reserved
// for nobody); the run level is gone, a later command takes the drive afresh.
TEST_F(ControlSupervisorObjectTest, ACardResetEndsTheExplicitHold) {
  card_.Drive(kStandby);
  EXPECT_EQ(card_.Ask(Hex("10 03 20 29 24 01 30 03 01")), Hex("90 00 00 00"));  // Run1
  EXPECT_TRUE(card_.runtime.drive_command_held());
  card_.channel.taken = false;  // the card reset
  card_.assemblies.Poll(1000);
  card_.assemblies.Poll(2000);
  EXPECT_EQ(card_.channel.commands, (Commands{{0x0400, 0}}));  // not taken over again
  EXPECT_FALSE(card_.channel.taken);
  EXPECT_FALSE(card_.runtime.drive_command_held());
  EXPECT_FALSE(card_.runtime.run1());
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 29 24 01 30 03")), Hex("8E 00 00 00 00"));
  // A new explicit command takes the drive command afresh.
  EXPECT_EQ(card_.Ask(Hex("10 03 20 2A 24 01 30 08 08 07")), Hex("90 00 00 00"));  // 1800 rpm, no run
  EXPECT_EQ(card_.channel.commands.back(), (DriveCommandWords{0x0000, 0x1770}));
  EXPECT_TRUE(card_.channel.taken);
}

// The same when the first thing after the reset is a new explicit command (no refresh in between): it is
// taken, not dropped with the old hold, and the old Run1 level does not come back with it.
TEST_F(ControlSupervisorObjectTest, ACommandRightAfterACardResetIsTakenAfresh) {
  card_.Drive(kStandby);
  EXPECT_EQ(card_.Ask(Hex("10 03 20 29 24 01 30 03 01")), Hex("90 00 00 00"));  // Run1
  card_.channel.taken = false;  // the card reset
  EXPECT_EQ(card_.Ask(Hex("10 03 20 29 24 01 30 05 01")), Hex("90 00 00 00"));  // NetCtrl
  EXPECT_EQ(card_.channel.commands, (Commands{{0x0400, 0}, {0x8000, 0}}));
  EXPECT_TRUE(card_.channel.taken);
  EXPECT_FALSE(card_.runtime.run1());
}

TEST_F(ControlSupervisorObjectTest, ResetServiceStopsWhatExplicitMessagingRuns) {
  card_.Drive(kStandby);
  EXPECT_EQ(card_.Ask(Hex("10 03 20 29 24 01 30 03 01")), Hex("90 00 00 00"));
  EXPECT_EQ(card_.Ask(Hex("05 02 20 29 24 01")), Hex("85 00 00 00"));
  EXPECT_EQ(card_.channel.commands, (Commands{{0x0400, 0}, {0x0000, 0}}));
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 29 24 01 30 03")), Hex("8E 00 00 00 00"));
  EXPECT_EQ(card_.Ask(Hex("05 02 20 29 24 01 00")), Hex("85 00 15 00"));
  EXPECT_EQ(card_.Ask(Hex("05 02 20 29 24 00")), Hex("85 00 08 00"));  // no class Reset
}

TEST_F(ControlSupervisorObjectTest, Errors) {
  EXPECT_EQ(card_.Ask(Hex("10 03 20 29 24 01 30 03 02")), Hex("90 00 09 00"));     // BOOL 2
  EXPECT_EQ(card_.Ask(Hex("10 03 20 29 24 01 30 03 01 00")), Hex("90 00 15 00"));  // too long
  EXPECT_EQ(card_.Ask(Hex("10 03 20 29 24 01 30 03")), Hex("90 00 13 00"));        // no value
  EXPECT_EQ(card_.Ask(Hex("10 03 20 29 24 01 30 06 03")), Hex("90 00 0E 00"));     // State
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 29 24 01 30 0D")), Hex("8E 00 14 00"));
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 29 24 02 30 06")), Hex("8E 00 16 00"));
  EXPECT_EQ(card_.Ask(Hex("01 02 20 29 24 01")), Hex("81 00 08 00"));
  EXPECT_TRUE(card_.channel.commands.empty());
}

// ---- AC/DC Drive ----------------------------------------------------------------------------------------

class AcDcDriveObjectTest : public ::testing::Test {
 protected:
  AcDcDriveObjectTest() {
    card_.Drive(kStandby);
    auto& r = card_.registers.registers;
    r[0x0009] = 100;     // acc 10.0 s
    r[0x0010] = 25;      // dec 2.5 s
    r[0x0012] = 6000;    // ul 60 Hz
    r[0x0013] = 500;     // ll 5 Hz
    r[0x0519] = 0;       // f519: 0.1 s
    r[0x0601] = 150;     // f601 150 %
    r[0x0405] = 75;      // f405 0.75 kW
    r[0x0417] = 1410;    // f417 1410 rpm
    r[0xFD00] = 0x1770;  // 60 Hz
    r[0xFE02] = 0x1770;
    r[0xFD03] = 5000;    // 50 %
    r[0xFE70] = 48;      // 4.8 A
    r[0xFD18] = 10000;   // 100 % torque
    r[0xFD30] = 75;      // 0.75 kW
    r[0xFE14] = 0x12;    // 18 h
    r[0x0856] = 2;       // f856: 2 pole pairs
  }
  DriveCard card_;
};

TEST_F(AcDcDriveObjectTest, ClassAndListAttributes) {
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 2A 24 00 30 01")), Hex("8E 00 00 00 01 00"));
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 2A 24 00 30 02")), Hex("8E 00 00 00 01 00"));
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 2A 24 00 30 07")), Hex("8E 00 00 00 2E 00"));
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 2A 24 01 30 01")), Hex("8E 00 00 00 13"));
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 2A 24 01 30 02")),
            Hex("8E 00 00 00 01 02 03 04 06 07 08 09 0A 0B 0F 12 13 14 15 1A 1C 1D 2E"));
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 2A 24 01 30 06")), Hex("8E 00 00 00 01"));
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 2A 24 01 30 1A")), Hex("8E 00 00 00 00 00"));
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 2A 24 01 30 1C")), Hex("8E 00 00 00 00 00"));
  EXPECT_TRUE(card_.registers.log.empty());
}

TEST_F(AcDcDriveObjectTest, SpeedActualWaitsForFd00) {
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 2A 24 01 30 07")), Hex("8E 00 00 00 08 07"));  // 1800 rpm
  EXPECT_EQ(card_.deferrals, 1);
  EXPECT_EQ(card_.registers.log, (Accesses{Read(0xFD00)}));
  config::CardConfig config;
  config.pole_pairs = 1;  // 2 poles: 3600 rpm at 60 Hz
  card_.runtime.SetCardConfig(config);
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 2A 24 01 30 07")), Hex("8E 00 00 00 10 0E"));
}

TEST_F(AcDcDriveObjectTest, AtReferenceNeedsEnabledAndTheReference) {
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 2A 24 01 30 03")), Hex("8E 00 00 00 00"));  // Ready, not Enabled
  EXPECT_EQ(card_.registers.log, (Accesses{Read(0xFD00), Read(0xFE02)}));
  EXPECT_EQ(card_.deferrals, 1);  // both reads travel together
  card_.Drive(kRunningForward, 0x1770, 0x1770);
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 2A 24 01 30 03")), Hex("8E 00 00 00 01"));
  card_.registers.registers[0xFD00] = 0x1700;  // still accelerating
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 2A 24 01 30 03")), Hex("8E 00 00 00 00"));
}

TEST_F(AcDcDriveObjectTest, MonitorAttributes) {
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 2A 24 01 30 09")), Hex("8E 00 00 00 18 00"));  // 2.4 A
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 2A 24 01 30 0A")), Hex("8E 00 00 00 48 00"));  // 150 % of 4.8 A
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 2A 24 01 30 0B")), Hex("8E 00 00 00 05 00"));  // 5.08 Nm
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 2A 24 01 30 0F")), Hex("8E 00 00 00 EE 02"));  // 750 W
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 2A 24 01 30 2E")), Hex("8E 00 00 00 12 00 00 00"));  // 18 h
  EXPECT_EQ(TorqueNewtonMetres(-10000, 75, 1410), 5);  // regenerating: a magnitude
  EXPECT_EQ(TorqueNewtonMetres(10000, 75, 0), 0);
}

TEST_F(AcDcDriveObjectTest, RampsInMilliseconds) {
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 2A 24 01 30 12")), Hex("8E 00 00 00 10 27"));  // 10000 ms
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 2A 24 01 30 13")), Hex("8E 00 00 00 C4 09"));  // 2500 ms
  card_.registers.registers[0x0519] = 1;  // 0.01 s
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 2A 24 01 30 12")), Hex("8E 00 00 00 E8 03"));  // 1000 ms
}

TEST_F(AcDcDriveObjectTest, SetRampReadsTheUnitThenWritesRamAndEeprom) {
  card_.registers.log.clear();
  EXPECT_EQ(card_.Ask(Hex("10 03 20 2A 24 01 30 12 C4 09")), Hex("90 00 00 00"));  // 2500 ms
  EXPECT_EQ(card_.registers.log, (Accesses{Read(0x0519), WriteW(0x0009, 25)}));
  EXPECT_EQ(card_.deferrals, 2);
  card_.registers.registers[0x0519] = 1;
  card_.registers.log.clear();
  EXPECT_EQ(card_.Ask(Hex("10 03 20 2A 24 01 30 13 C4 09")), Hex("90 00 00 00"));
  EXPECT_EQ(card_.registers.log, (Accesses{Read(0x0519), WriteW(0x0010, 250)}));
}

TEST_F(AcDcDriveObjectTest, SpeedLimitsInRpm) {
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 2A 24 01 30 14")), Hex("8E 00 00 00 96 00"));  // 150 rpm
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 2A 24 01 30 15")), Hex("8E 00 00 00 08 07"));  // 1800 rpm
  card_.registers.log.clear();
  EXPECT_EQ(card_.Ask(Hex("10 03 20 2A 24 01 30 15 60 09")), Hex("90 00 00 00"));  // 2400 rpm
  EXPECT_EQ(card_.Ask(Hex("10 03 20 2A 24 01 30 14 00 00")), Hex("90 00 00 00"));
  EXPECT_EQ(card_.registers.log, (Accesses{Read(0x0856), WriteW(0x0012, 8000), Read(0x0856), WriteW(0x0013, 0)}));
  card_.registers.registers[0x0856] = 4;  // 8 poles: 1800 rpm is 120 Hz
  EXPECT_EQ(card_.Ask(Hex("10 03 20 2A 24 01 30 15 08 07")), Hex("90 00 00 00"));
  EXPECT_EQ(card_.registers.registers[0x0012], 12000);
}

TEST_F(AcDcDriveObjectTest, SetCurrentLimitConvertsThroughTheRatedCurrent) {
  card_.registers.log.clear();
  EXPECT_EQ(card_.Ask(Hex("10 03 20 2A 24 01 30 0A 30 00")), Hex("90 00 00 00"));  // 4.8 A
  EXPECT_EQ(card_.registers.log, (Accesses{Read(0xFE70), WriteW(0x0601, 100)}));
  card_.registers.registers[0xFE70] = 0;
  EXPECT_EQ(card_.Ask(Hex("10 03 20 2A 24 01 30 0A 30 00")), Hex("90 00 09 00"));
}

TEST_F(AcDcDriveObjectTest, ScalingOnlyZero) {
  EXPECT_EQ(card_.Ask(Hex("10 03 20 2A 24 01 30 1A 00 00")), Hex("90 00 00 00"));
  EXPECT_EQ(card_.Ask(Hex("10 03 20 2A 24 01 30 1A 01 00")), Hex("90 00 09 00"));
  EXPECT_EQ(card_.Ask(Hex("10 03 20 2A 24 01 30 1C 02 00")), Hex("90 00 09 00"));
  EXPECT_EQ(card_.Ask(Hex("10 03 20 2A 24 01 30 1C 00")), Hex("90 00 13 00"));
}

TEST_F(AcDcDriveObjectTest, AccessErrors) {
  card_.registers.registers.erase(0x0013);
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 2A 24 01 30 14")), Hex("8E 00 14 00"));  // no ll: no such attribute
  card_.registers.errors[0x0012] = drive_link::AccessError::kOutOfRange;
  EXPECT_EQ(card_.Ask(Hex("10 03 20 2A 24 01 30 15 FF 7F")), Hex("90 00 09 00"));
  card_.registers.errors[0x0012] = drive_link::AccessError::kNotWritableWhileRunning;
  EXPECT_EQ(card_.Ask(Hex("10 03 20 2A 24 01 30 15 08 07")), Hex("90 00 10 00"));
  card_.registers.link_down = true;
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 2A 24 01 30 07")), Hex("8E 00 10 00"));
  card_.registers.link_down = false;
  card_.registers.busy_next = 1;
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 2A 24 01 30 2E")), Hex("8E 00 02 00"));
}

TEST_F(AcDcDriveObjectTest, NotSettableAndUnknown) {
  EXPECT_EQ(card_.Ask(Hex("10 03 20 2A 24 01 30 07 08 07")), Hex("90 00 0E 00"));
  EXPECT_EQ(card_.Ask(Hex("10 03 20 2A 24 01 30 1D 01")), Hex("90 00 0E 00"));
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 2A 24 01 30 05")), Hex("8E 00 14 00"));
  EXPECT_EQ(card_.Ask(Hex("10 03 20 2A 24 01 30 04 05")), Hex("90 00 09 00"));
  EXPECT_EQ(card_.Ask(Hex("10 03 20 2A 24 01 30 08 08")), Hex("90 00 13 00"));
  EXPECT_TRUE(card_.registers.log.empty());
  EXPECT_TRUE(card_.channel.commands.empty());
}

}  // namespace
}  // namespace cip::drive
