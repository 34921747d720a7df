// The drive profile's runtime through its assemblies (cip/drive/drive_assemblies.h,
// drive_profile_runtime.h): Describe's points, kinds, sizes and refusals; §5's worked examples from the
// consumed packet to SetDriveCommand and back to the produced bytes; idle; scanner masks; the parameter
// channel over the register fake; explicit access to the assemblies; connection changes and feedback.
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <vector>

#include "drive_channel_fake.h"

namespace cip::drive {
namespace {

using drive_link::DriveCommandWords;
using test::Bytes;
using test::DriveCard;
using test::FakeDriveCommandChannel;
using test::Hex;
using test::kRunningForward;
using test::kRunningReverse;
using test::kStandby;
using test::kTripped;
using test::Of;

using Commands = std::vector<DriveCommandWords>;

class DriveAssembliesTest : public ::testing::Test {
 protected:
  void Consume(std::uint32_t point, const Bytes& data, bool run = true) { card_.assemblies.Consume(point, data, run); }
  Bytes Produce(std::uint32_t point, std::size_t size) {
    Bytes out(size, 0xEE);
    card_.assemblies.Produce(point, out);
    return out;
  }
  IoConnectionSpec Describe(std::optional<std::uint32_t> configuration, std::uint32_t consumed, std::uint32_t produced,
                            std::uint16_t consumed_size = 0, std::uint16_t produced_size = 0) {
    return card_.assemblies.Describe(IoPoints{configuration, consumed, produced}, {consumed_size, produced_size});
  }

