// The drive profile of the EtherNet/IP side (docs/drive-profile.md): every worked example of seed 000 §5
// (and §3.2.4.1) as exact bytes, decoded and encoded; every bit of every map; the size rules; the
// FA06/FA07 the card writes; the feedback; the parameter channel; the unit conversions.
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <vector>

#include "cip/drive/assembly_codec.h"
#include "cip/drive/drive_units.h"
#include "cip_test_support.h"
#include "drive_link/drive_registers.h"

namespace cip::drive {
namespace {

using drive_link::AccessError;
using drive_link::AccessResult;
using test::Bytes;
using test::Hex;

// FD01 values of §5's examples (and seed 003/E6581913): stopped, running forward, running reverse, tripped.
constexpr std::uint16_t kFd01Stopped = 0x4800;
constexpr std::uint16_t kFd01Forward = 0x6400;
constexpr std::uint16_t kFd01Reverse = 0x6600;
constexpr std::uint16_t kFd01Tripped = 0x0003;

DriveCommand Decode(std::uint32_t instance, const Bytes& data) {
  DriveCommand command;
  EXPECT_TRUE(DecodeOutput(instance, data, command)) << instance;
  return command;
}

Bytes Encode(std::uint32_t instance, const DriveFeedback& feedback, std::size_t size = 0) {
  Bytes out(size == 0 ? AssemblySize(instance) : size, 0xEE);
  EXPECT_TRUE(EncodeInput(instance, feedback, out)) << instance;
  return out;
}

// One connection as the runtime runs it: decode, edges, supervisor, registers; then the feedback.
struct Card {
  OutputEdgeTracker edges;
  ControlSupervisor supervisor;
  DriveContext context;
  std::uint16_t cmod = 1;  // factory (§3.1)
  std::uint16_t fmod = 0;
  std::uint16_t last_fa06 = 0;
  bool run1 = false;  // the levels last consumed (attributes 3/4)
  bool run2 = false;

  CommandWrites Consume(std::uint32_t instance, const Bytes& data, std::uint16_t fd01) {
    const DriveCommand command = Decode(instance, data);
    const OutputEvents events = edges.Track(command);
    ApplyNetBits(command, context.net_ctrl_attribute, context.net_ref_attribute);
    SupervisorInputs in;
    in.drive = DriveStatus{true, fd01};
    if (command.profile == CommandProfile::kCipSpeed) {
      run1 = command.run_forward;
      run2 = command.run_reverse;
      in.fault_reset = events.fault_reset;
    }
    in.run1 = run1;
    in.run2 = run2;
    const SupervisorOutputs out = supervisor.Step(in);
    context.run = out.run;
    context.fault_reset = command.profile == CommandProfile::kNative ? events.fault_reset : out.send_fault_reset;
    const CommandWrites writes = CommandRegisters(command, context);
    if (writes.write_fa06) last_fa06 = writes.fa06;
    return writes;
  }