  DriveCard card_;
};

// ---- Describe -------------------------------------------------------------------------------------------

TEST_F(DriveAssembliesTest, DescribesTheDocumentedPairsAsExclusiveOwners) {
  const std::array<std::array<std::uint16_t, 3>, 6> pairs = {{
      {20, 70, 4}, {21, 71, 4}, {101, 151, 8}, {102, 152, 12}, {105, 155, 18}, {100, 150, 16},
  }};
  for (const auto& [consumed, produced, size] : pairs) {
    const IoConnectionSpec spec = Describe(1, consumed, produced, size, size);
    EXPECT_EQ(spec.extended, 0) << consumed;
    EXPECT_EQ(spec.kind, IoConnectionKind::kExclusiveOwner) << consumed;
    EXPECT_EQ(spec.consumed_size, size) << consumed;
    EXPECT_EQ(spec.produced_size, size) << consumed;
    EXPECT_EQ(spec.configuration_size, 0) << consumed;
  }
}

// One owner of the drive command: while an exclusive owner of one command output is open (20, 21, 100,
// 101; 102/105 while a c00n menu targets FA06/FA07), an exclusive owner of another is a conflict (the
// Connection Manager answers 0x0106). The same point is the manager's own check (IsOwned).
TEST_F(DriveAssembliesTest, ASecondCommandOutputOwnerConflicts) {
  for (const std::uint32_t owned : {20U, 21U, 100U, 101U, 102U, 105U}) {
    card_.ownership.owned = {owned};
    for (const std::uint32_t consumed : {20U, 21U, 100U, 101U, 102U, 105U}) {
      const IoConnectionSpec spec = Describe(1, consumed, 150, 4, 4);
      EXPECT_EQ(spec.owner_conflict, consumed != owned) << owned << " owned, " << consumed << " asked";
    }
    EXPECT_FALSE(Describe(1, 199, 71, 0, 4).owner_conflict);  // input only
    EXPECT_FALSE(Describe(1, 198, 71, 0, 4).owner_conflict);  // listen only
  }
  card_.ownership.owned.clear();
  for (const std::uint32_t consumed : {20U, 21U, 100U, 101U, 102U, 105U}) {
    EXPECT_FALSE(Describe(1, consumed, 150, 4, 4).owner_conflict) << consumed;
  }
}

TEST_F(DriveAssembliesTest, ScannerOutputsWithoutDriveCommandMenusCoexistWithACommandOwner) {
  config::CardConfig config;
  config.command_menus = {0, 0, 0, 0, 0, 0};  // no c00n targets FA06/FA07
  card_.runtime.SetCardConfig(config);
  card_.ownership.owned = {21};
  EXPECT_FALSE(Describe(1, 102, 152, 12, 12).owner_conflict);
  EXPECT_FALSE(Describe(1, 105, 155, 18, 18).owner_conflict);
  EXPECT_TRUE(Describe(1, 100, 150, 4, 4).owner_conflict);
  card_.ownership.owned = {102};
  EXPECT_FALSE(Describe(1, 21, 71, 4, 4).owner_conflict);
  EXPECT_FALSE(Describe(1, 105, 155, 18, 18).owner_conflict);
}

TEST_F(DriveAssembliesTest, AnyOutputPairsWithAnyInputAndTheConfigurationPointMayBeAbsent) {
  const IoConnectionSpec spec = Describe(std::nullopt, 21, 155, 4, 18);
  EXPECT_EQ(spec.extended, 0);
  EXPECT_EQ(spec.consumed_size, 4);
  EXPECT_EQ(spec.produced_size, 18);
}

TEST_F(DriveAssembliesTest, HeartbeatsMakeInputOnlyAndListenOnly) {
  IoConnectionSpec spec = Describe(1, 199, 71, 0, 4);
  EXPECT_EQ(spec.extended, 0);
  EXPECT_EQ(spec.kind, IoConnectionKind::kInputOnly);
  EXPECT_EQ(spec.consumed_size, 0);
  EXPECT_EQ(spec.produced_size, 4);
  spec = Describe(1, 198, 150, 0, 8);
  EXPECT_EQ(spec.extended, 0);
  EXPECT_EQ(spec.kind, IoConnectionKind::kListenOnly);
  EXPECT_EQ(spec.consumed_size, 0);
  EXPECT_EQ(spec.produced_size, 8);
}

TEST_F(DriveAssembliesTest, NativeSizesAreTheRequestedEvenSizeFrom4To16ElseTheLargest) {
  for (std::uint16_t size = 4; size <= 16; size += 2) {
    const IoConnectionSpec spec = Describe(1, 100, 150, size, static_cast<std::uint16_t>(20 - size));
    EXPECT_EQ(spec.consumed_size, size);
    EXPECT_EQ(spec.produced_size, 20 - size);
  }
  for (const std::uint16_t size : std::array<std::uint16_t, 8>{0, 2, 3, 5, 15, 17, 18, 100}) {
    const IoConnectionSpec spec = Describe(1, 100, 150, size, size);
    EXPECT_EQ(spec.extended, 0);  // the Connection Manager refuses with 0x0127/0x0128 naming 16
    EXPECT_EQ(spec.consumed_size, 16) << size;
    EXPECT_EQ(spec.produced_size, 16) << size;
  }
  // Every other point has its one size whatever is asked.
  const IoConnectionSpec spec = Describe(1, 101, 151, 6, 10);
  EXPECT_EQ(spec.consumed_size, 8);
  EXPECT_EQ(spec.produced_size, 8);
}

TEST_F(DriveAssembliesTest, RefusalCodes) {
  EXPECT_EQ(Describe(2, 21, 71, 4, 4).extended, 0x0129);    // configuration point other than 1
  EXPECT_EQ(Describe(21, 21, 71, 4, 4).extended, 0x0129);
  EXPECT_EQ(Describe(1, 22, 71, 4, 4).extended, 0x012A);    // no such consumed point
  EXPECT_EQ(Describe(1, 197, 71, 4, 4).extended, 0x012A);
  EXPECT_EQ(Describe(1, 21, 72, 4, 4).extended, 0x012B);    // no such produced point
  EXPECT_EQ(Describe(1, 21, 0, 4, 4).extended, 0x012B);
  EXPECT_EQ(Describe(1, 70, 71, 4, 4).extended, 0x012F);    // an input consumed
  EXPECT_EQ(Describe(1, 21, 20, 4, 4).extended, 0x012F);    // an output produced
  EXPECT_EQ(Describe(1, 21, 199, 4, 0).extended, 0x012F);   // a heartbeat produced
  EXPECT_EQ(Describe(1, 1, 71, 0, 4).extended, 0x012F);     // the configuration point as data
  // The configuration check comes first, then consumed, then produced.
  EXPECT_EQ(Describe(3, 22, 72, 4, 4).extended, 0x0129);
  EXPECT_EQ(Describe(1, 22, 72, 4, 4).extended, 0x012A);
}

// ---- §5 worked examples ---------------------------------------------------------------------------------

TEST_F(DriveAssembliesTest, ExtendedSpeedForward1800Rpm) {
  card_.Drive(kStandby);
  Consume(21, Hex("61 00 08 07"));
  EXPECT_EQ(card_.channel.commands, (Commands{{0xC400, 0x1770}}));
  EXPECT_TRUE(card_.channel.masked.empty());
  // The drive runs forward at the reference.
  card_.Drive(kRunningForward, 0x1770, 0x1770);
  EXPECT_EQ(Produce(71, 4), Hex("F4 04 08 07"));
  EXPECT_EQ(card_.channel.commands.size(), 1u);  // nothing changed: nothing handed over again
}

TEST_F(DriveAssembliesTest, ExtendedSpeedStop) {
  card_.Drive(kStandby);
  Consume(21, Hex("00 00 00 00"));
  EXPECT_EQ(card_.channel.commands, (Commands{{0x0000, 0x0000}}));
  EXPECT_EQ(Produce(71, 4), Hex("10 03 00 00"));  // Ready, state 3
}

TEST_F(DriveAssembliesTest, ExtendedSpeedReverse) {
  card_.Drive(kStandby);
  Consume(21, Hex("62 00 08 07"));
  EXPECT_EQ(card_.channel.commands, (Commands{{0xC600, 0x1770}}));
  card_.Drive(kRunningReverse, 0x1770, 0x1770);
  EXPECT_EQ(Produce(71, 4), Hex("F8 04 08 07"));  // Running2
}

TEST_F(DriveAssembliesTest, BasicSpeedForward1800RpmUsesTheAttributesForThePriorities) {
  card_.Drive(kStandby);
  Consume(20, Hex("01 00 08 07"));
  EXPECT_EQ(card_.channel.commands, (Commands{{0x0400, 0x1770}}));
  card_.Drive(kRunningForward, 0x1770, 0x1770);
  EXPECT_EQ(Produce(70, 4), Hex("04 00 08 07"));
}

TEST_F(DriveAssembliesTest, NativeForwardAndReverse60Hz) {
  card_.Drive(kStandby);
  Consume(100, Hex("00 C4 70 17"));
  EXPECT_EQ(card_.channel.commands, (Commands{{0xC400, 0x1770}}));
  card_.Drive(kRunningForward, 0x1770, 0x1770);
  EXPECT_EQ(Produce(150, 4), Hex("00 64 70 17"));
  Consume(100, Hex("00 C6 70 17"));
  EXPECT_EQ(card_.channel.commands.back(), (DriveCommandWords{0xC600, 0x1770}));
  card_.Drive(kRunningReverse, 0x1770, 0x1770);
  EXPECT_EQ(Produce(150, 4), Hex("00 66 70 17"));
  card_.Drive(kStandby | 0x0800);  // stopped with ST off: FD01 4800h
  EXPECT_EQ(Produce(150, 4), Hex("00 48 00 00"));
}

// The supervisor follows the newest FD01; FD00/FE02 and their FD01 come from one exchange cycle. While
// that cycle's FD01 does not show the drive running yet (it just started), 71 is not "at reference"
// although FD00 = FE02 = 0 (the eip_scanner test saw `F4 04 00 00` for one packet at each start).
TEST_F(DriveAssembliesTest, AtReferenceWaitsForTheFeedbackCycleThatSeesTheDriveRunning) {
  card_.Drive(kStandby);
  Consume(21, Hex("61 00 08 07"));
  card_.status.status = DriveStatus{true, kRunningForward};
  card_.channel.feedback = drive_link::DriveFeedbackWords{kStandby, 0, 0, true};
  EXPECT_EQ(Produce(71, 4), Hex("74 04 00 00"));
  card_.channel.feedback = drive_link::DriveFeedbackWords{kRunningForward, 0x0100, 0x1770, true};
  EXPECT_EQ(Produce(71, 4), Hex("74 04 4D 00"));  // 2.56 Hz = 77 rpm (2 pole pairs)
  card_.channel.feedback = drive_link::DriveFeedbackWords{kRunningForward, 0x1770, 0x1770, true};
  EXPECT_EQ(Produce(71, 4), Hex("F4 04 08 07"));
}

TEST_F(DriveAssembliesTest, NativeParameterRunsAs21AndAnswersInIts151) {
  card_.Drive(kStandby);
  Consume(101, Hex("61 00 08 07 68 02 00 00"));  // forward 1800 rpm, read f268
  EXPECT_EQ(card_.channel.commands, (Commands{{0xC400, 0x1770}}));
  ASSERT_EQ(card_.registers.log.size(), 1u);
  EXPECT_EQ(card_.registers.log[0],
            (drive_link::test::ScriptedDriveRegisters::Access{false, 0x0268, 0, drive_link::WriteMode::kRamOnly}));
  card_.Drive(kRunningForward, 0x1770, 0x1770);
  EXPECT_EQ(Produce(151, 8), Hex("F4 04 08 07 00 00 00 00"));  // no answer yet
  card_.registers.CompleteWith(drive_link::AccessResult{drive_link::AccessError::kNone, 0, 0x1770});
  EXPECT_EQ(Produce(151, 8), Hex("F4 04 08 07 68 02 70 17"));
}

// ---- Fault reset and idle -------------------------------------------------------------------------------

TEST_F(DriveAssembliesTest, FaultResetIsSentOnceOnItsEdge) {
  card_.Drive(kTripped);
  Consume(21, Hex("04 00 00 00"));
  Consume(21, Hex("04 00 00 00"));
  Consume(21, Hex("04 00 00 00"));
  EXPECT_EQ(card_.channel.commands, (Commands{{0x2000, 0x0000}, {0x0000, 0x0000}}));
  Consume(21, Hex("00 00 00 00"));
  Consume(21, Hex("04 00 00 00"));  // a new edge
  EXPECT_EQ(card_.channel.commands, (Commands{{0x2000, 0}, {0, 0}, {0x2000, 0}}));
}

TEST_F(DriveAssembliesTest, FaultResetOnlyWhileTripped) {
  card_.Drive(kStandby);
  Consume(21, Hex("04 00 00 00"));
  EXPECT_EQ(card_.channel.commands, (Commands{{0x0000, 0x0000}}));
}

TEST_F(DriveAssembliesTest, NativeFaultResetBitIsAnEdgeToo) {
  card_.Drive(kStandby);  // 100 is FA06 itself: sent on every edge, tripped or not
  Consume(100, Hex("00 20 00 00"));
  Consume(100, Hex("00 20 00 00"));
  EXPECT_EQ(card_.channel.commands, (Commands{{0x2000, 0x0000}, {0x0000, 0x0000}}));
}

TEST_F(DriveAssembliesTest, IdleDataIsNotApplied) {
  card_.Drive(kTripped);
  Consume(21, Hex("65 00 08 07"), /*run=*/false);
  Consume(100, Hex("00 E4 70 17 01 00"), false);
  Consume(101, Hex("61 00 08 07 68 02 00 00"), false);
  Consume(102, Hex("01 00 02 00 03 00 04 00 05 00 06 00"), false);
  EXPECT_TRUE(card_.channel.commands.empty());
  EXPECT_TRUE(card_.channel.masked.empty());
  EXPECT_TRUE(card_.registers.log.empty());
  EXPECT_EQ(Of(card_.assemblies.Memory(21)), Hex("00 00 00 00"));
  // Run again: the first packet in run mode counts from zero levels (its fault reset is an edge).
  Consume(21, Hex("04 00 00 00"));
  EXPECT_EQ(card_.channel.commands, (Commands{{0x2000, 0x0000}}));
}

// ---- Scanner words --------------------------------------------------------------------------------------

TEST_F(DriveAssembliesTest, NativeOfSixWordsWritesScannerWords3And4Only) {
  card_.Drive(kStandby);
  Consume(100, Hex("00 C4 70 17 11 11 22 22 33 33 44 44"));
  EXPECT_EQ(card_.channel.commands, (Commands{{0xC400, 0x1770}}));
  // Factory c001 = 1 (FA06) and c002 = 3 (FA07): words 1-2 of 100 own those registers.
  ASSERT_EQ(card_.channel.masked.size(), 1u);
  EXPECT_EQ(card_.channel.masked[0],
            (FakeDriveCommandChannel::MaskedWords{{0x1111, 0x2222, 0x3333, 0x4444, 0, 0}, 0x0C}));
}

TEST_F(DriveAssembliesTest, NativeScannerMaskFollowsTheMenus) {
  config::CardConfig config;
  config.command_menus = {13, 14, 0, 0, 0, 1};  // acc, dec, -, -, -, FA06
  card_.runtime.SetCardConfig(config);
  Consume(100, Hex("00 00 00 00 01 00 02 00 03 00 04 00 05 00 06 00"));
  ASSERT_EQ(card_.channel.masked.size(), 1u);
  EXPECT_EQ(card_.channel.masked[0].mask, 0x1F);
  // Two words only: no scanner word, and no call that would silence another connection's words.
  Consume(100, Hex("00 00 00 00"));
  EXPECT_EQ(card_.channel.masked.size(), 1u);
}

TEST_F(DriveAssembliesTest, ScannerAssemblyWritesAllSixWordsAndNoDriveCommand) {
  Consume(102, Hex("01 00 02 00 03 00 04 00 05 00 06 00"));
  ASSERT_EQ(card_.channel.masked.size(), 1u);
  EXPECT_EQ(card_.channel.masked[0], (FakeDriveCommandChannel::MaskedWords{{1, 2, 3, 4, 5, 6}, 0x3F}));
  EXPECT_TRUE(card_.channel.commands.empty());
  card_.scanner.monitor_words = {0x6400, 0x1770, 0x1234, 0, 0, 0x0012};
  EXPECT_EQ(Produce(152, 12), Hex("00 64 70 17 34 12 00 00 00 00 12 00"));
}

// ---- Parameter channel ----------------------------------------------------------------------------------

TEST_F(DriveAssembliesTest, ParameterWriteOkAndNg) {
  card_.Drive(kStandby);
  card_.registers.registers[0x0018] = 0;
  Consume(101, Hex("00 00 00 00 18 80 70 17"));  // write sr1 = 60 Hz
  ASSERT_EQ(card_.registers.log.size(), 1u);
  EXPECT_EQ(card_.registers.log[0], (drive_link::test::ScriptedDriveRegisters::Access{
                                        true, 0x0018, 0x1770, drive_link::WriteMode::kRamAndEeprom}));
  card_.registers.CompleteAll();
  EXPECT_EQ(Produce(151, 8), Hex("10 03 00 00 18 80 70 17"));
  Consume(101, Hex("00 00 00 00 18 80 70 17"));  // the same request: not executed again
  EXPECT_EQ(card_.registers.log.size(), 1u);
  Consume(101, Hex("00 00 00 00 18 80 71 17"));
  card_.registers.CompleteWith(drive_link::AccessResult{drive_link::AccessError::kOutOfRange, 0, 0});
  EXPECT_EQ(Produce(151, 8), Hex("10 03 00 00 18 C0 00 11"));
}

TEST_F(DriveAssembliesTest, ToshibaSpecificReadAndScannerWords) {
  card_.registers.registers[0x0003] = 0;
  Consume(105, Hex("00 00 03 00 00 00 01 00 02 00 03 00 04 00 05 00 06 00"));  // read cmod
  EXPECT_EQ(card_.channel.masked.back(), (FakeDriveCommandChannel::MaskedWords{{1, 2, 3, 4, 5, 6}, 0x3F}));
  card_.registers.CompleteAll();
  card_.scanner.monitor_words = {1, 2, 3, 4, 5, 6};
  EXPECT_EQ(Produce(155, 18), Hex("00 00 03 00 00 00 01 00 02 00 03 00 04 00 05 00 06 00"));
  Consume(105, Hex("00 80 18 00 70 17 01 00 02 00 03 00 04 00 05 00 06 00"));  // write sr1, refused
  card_.registers.CompleteWith(drive_link::AccessResult{drive_link::AccessError::kRefused, 0, 0});
  EXPECT_EQ(Produce(155, 18), Hex("00 40 18 00 01 00 01 00 02 00 03 00 04 00 05 00 06 00"));
}

TEST_F(DriveAssembliesTest, ParameterAccessIsRetriedWhenThePoolIsFull) {
  card_.registers.registers[0x0268] = 0x1770;
  card_.assemblies.Poll(1000);
  card_.registers.busy_next = 1;
  Consume(101, Hex("00 00 00 00 68 02 00 00"));
  EXPECT_TRUE(card_.registers.log.empty());
  EXPECT_EQ(card_.assemblies.NextDeadline(), 2000u);
  card_.assemblies.Poll(1999);
  EXPECT_TRUE(card_.registers.log.empty());
  card_.assemblies.Poll(2000);
  ASSERT_EQ(card_.registers.log.size(), 1u);
  EXPECT_EQ(card_.assemblies.NextDeadline(), hal::kNever);
  card_.registers.CompleteAll();
  EXPECT_EQ(Produce(151, 8), Hex("10 03 00 00 68 02 70 17"));
}

TEST_F(DriveAssembliesTest, ParameterAccessWithTheLinkDownAnswersAnError) {
  card_.registers.link_down = true;
  Consume(101, Hex("00 00 00 00 68 02 00 00"));
  EXPECT_EQ(Produce(151, 8), Hex("10 03 00 00 68 42 00 11"));  // 0x1100 data out of range
}

// ---- Explicit access ------------------------------------------------------------------------------------

TEST_F(DriveAssembliesTest, AssemblyClassReads199And13) {
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 04 24 00 30 02")), Hex("8E 00 00 00 C7 00"));
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 04 24 00 30 03")), Hex("8E 00 00 00 0D 00"));
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 04 24 64 30 04")), Hex("8E 00 00 00 10 00"));  // 100: 16 bytes
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 04 24 C7 30 04")), Hex("8E 00 00 00 00 00"));  // 199: heartbeat
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 04 24 C6 30 03")), Hex("8E 00 16 00"));         // 198: a point only
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 04 24 01 30 03")), Hex("8E 00 16 00"));         // 1: a point only
}

TEST_F(DriveAssembliesTest, ExplicitSetOfAnOwnedOutputIsADeviceStateConflict) {
  card_.ownership.owned = {21};
  EXPECT_EQ(card_.Ask(Hex("10 03 20 04 24 15 30 03 61 00 08 07")), Hex("90 00 10 00"));
  // Another command assembly would fight the owner over FA06 as well.
  EXPECT_EQ(card_.Ask(Hex("10 03 20 04 24 14 30 03 01 00 08 07")), Hex("90 00 10 00"));
  EXPECT_TRUE(card_.channel.commands.empty());
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 04 24 15 30 03")), Hex("8E 00 00 00 00 00 00 00"));
  // 102 carries no FA06 of its own: only its own owner blocks it.
  EXPECT_EQ(card_.Ask(Hex("10 03 20 04 24 66 30 03 01 00 02 00 03 00 04 00 05 00 06 00")), Hex("90 00 00 00"));
  card_.ownership.owned = {102};
  EXPECT_EQ(card_.Ask(Hex("10 03 20 04 24 66 30 03 01 00 02 00 03 00 04 00 05 00 06 00")), Hex("90 00 10 00"));
}

TEST_F(DriveAssembliesTest, ExplicitSetOfAFreeOutputCommandsTheDrive) {
  card_.Drive(kStandby);
  EXPECT_EQ(card_.Ask(Hex("10 03 20 04 24 15 30 03 61 00 08 07")), Hex("90 00 00 00"));
  EXPECT_EQ(card_.channel.commands, (Commands{{0xC400, 0x1770}}));
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 04 24 15 30 03")), Hex("8E 00 00 00 61 00 08 07"));
  EXPECT_EQ(card_.Ask(Hex("10 03 20 04 24 15 30 03 61 00 08")), Hex("90 00 13 00"));  // short
  EXPECT_EQ(card_.Ask(Hex("10 03 20 04 24 47 30 03 00 00 00 00")), Hex("90 00 0E 00"));  // an input
  EXPECT_EQ(card_.Ask(Hex("10 03 20 04 24 C7 30 03")), Hex("90 00 00 00"));  // heartbeat: nothing to do
}

// docs/drive-control.md: an explicit write of a command output while a loss holds the drive: a run or
// scanner words 0x10 and nothing handed over; a stop (21 without run bits, 100 without run/jog) taken
// and held as the loss action's FA06.
TEST_F(DriveAssembliesTest, ExplicitOutputWhileALossHoldsTheDriveTakesStopsOnly) {
  card_.Drive(kStandby);
  card_.channel.held_by_loss = true;
  EXPECT_EQ(card_.Ask(Hex("10 03 20 04 24 15 30 03 61 00 08 07")), Hex("90 00 10 00"));  // 21 run forward
  EXPECT_EQ(card_.Ask(Hex("10 03 20 04 24 64 30 03 00 C4 70 17 00 00 00 00 00 00 00 00 00 00 00 00")), Hex("90 00 10 00"));  // 100 C400h
  EXPECT_EQ(card_.Ask(Hex("10 03 20 04 24 66 30 03 01 00 02 00 03 00 04 00 05 00 06 00")), Hex("90 00 10 00"));
  EXPECT_TRUE(card_.channel.commands.empty());
  EXPECT_EQ(card_.Ask(Hex("10 03 20 04 24 15 30 03 60 00 08 07")), Hex("90 00 00 00"));  // 21 stop
  EXPECT_EQ(card_.channel.commands, (Commands{{0xC000, 0x1770}}));
  EXPECT_EQ(card_.Ask(Hex("10 03 20 04 24 64 30 03 00 88 70 17 00 00 00 00 00 00 00 00 00 00 00 00")), Hex("90 00 00 00"));  // 100 coast
  EXPECT_EQ(card_.channel.commands.back(), (DriveCommandWords{0x8800, 0x1770}));
  EXPECT_EQ(card_.channel.held_stops, (std::vector<std::uint16_t>{0xC000, 0x8800}));
}

TEST_F(DriveAssembliesTest, ExplicitGetOfAnInputIsLive) {
  card_.Drive(kStandby);
  Consume(21, Hex("61 00 08 07"));
  card_.Drive(kRunningForward, 0x1770, 0x1770);
  card_.scanner.monitor_words = {1, 2, 3, 4, 5, 6};
  card_.assemblies.Poll(1000);
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 04 24 47 30 03")), Hex("8E 00 00 00 F4 04 08 07"));
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 04 24 96 30 03")),
            Hex("8E 00 00 00 00 64 70 17 01 00 02 00 03 00 04 00 05 00 06 00"));
  card_.Drive(kTripped);
  card_.assemblies.Poll(2000);
  EXPECT_EQ(card_.Ask(Hex("0E 03 20 04 24 46 30 03")), Hex("8E 00 00 00 01 00 00 00"));  // Faulted
  EXPECT_EQ(card_.Ask(Hex("10 03 20 04 24 46 30 03 00 00 00 00")), Hex("90 00 0E 00"));
}

// ---- Connections, supervision and feedback --------------------------------------------------------------

TEST_F(DriveAssembliesTest, ATripDropsTheRunAndAHeldLevelNeedsANewEdge) {
  card_.Drive(kStandby);
  Consume(21, Hex("61 00 08 07"));
  card_.Drive(kRunningForward, 0x1770, 0x1770);
  card_.assemblies.Poll(500);
  EXPECT_EQ(card_.runtime.supervisor().state(), SupervisorState::kEnabled);
  card_.Drive(kRunningForward | kTripped, 0x1000, 0x1770);  // tripped while running: Fault_Stop
  card_.assemblies.Poll(1000);
  EXPECT_EQ(card_.runtime.supervisor().state(), SupervisorState::kFaultStop);
  EXPECT_EQ(card_.channel.commands, (Commands{{0xC400, 0x1770}, {0xC000, 0x1770}}));
  card_.Drive(kStandby);  // reset (panel): Ready again, but Run Fwd is still held at 1
  Consume(21, Hex("61 00 08 07"));
  card_.assemblies.Poll(2000);
  EXPECT_EQ(card_.channel.commands.back(), (DriveCommandWords{0xC000, 0x1770}));
  Consume(21, Hex("60 00 08 07"));
  Consume(21, Hex("61 00 08 07"));
  EXPECT_EQ(card_.channel.commands.back(), (DriveCommandWords{0xC400, 0x1770}));
}

TEST_F(DriveAssembliesTest, TheControllingConnectionGoingAwayReleasesWithoutWriting) {
  card_.Drive(kTripped);
  card_.ownership.owned = {101};
  card_.assemblies.OnConnectionsChanged();
  card_.registers.registers[0x0268] = 0x1770;
  Consume(101, Hex("05 00 08 07 68 02 00 00"));
  card_.registers.CompleteAll();
  EXPECT_EQ(Produce(151, 8), Hex("01 07 00 00 68 02 70 17"));
  const std::size_t written = card_.channel.commands.size();
  card_.ownership.owned.clear();  // closed or timed out
  card_.assemblies.OnConnectionsChanged();
  EXPECT_EQ(card_.channel.releases, 1);
  EXPECT_FALSE(card_.channel.taken);
  EXPECT_EQ(card_.channel.commands.size(), written);  // nothing written for it
  EXPECT_FALSE(card_.runtime.run1());
  EXPECT_EQ(Produce(151, 8), Hex("01 07 00 00 00 00 00 00"));  // the channel starts empty
  // A new connection: its first packet's fault reset is an edge again.
  card_.ownership.owned = {101};
  card_.assemblies.OnConnectionsChanged();
  Consume(101, Hex("04 00 00 00 00 00 00 00"));
  EXPECT_EQ(card_.channel.commands.back(), (DriveCommandWords{0x2000, 0x0000}));
}

// A closed 102's words must not keep FA06/FA07 reserved for nobody, nor come back when another owner
// gives the drive command back (found by integration.drive_control_matrix, docs/drive-control.md).
TEST_F(DriveAssembliesTest, TheScannerConnectionGoingAwayTakesItsWordsOut) {
  card_.ownership.owned = {102};
  card_.assemblies.OnConnectionsChanged();
  Consume(102, Hex("00 C4 B8 0B 00 00 00 00 00 00 00 00"));
  ASSERT_EQ(card_.channel.masked.size(), 1u);
  EXPECT_EQ(card_.channel.masked[0], (FakeDriveCommandChannel::MaskedWords{{0xC400, 0x0BB8, 0, 0, 0, 0}, 0x3F}));
  card_.ownership.owned = {102, 21};  // another point opened: the scanner's master is still there
  card_.assemblies.OnConnectionsChanged();
  EXPECT_EQ(card_.channel.masked.size(), 1u);
  card_.ownership.owned = {21};  // 102 closed or timed out
  card_.assemblies.OnConnectionsChanged();
  ASSERT_EQ(card_.channel.masked.size(), 2u);
  EXPECT_EQ(card_.channel.masked[1], (FakeDriveCommandChannel::MaskedWords{{0, 0, 0, 0, 0, 0}, 0x00}));
  card_.ownership.owned.clear();  // once only, and not for a connection that sent no scanner words
  card_.assemblies.OnConnectionsChanged();
  EXPECT_EQ(card_.channel.masked.size(), 2u);
  EXPECT_EQ(card_.channel.releases, 0);
}

TEST_F(DriveAssembliesTest, TheCommandIsTakenAgainAfterTheDriveLinkGaveItBack) {
  card_.Drive(kStandby);
  Consume(21, Hex("61 00 08 07"));
  card_.assemblies.Poll(1000);
  EXPECT_EQ(card_.channel.commands.size(), 1u);
  card_.channel.taken = false;  // a card reset (f899 = 1) gave FA06/FA07 back
  card_.assemblies.Poll(2000);
  EXPECT_EQ(card_.channel.commands, (Commands{{0xC400, 0x1770}, {0xC400, 0x1770}}));
  EXPECT_TRUE(card_.channel.taken);
}

TEST_F(DriveAssembliesTest, FeedbackIsWantedWhileSpeedStatusIsProduced) {
  card_.assemblies.Poll(1000);
  (void)Produce(152, 12);
  EXPECT_FALSE(card_.channel.wanted);
  (void)Produce(71, 4);
  EXPECT_TRUE(card_.channel.wanted);
  card_.assemblies.Poll(2000);
  EXPECT_EQ(card_.assemblies.NextDeadline(), 2000u + 11 * hal::kMicrosPerSecond);
  (void)Produce(151, 8);
  card_.assemblies.Poll(5 * hal::kMicrosPerSecond);
  card_.assemblies.Poll(15 * hal::kMicrosPerSecond);
  EXPECT_TRUE(card_.channel.wanted);
  card_.assemblies.Poll(16 * hal::kMicrosPerSecond);
  EXPECT_FALSE(card_.channel.wanted);
  EXPECT_EQ(card_.channel.wanted_calls, (std::vector<bool>{true, false}));
  EXPECT_EQ(card_.assemblies.NextDeadline(), hal::kNever);
}

TEST_F(DriveAssembliesTest, UnknownFeedbackIsNeverAtReference) {
  card_.Drive(kStandby);
  Consume(21, Hex("61 00 00 00"));  // forward at 0 rpm
  card_.status.status = DriveStatus{true, kRunningForward};
  card_.channel.feedback = drive_link::DriveFeedbackWords{};  // FD00/FE02 not read yet
  EXPECT_EQ(Produce(71, 4), Hex("74 04 00 00"));
}

}  // namespace
}  // namespace cip::drive