  DriveFeedback Feedback(std::uint16_t fd01, std::uint16_t fd00, std::uint16_t fe02) {
    supervisor.Step(SupervisorInputs{run1, run2, false, DriveStatus{true, fd01}});
    return MakeFeedback(DriveMonitors{fd01, fd00, fe02}, supervisor.state(), ControlSourcesOf(last_fa06, cmod, fmod),
                        FeedbackOptions{context.pole_pairs, 0});
  }
};

// ---- Sizes and instances ----

TEST(CipDriveAssemblyTest, SizesOfEveryInstanceOfSection5_1) {
  for (std::uint32_t instance : {20u, 21u, 70u, 71u}) {
    EXPECT_TRUE(IsValidSize(instance, 4));
    EXPECT_FALSE(IsValidSize(instance, 2));
    EXPECT_FALSE(IsValidSize(instance, 6));
    EXPECT_EQ(AssemblySize(instance), 4u);
  }
  for (std::uint32_t instance : {100u, 150u}) {
    for (std::size_t bytes = 0; bytes <= 20; ++bytes) {
      EXPECT_EQ(IsValidSize(instance, bytes), bytes >= 4 && bytes <= 16 && bytes % 2 == 0) << instance << " " << bytes;
    }
    EXPECT_EQ(AssemblySize(instance), 16u);
  }
  EXPECT_TRUE(IsValidSize(101, 8));
  EXPECT_TRUE(IsValidSize(151, 8));
  EXPECT_TRUE(IsValidSize(102, 12));
  EXPECT_TRUE(IsValidSize(152, 12));
  EXPECT_TRUE(IsValidSize(105, 18));
  EXPECT_TRUE(IsValidSize(155, 18));
  EXPECT_FALSE(IsValidSize(101, 4));
  EXPECT_FALSE(IsValidSize(105, 16));
  EXPECT_FALSE(IsValidSize(152, 13));
  for (std::uint32_t other : {0u, 1u, 22u, 72u, 103u, 198u, 199u, 0x10064u}) {
    EXPECT_FALSE(IsValidSize(other, 0)) << other;
    EXPECT_FALSE(IsValidSize(other, 4)) << other;
    EXPECT_EQ(AssemblySize(other), 0u) << other;
    EXPECT_FALSE(IsOutputInstance(other));
    EXPECT_FALSE(IsInputInstance(other));
  }
  EXPECT_EQ(kMaxAssemblySize, 18u);
}

TEST(CipDriveAssemblyTest, DirectionsAndPairs) {
  for (std::size_t i = 0; i < kOutputInstances.size(); ++i) {
    EXPECT_TRUE(IsOutputInstance(kOutputInstances[i]));
    EXPECT_FALSE(IsInputInstance(kOutputInstances[i]));
    EXPECT_TRUE(IsInputInstance(kInputInstances[i]));
    EXPECT_FALSE(IsOutputInstance(kInputInstances[i]));
    EXPECT_EQ(PairedInput(kOutputInstances[i]), kInputInstances[i]);
  }
  EXPECT_EQ(PairedInput(70), 0);
  EXPECT_EQ(kConfigurationInstance, 1);
  EXPECT_EQ(kListenOnlyHeartbeat, 198);
  EXPECT_EQ(kInputOnlyHeartbeat, 199);
}

TEST(CipDriveAssemblyTest, WrongSizeOrDirectionIsRefusedAndTouchesNothing) {
  DriveCommand command;
  command.instance = 77;
  EXPECT_FALSE(DecodeOutput(21, Hex("61 00 08"), command));
  EXPECT_FALSE(DecodeOutput(100, Hex("00 C4 70 17 00"), command));
  EXPECT_FALSE(DecodeOutput(71, Hex("00 00 00 00"), command));  // an input
  EXPECT_EQ(command.instance, 77);
  Bytes out(5, 0xEE);
  EXPECT_FALSE(EncodeInput(150, DriveFeedback{}, out));
  EXPECT_FALSE(EncodeInput(20, DriveFeedback{}, std::span<std::uint8_t>(out).first(4)));  // an output
  EXPECT_EQ(out, Bytes(5, 0xEE));
}

// ---- Instance 20 / 70 (§5.1.1, §5.1.2) ----

TEST(CipDriveAssemblyTest, Instance20_70_Stop) {
  Card card;
  const CommandWrites writes = card.Consume(20, Hex("00 00 00 00"), kFd01Stopped);
  EXPECT_EQ(writes.fa06, 0x0000);
  EXPECT_EQ(writes.fa07, 0);
  EXPECT_EQ(Encode(70, card.Feedback(kFd01Stopped, 0, 0)), Hex("00 00 00 00"));
}

TEST(CipDriveAssemblyTest, Instance20_70_ForwardRunning1800Rpm) {
  Card card;
  const DriveCommand command = Decode(20, Hex("01 00 08 07"));
  EXPECT_EQ(command.profile, CommandProfile::kCipSpeed);
  EXPECT_TRUE(command.run_forward);
  EXPECT_FALSE(command.has_net_bits);
  EXPECT_EQ(command.speed_reference_rpm, 1800);
  // 20 has no NetCtrl/NetRef: the attributes (default 0, local) apply; cmod = 4 / fmod = 7 make it run.
  CommandWrites writes = card.Consume(20, Hex("01 00 08 07"), kFd01Stopped);
  EXPECT_TRUE(writes.write_fa06);
  EXPECT_EQ(writes.fa06, 0x0400);
  EXPECT_EQ(writes.fa07, 0x1770);  // 1800 rpm, f856 = 2: 60.00 Hz
  card.context.net_ctrl_attribute = true;
  card.context.net_ref_attribute = true;
  writes = card.Consume(20, Hex("01 00 08 07"), kFd01Forward);
  EXPECT_EQ(writes.fa06, 0xC400);
  EXPECT_EQ(Encode(70, card.Feedback(kFd01Forward, 6000, 6000)), Hex("04 00 08 07"));
}

TEST(CipDriveAssemblyTest, Instance20_FaultResetWorksOnlyOnceOn0To1) {
  Card card;
  EXPECT_EQ(card.Consume(20, Hex("04 00 00 00"), kFd01Tripped).fa06, 0x2000);
  EXPECT_EQ(card.Consume(20, Hex("04 00 00 00"), kFd01Tripped).fa06, 0x0000);  // held: no second reset
  EXPECT_EQ(card.Consume(20, Hex("00 00 00 00"), kFd01Tripped).fa06, 0x0000);
  EXPECT_EQ(card.Consume(20, Hex("04 00 00 00"), kFd01Tripped).fa06, 0x2000);  // a new edge
  // Not tripped: the edge is not sent (a reset re-initialises the inverter, 1 s of silence).
  EXPECT_EQ(card.Consume(20, Hex("00 00 00 00"), kFd01Stopped).fa06, 0x0000);
  EXPECT_EQ(card.Consume(20, Hex("04 00 00 00"), kFd01Stopped).fa06, 0x0000);
  EXPECT_EQ(Encode(70, card.Feedback(kFd01Tripped, 0, 0)), Hex("01 00 00 00"));
}

TEST(CipDriveAssemblyTest, Instance20_EveryBit) {
  DriveCommand command = Decode(20, Hex("FF FF 00 00"));
  EXPECT_TRUE(command.run_forward);
  EXPECT_TRUE(command.fault_reset);
  EXPECT_FALSE(command.run_reverse);  // "-" in 20
  EXPECT_FALSE(command.has_net_bits);
  command = Decode(20, Hex("FA FF 00 00"));  // everything but bits 0 and 2
  EXPECT_FALSE(command.run_forward);
  EXPECT_FALSE(command.fault_reset);
  EXPECT_EQ(Decode(20, Hex("00 00 FF 7F")).speed_reference_rpm, 32767);
  EXPECT_EQ(Decode(20, Hex("00 00 00 80")).speed_reference_rpm, -32768);
}

TEST(CipDriveAssemblyTest, Instance70_EveryBit) {
  DriveFeedback feedback;
  feedback.faulted = true;
  EXPECT_EQ(Encode(70, feedback), Hex("01 00 00 00"));
  feedback = DriveFeedback{};
  feedback.running_forward = true;
  EXPECT_EQ(Encode(70, feedback), Hex("04 00 00 00"));
  // Everything 71 has beyond 70 stays 0 in 70, the state byte too.
  feedback = DriveFeedback{};
  feedback.warning = feedback.running_reverse = feedback.ready = feedback.ctrl_from_net = true;
  feedback.ref_from_net = feedback.at_reference = true;
  feedback.state = SupervisorState::kEnabled;
  feedback.speed_actual_rpm = 0x1234;
  EXPECT_EQ(Encode(70, feedback), Hex("00 00 34 12"));
}

// ---- Instance 21 / 71 (§5.1.3, §5.1.4) ----

TEST(CipDriveAssemblyTest, Instance21_71_Stop) {
  Card card;
  const CommandWrites writes = card.Consume(21, Hex("00 00 00 00"), kFd01Stopped);
  EXPECT_EQ(writes.fa06, 0x0000);
  EXPECT_EQ(Encode(71, card.Feedback(kFd01Stopped, 0, 0)), Hex("10 03 00 00"));  // 0x0310: Ready, state 3
}

TEST(CipDriveAssemblyTest, Instance21_71_ForwardRunning1800Rpm) {
  Card card;
  const DriveCommand command = Decode(21, Hex("61 00 08 07"));  // 0x0061: NetRef, NetCtrl, Run Fwd
  EXPECT_TRUE(command.run_forward);
  EXPECT_FALSE(command.run_reverse);
  EXPECT_TRUE(command.has_net_bits && command.net_ctrl && command.net_ref);
  const CommandWrites writes = card.Consume(21, Hex("61 00 08 07"), kFd01Stopped);
  EXPECT_EQ(writes.fa06, 0xC400);  // the same FA06/FA07 as 100's "Forward running 60Hz"
  EXPECT_EQ(writes.fa07, 0x1770);
  EXPECT_TRUE(card.context.net_ctrl_attribute);
  EXPECT_TRUE(card.context.net_ref_attribute);
  // 0x04F4: At Reference, Ref From Net, Ctrl From Net, Ready, Running1; state 4 Enabled.
  EXPECT_EQ(Encode(71, card.Feedback(kFd01Forward, 6000, 6000)), Hex("F4 04 08 07"));
}

TEST(CipDriveAssemblyTest, Instance21_ReverseAndFaultReset) {
  Card card;
  EXPECT_EQ(card.Consume(21, Hex("62 00 08 07"), kFd01Stopped).fa06, 0xC600);  // Run Rev: bits 10 + 9
  EXPECT_EQ(Encode(71, card.Feedback(kFd01Reverse, 6000, 6000)), Hex("F8 04 08 07"));
  EXPECT_EQ(card.Consume(21, Hex("04 00 00 00"), kFd01Tripped).fa06, 0x2000);
  EXPECT_EQ(card.Consume(21, Hex("04 00 00 00"), kFd01Tripped).fa06, 0x0000);
}

TEST(CipDriveAssemblyTest, Instance21_EveryBit) {
  struct Case {
    const char* data;
    bool fwd, rev, reset, ctrl, ref;
  };
  const Case cases[] = {
      {"01 00 00 00", true, false, false, false, false}, {"02 00 00 00", false, true, false, false, false},
      {"04 00 00 00", false, false, true, false, false}, {"20 00 00 00", false, false, false, true, false},
      {"40 00 00 00", false, false, false, false, true}, {"98 FF 00 00", false, false, false, false, false},
  };
  for (const Case& c : cases) {
    const DriveCommand command = Decode(21, Hex(c.data));
    EXPECT_EQ(command.run_forward, c.fwd) << c.data;
    EXPECT_EQ(command.run_reverse, c.rev) << c.data;
    EXPECT_EQ(command.fault_reset, c.reset) << c.data;
    EXPECT_EQ(command.net_ctrl, c.ctrl) << c.data;
    EXPECT_EQ(command.net_ref, c.ref) << c.data;
    EXPECT_TRUE(command.has_net_bits);
  }
}

TEST(CipDriveAssemblyTest, Instance71_EveryBitAndEveryState) {
  bool DriveFeedback::*flags[] = {&DriveFeedback::faulted,       &DriveFeedback::warning,
                                  &DriveFeedback::running_forward, &DriveFeedback::running_reverse,
                                  &DriveFeedback::ready,         &DriveFeedback::ctrl_from_net,
                                  &DriveFeedback::ref_from_net,  &DriveFeedback::at_reference};
  for (unsigned bit = 0; bit < 8; ++bit) {
    DriveFeedback feedback;
    feedback.state = SupervisorState::kNonExistent;
    feedback.*flags[bit] = true;
    EXPECT_EQ(Encode(71, feedback), Bytes({static_cast<std::uint8_t>(1u << bit), 0, 0, 0})) << bit;
  }
  for (std::uint8_t state = 0; state <= 7; ++state) {
    DriveFeedback feedback;
    feedback.state = static_cast<SupervisorState>(state);
    feedback.speed_actual_rpm = 0x0708;
    EXPECT_EQ(Encode(71, feedback), Bytes({0, state, 0x08, 0x07}));
  }
}

// ---- Instance 100 / 150 (§5.1.5, §5.1.6) ----

TEST(CipDriveAssemblyTest, Instance100_150_Stop) {
  Card card;
  const CommandWrites writes = card.Consume(100, Hex("00 00 00 00"), kFd01Stopped);
  EXPECT_TRUE(writes.write_fa06 && writes.write_fa07);
  EXPECT_EQ(writes.fa06, 0x0000);
  EXPECT_EQ(Encode(150, card.Feedback(kFd01Stopped, 0, 0), 4), Hex("00 48 00 00"));
}

TEST(CipDriveAssemblyTest, Instance100_150_ForwardRunning60Hz) {
  Card card;
  const DriveCommand command = Decode(100, Hex("00 C4 70 17"));
  EXPECT_EQ(command.profile, CommandProfile::kNative);
  EXPECT_TRUE(command.net_ctrl && command.net_ref);
  EXPECT_EQ(command.scanner_count, 0);
  const CommandWrites writes = card.Consume(100, Hex("00 C4 70 17"), kFd01Stopped);
  EXPECT_EQ(writes.fa06, 0xC400);
  EXPECT_EQ(writes.fa07, 0x1770);
  EXPECT_EQ(writes.scanner_mask, 0);
  EXPECT_EQ(Encode(150, card.Feedback(kFd01Forward, 6000, 6000), 4), Hex("00 64 70 17"));
}

TEST(CipDriveAssemblyTest, Instance100_150_ReverseRunning60Hz) {
  Card card;
  const CommandWrites writes = card.Consume(100, Hex("00 C6 70 17"), kFd01Stopped);
  EXPECT_EQ(writes.fa06, 0xC600);
  EXPECT_EQ(writes.fa07, 0x1770);
  EXPECT_EQ(Encode(150, card.Feedback(kFd01Reverse, 6000, 6000), 4), Hex("00 66 70 17"));
}

TEST(CipDriveAssemblyTest, Instance100_150_PresetSpeed1WithForwardRunning) {
  Card card;
  const CommandWrites writes = card.Consume(100, Hex("01 84 00 00"), kFd01Stopped);
  EXPECT_EQ(writes.fa06, 0x8401);  // command priority, run, preset speed 1 (sr1)
  EXPECT_EQ(Encode(150, card.Feedback(kFd01Forward, 500, 500), 4), Hex("00 64 F4 01"));  // sr1 = 5 Hz
}

TEST(CipDriveAssemblyTest, Instance100_FaultResetWorksOnlyOnceOn0To1) {
  Card card;
  EXPECT_EQ(card.Consume(100, Hex("00 20 00 00"), kFd01Tripped).fa06, 0x2000);
  EXPECT_EQ(card.Consume(100, Hex("00 20 00 00"), kFd01Tripped).fa06, 0x0000);
  EXPECT_EQ(card.Consume(100, Hex("00 A0 00 00"), kFd01Tripped).fa06, 0x8000);  // other bits pass
  EXPECT_EQ(card.Consume(100, Hex("00 00 00 00"), kFd01Tripped).fa06, 0x0000);
  EXPECT_EQ(card.Consume(100, Hex("00 20 00 00"), kFd01Tripped).fa06, 0x2000);
}

TEST(CipDriveAssemblyTest, Instance100_EveryBitIsFa06) {
  for (unsigned bit = 0; bit < 16; ++bit) {
    if (bit == 13) continue;  // the one-shot, above
    Card card;
    const std::uint16_t word = static_cast<std::uint16_t>(1u << bit);
    const Bytes data = {static_cast<std::uint8_t>(word), static_cast<std::uint8_t>(word >> 8), 0x34, 0x12};
    const CommandWrites writes = card.Consume(100, data, kFd01Stopped);
    EXPECT_EQ(writes.fa06, word) << bit;
    EXPECT_EQ(writes.fa07, 0x1234) << bit;
  }
}

TEST(CipDriveAssemblyTest, Instance150_EveryBitIsFd01ButThe2SectionLeavesOut) {
  for (unsigned bit = 0; bit < 16; ++bit) {
    DriveFeedback feedback;
    feedback.status_word = static_cast<std::uint16_t>(1u << bit);
    const bool passes = bit != 3 && bit != 15;  // "-" in §5.1.6: undervoltage, reserved
    const std::uint16_t word = passes ? feedback.status_word : 0;
    EXPECT_EQ(Encode(150, feedback, 4), Bytes({static_cast<std::uint8_t>(word), static_cast<std::uint8_t>(word >> 8), 0, 0}))
        << bit;
  }
  DriveFeedback feedback;
  feedback.status_word = 0xE404;  // E6581913's real trace, running at 60 Hz
  feedback.output_frequency = 6000;
  EXPECT_EQ(Encode(150, feedback, 4), Hex("04 64 70 17"));
}

TEST(CipDriveAssemblyTest, Instance100_150_SizeChosenByTheConnection) {
  // 8 words: FA06, FA07, c001-c006. With the factory c001 = 1 (FA06) and c002 = 3 (FA07), scanner words
  // 1-2 would write FA06/FA07 a second time: words 1-2 own those registers, the scanner words are dropped.
  Card card;
  const Bytes eight = Hex("00 C4 70 17 11 11 22 22 33 33 44 44 55 55 66 66");
  const DriveCommand command = Decode(100, eight);
  EXPECT_EQ(command.scanner_count, 6);
  EXPECT_EQ(command.scanner_words, (drive_link::ScannerWords{0x1111, 0x2222, 0x3333, 0x4444, 0x5555, 0x6666}));
  CommandWrites writes = card.Consume(100, eight, kFd01Stopped);
  EXPECT_EQ(writes.scanner_mask, 0b111100);
  EXPECT_EQ(writes.scanner_words[2], 0x3333);
  card.context.command_menus = {13, 14, 0, 0, 5, 3};  // acc, dec, -, -, FA50, FA07
  writes = card.Consume(100, eight, kFd01Stopped);
  EXPECT_EQ(writes.scanner_mask, 0b011111);
  // 5 words: 3 scanner words carried, the rest not written.
  card.context.command_menus = {13, 14, 16, 0, 0, 0};
  writes = card.Consume(100, Hex("00 C4 70 17 11 11 22 22 33 33"), kFd01Stopped);
  EXPECT_EQ(writes.scanner_mask, 0b000111);
  // 150 at 3 and 8 words.
  DriveFeedback feedback;
  feedback.status_word = kFd01Forward;
  feedback.output_frequency = 6000;
  feedback.monitor_words = {0x6400, 0x1770, 0x1388, 4, 5, 6};
  EXPECT_EQ(Encode(150, feedback, 6), Hex("00 64 70 17 00 64"));
  EXPECT_EQ(Encode(150, feedback, 16), Hex("00 64 70 17 00 64 70 17 88 13 04 00 05 00 06 00"));
}

// ---- Instance 101 / 151 (§5.1.7, §5.1.8) ----

struct ChannelRun {
  ParameterChannel channel;
  Bytes Exchange(std::uint32_t out_instance, const Bytes& data, const AccessResult& result, std::uint32_t in_instance) {
    channel.Offer(Decode(out_instance, data).parameter);
    ParameterRequest request;
    if (channel.TakeDue(request)) channel.Complete(result);
    DriveFeedback feedback;
    feedback.state = SupervisorState::kReady;
    feedback.ready = true;
    feedback.parameter = channel.response();
    return Encode(in_instance, feedback);
  }
};

AccessResult Ok(std::uint16_t number, std::uint16_t value) { return AccessResult{AccessError::kNone, number, value}; }
AccessResult Failed(std::uint16_t number, AccessError error) { return AccessResult{error, number, 0}; }

TEST(CipDriveAssemblyTest, Instance101_151_ReadCmod) {
  const DriveCommand command = Decode(101, Hex("00 00 00 00 03 00 00 00"));
  EXPECT_TRUE(command.parameter.present && command.parameter.valid);
  EXPECT_FALSE(command.parameter.write);
  EXPECT_EQ(command.parameter.number, 0x0003);
  ChannelRun run;
  EXPECT_EQ(run.Exchange(101, Hex("00 00 00 00 03 00 00 00"), Ok(3, 0), 151), Hex("10 03 00 00 03 00 00 00"));
}

TEST(CipDriveAssemblyTest, Instance101_151_ReadF268Is60Hz) {
  ChannelRun run;
  EXPECT_EQ(run.Exchange(101, Hex("00 00 00 00 68 02 00 00"), Ok(0x0268, 0x1770), 151), Hex("10 03 00 00 68 02 70 17"));
}

TEST(CipDriveAssemblyTest, Instance101_151_WriteSr1_60Hz_OkAndNg) {
  const DriveCommand command = Decode(101, Hex("00 00 00 00 18 80 70 17"));
  EXPECT_TRUE(command.parameter.write);
  EXPECT_EQ(command.parameter.number, 0x0018);
  EXPECT_EQ(command.parameter.data, 0x1770);
  ChannelRun ok;
  EXPECT_EQ(ok.Exchange(101, Hex("00 00 00 00 18 80 70 17"), Ok(0x18, 0x1770), 151), Hex("10 03 00 00 18 80 70 17"));
  ChannelRun ng;
  EXPECT_EQ(ng.Exchange(101, Hex("00 00 00 00 18 80 70 17"), Failed(0x18, AccessError::kOutOfRange), 151),
            Hex("10 03 00 00 18 C0 00 11"));  // 0xC018 / 0x1100 data out of range
  ChannelRun bad;
  EXPECT_EQ(bad.Exchange(101, Hex("00 00 00 00 99 00 00 00"), Failed(0x99, AccessError::kNoSuchRegister), 151),
            Hex("10 03 00 00 99 40 01 11"));  // 0x4099 / 0x1101 bad address
}

TEST(CipDriveAssemblyTest, Instance101_SpeedPartIsInstance21AndIndexHas14Bits) {
  const DriveCommand command = Decode(101, Hex("63 FF 08 07 FF 7F 34 12"));
  EXPECT_EQ(command.profile, CommandProfile::kCipSpeed);
  EXPECT_TRUE(command.run_forward && command.run_reverse && command.net_ctrl && command.net_ref);
  EXPECT_FALSE(command.fault_reset);
  EXPECT_EQ(command.speed_reference_rpm, 1800);
  EXPECT_FALSE(command.parameter.write);
  EXPECT_EQ(command.parameter.number, 0x3FFF);  // bit 14 is the response's error flag, not the number
  EXPECT_EQ(command.parameter.data, 0x1234);
  DriveFeedback feedback;
  feedback.parameter = ParameterResponse{true, true, false, AccessError::kNone, 0x0018, 0x1770};
  feedback.state = SupervisorState::kEnabled;
  feedback.running_forward = feedback.ready = feedback.ctrl_from_net = feedback.ref_from_net = true;
  feedback.at_reference = true;
  feedback.speed_actual_rpm = 1800;
  EXPECT_EQ(Encode(151, feedback), Hex("F4 04 08 07 18 80 70 17"));
  EXPECT_EQ(Encode(151, DriveFeedback{}), Hex("00 01 00 00 00 00 00 00"));  // no response yet: zeros
}

TEST(CipDriveAssemblyTest, Error151ForEveryAccessError) {
  EXPECT_EQ(Error151(AccessError::kNoSuchRegister), 0x1101);
  EXPECT_EQ(Error151(AccessError::kReadOnly), 0x1101);
  EXPECT_EQ(Error151(AccessError::kReservedForScanner), 0x1101);
  for (AccessError error : {AccessError::kOutOfRange, AccessError::kNotWritableWhileRunning, AccessError::kRefused,
                            AccessError::kLinkDown, AccessError::kTimeout}) {
    EXPECT_EQ(Error151(error), 0x1100) << drive_link::AccessErrorName(error);
  }
}

// ---- Instance 102 / 152 (§5.1.9, §5.1.10, §3.2.4.1) ----

TEST(CipDriveAssemblyTest, Instance102_CommandC400ToFa06ThroughC001) {
  Card card;
  const CommandWrites writes = card.Consume(102, Hex("00 C4 02 00 03 00 04 00 05 00 06 00"), kFd01Stopped);
  EXPECT_FALSE(writes.write_fa06);  // FA06 is reached as scanner word 1 (c001 = 1)
  EXPECT_FALSE(writes.write_fa07);
  EXPECT_EQ(writes.scanner_mask, 0b111111);
  EXPECT_EQ(writes.scanner_words, (drive_link::ScannerWords{0xC400, 2, 3, 4, 5, 6}));
}

TEST(CipDriveAssemblyTest, Instance152_OutputCurrent0x1234ThroughC021) {
  DriveFeedback feedback;
  feedback.monitor_words = {0x1234, 0x0102, 0, 0, 0, 0xFFFF};
  EXPECT_EQ(Encode(152, feedback), Hex("34 12 02 01 00 00 00 00 00 00 FF FF"));
}

// ---- Instance 105 / 155 (§5.1.11, §5.1.12) ----

TEST(CipDriveAssemblyTest, Instance105_155_ReadCmod) {
  const Bytes out = Hex("00 00 03 00 00 00 | 01 00 02 00 03 00 04 00 05 00 06 00");
  const DriveCommand command = Decode(105, out);
  EXPECT_EQ(command.profile, CommandProfile::kScanner);
  EXPECT_TRUE(command.parameter.present && command.parameter.valid);
  EXPECT_FALSE(command.parameter.write);
  EXPECT_EQ(command.parameter.number, 3);
  EXPECT_EQ(command.scanner_count, 6);
  EXPECT_EQ(command.scanner_words, (drive_link::ScannerWords{1, 2, 3, 4, 5, 6}));
  ChannelRun run;
  EXPECT_EQ(run.Exchange(105, out, Ok(3, 0), 155), Hex("00 00 03 00 00 00 | 00 00 00 00 00 00 00 00 00 00 00 00"));
}

TEST(CipDriveAssemblyTest, Instance105_155_ReadF268Is60Hz) {
  ChannelRun run;
  EXPECT_EQ(run.Exchange(105, Hex("00 00 68 02 00 00 | 00 00 00 00 00 00 00 00 00 00 00 00"), Ok(0x268, 0x1770), 155),
            Hex("00 00 68 02 70 17 | 00 00 00 00 00 00 00 00 00 00 00 00"));
}

TEST(CipDriveAssemblyTest, Instance105_155_WriteSr1_60Hz_OkAndNg) {
  const Bytes out = Hex("00 80 18 00 70 17 | 00 00 00 00 00 00 00 00 00 00 00 00");
  const DriveCommand command = Decode(105, out);
  EXPECT_TRUE(command.parameter.write);
  EXPECT_EQ(command.parameter.function, 0x80);
  EXPECT_EQ(command.parameter.data, 0x1770);
  ChannelRun ok;
  // Done: function result 0x00 (not 0x80: §5.1.12's example), index and data echoed.
  EXPECT_EQ(ok.Exchange(105, out, Ok(0x18, 0x1770), 155), Hex("00 00 18 00 70 17 | 00 00 00 00 00 00 00 00 00 00 00 00"));
  ChannelRun ng;
  EXPECT_EQ(ng.Exchange(105, out, Failed(0x18, AccessError::kOutOfRange), 155),
            Hex("00 40 18 00 01 00 | 00 00 00 00 00 00 00 00 00 00 00 00"));
}

TEST(CipDriveAssemblyTest, Instance105_UnknownFunctionIsAnErrorWithoutAccess) {
  ChannelRun run;
  run.channel.Offer(Decode(105, Hex("FF 81 09 00 32 00 | 00 00 00 00 00 00 00 00 00 00 00 00")).parameter);
  ParameterRequest request;
  EXPECT_FALSE(run.channel.TakeDue(request));
  DriveFeedback feedback;
  feedback.parameter = run.channel.response();
  feedback.monitor_words = {0x6400, 0x1770, 0, 0, 0, 0};
  EXPECT_EQ(Encode(155, feedback), Hex("00 40 09 00 01 00 | 00 64 70 17 00 00 00 00 00 00 00 00"));
  // Bytes 0 of 105 (blank) is ignored; full 16-bit index (monitors and c-parameters are reachable).
  const DriveCommand command = Decode(105, Hex("5A 00 00 FD 00 00 | 00 00 00 00 00 00 00 00 00 00 00 00"));
  EXPECT_TRUE(command.parameter.valid);
  EXPECT_EQ(command.parameter.number, 0xFD00);
}

// ---- Parameter channel ----

TEST(CipDriveParameterChannelTest, OneAccessPerDistinctRequest) {
  ParameterChannel channel;
  ParameterRequest request;
  EXPECT_FALSE(channel.TakeDue(request));
  const ParameterRequest write{true, true, true, 0x0018, 0x1770, 0x80};
  channel.Offer(write);
  channel.Offer(write);
  ASSERT_TRUE(channel.TakeDue(request));
  EXPECT_EQ(request, write);
  EXPECT_TRUE(channel.busy());
  EXPECT_FALSE(channel.TakeDue(request));
  channel.Offer(write);  // every RPI: the same request
  channel.Complete(Ok(0x18, 0x1770));
  EXPECT_EQ(channel.response(), (ParameterResponse{true, true, false, AccessError::kNone, 0x18, 0x1770}));
  channel.Offer(write);
  EXPECT_FALSE(channel.TakeDue(request));  // written once, never again while unchanged
  ParameterRequest other = write;
  other.data = 0x0BB8;  // new data: a new request
  channel.Offer(other);
  ASSERT_TRUE(channel.TakeDue(request));
  EXPECT_EQ(request.data, 0x0BB8);
  EXPECT_EQ(channel.response().value, 0x1770);  // the old answer until the new one completes
}

TEST(CipDriveParameterChannelTest, NewerRequestSupersedesTheOneOnTheWay) {
  ParameterChannel channel;
  ParameterRequest request;
  channel.Offer(ParameterRequest{true, true, false, 0x0003, 0, 0});
  ASSERT_TRUE(channel.TakeDue(request));
  channel.Offer(ParameterRequest{true, true, false, 0x0268, 0, 0});
  channel.Complete(Ok(3, 1));
  EXPECT_FALSE(channel.response().present);  // cmod's answer is no longer wanted
  ASSERT_TRUE(channel.TakeDue(request));
  EXPECT_EQ(request.number, 0x0268);
  channel.Complete(Ok(0x268, 0x1770));
  EXPECT_EQ(channel.response().number, 0x0268);
  // An invalid newer request answered at once is not overwritten by the older echo.
  channel.Offer(ParameterRequest{true, true, false, 0x0009, 0, 0});
  ASSERT_TRUE(channel.TakeDue(request));
  channel.Offer(ParameterRequest{true, false, false, 0x0010, 0, 0x40});
  channel.Complete(Ok(9, 50));
  EXPECT_TRUE(channel.response().error);
  EXPECT_EQ(channel.response().number, 0x0010);
}

TEST(CipDriveParameterChannelTest, RetryResetAndAbsentChannel) {
  ParameterChannel channel;
  ParameterRequest request;
  channel.Offer(ParameterRequest{});  // 20/21/100/102: no channel
  EXPECT_FALSE(channel.TakeDue(request));
  channel.Offer(ParameterRequest{true, true, false, 0x0003, 0, 0});
  ASSERT_TRUE(channel.TakeDue(request));
  channel.Retry();  // the access could not start (pool full)
  ASSERT_TRUE(channel.TakeDue(request));
  EXPECT_EQ(request.number, 3);
  channel.Complete(Failed(3, AccessError::kTimeout));
  EXPECT_TRUE(channel.response().error);
  EXPECT_EQ(channel.response().cause, AccessError::kTimeout);
  channel.Reset();
  EXPECT_FALSE(channel.response().present);
  channel.Offer(ParameterRequest{true, true, false, 0x0003, 0, 0});  // after a reset: new again
  EXPECT_TRUE(channel.TakeDue(request));
}

}  // namespace
}  // namespace cip::drive
