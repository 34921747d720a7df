// Commands to registers and registers to feedback (drive_profile.h, docs/drive-profile.md).
#include "cip/drive/drive_profile.h"

#include "cip/drive/drive_units.h"
#include "config/card_config.h"
#include "drive_link/drive_registers.h"
#include "drive_link/register_access.h"

namespace cip::drive {

namespace reg = drive_link::reg;
namespace command_bit = drive_link::reg::command_bit;
namespace status_bit = drive_link::reg::status_bit;

namespace {

constexpr std::uint16_t kCmodOption = 4;  // cmod: communication option (§3.1)
constexpr std::uint16_t kFmodOption = 7;  // fmod: communication option (§3.1)

constexpr std::uint8_t AllWords(std::uint8_t count) { return static_cast<std::uint8_t>((1u << count) - 1u); }

}  // namespace

OutputEvents OutputEdgeTracker::Track(const DriveCommand& command) {
  OutputEvents events;
  if (command.profile == CommandProfile::kCipSpeed || command.profile == CommandProfile::kNative) {
    events.fault_reset = command.fault_reset && !fault_reset_;
    fault_reset_ = command.fault_reset;
  } else {
    fault_reset_ = false;  // 102/105 carry no fault-reset level of their own
  }
  return events;
}

CommandWrites CommandRegisters(const DriveCommand& command, const DriveContext& context) {
  CommandWrites out;
  switch (command.profile) {
    case CommandProfile::kNone:
      break;
    case CommandProfile::kCipSpeed: {
      const bool net_ctrl = command.has_net_bits ? command.net_ctrl : context.net_ctrl_attribute;
      const bool net_ref = command.has_net_bits ? command.net_ref : context.net_ref_attribute;
      std::uint16_t fa06 = 0;
      if (context.run == RunType::kRun1) fa06 |= command_bit::kRun;
      if (context.run == RunType::kRun2) fa06 |= command_bit::kRun | command_bit::kReverse;
      if (context.fault_reset) fa06 |= command_bit::kFaultReset;
      if (net_ref) fa06 |= command_bit::kFrequencyPriority;
      if (net_ctrl) fa06 |= command_bit::kCommandPriority;
      out.write_fa06 = true;
      out.fa06 = fa06;
      out.write_fa07 = true;
      out.fa07 = RpmToFrequency(command.speed_reference_rpm, context.pole_pairs);
      break;
    }
    case CommandProfile::kNative: {
      out.write_fa06 = true;
      out.fa06 = static_cast<std::uint16_t>(command.native_command & ~command_bit::kFaultReset);
      if (context.fault_reset) out.fa06 |= command_bit::kFaultReset;
      out.write_fa07 = true;
      out.fa07 = command.native_frequency;
      std::uint8_t mask = AllWords(command.scanner_count);
      for (std::size_t i = 0; i < drive_link::kScannerWordCount; ++i) {
        const std::uint16_t target = config::CommandMenuTarget(context.command_menus[i]);
        if (drive_link::IsDriveCommandRegister(target)) mask = static_cast<std::uint8_t>(mask & ~(1u << i));
      }
      out.scanner_mask = mask;
      out.scanner_words = command.scanner_words;
      break;
    }
    case CommandProfile::kScanner:
      out.scanner_mask = AllWords(command.scanner_count);
      out.scanner_words = command.scanner_words;
      break;
  }
  return out;
}

void ApplyNetBits(const DriveCommand& command, bool& net_ctrl_attribute, bool& net_ref_attribute) {
  if (!command.has_net_bits) return;
  net_ctrl_attribute = command.net_ctrl;
  net_ref_attribute = command.net_ref;
}

ControlSources ControlSourcesOf(std::uint16_t fa06_written, std::uint16_t cmod, std::uint16_t fmod) {
  ControlSources sources;
  sources.ctrl_from_net = (fa06_written & command_bit::kCommandPriority) != 0 || cmod == kCmodOption;
  sources.ref_from_net = (fa06_written & command_bit::kFrequencyPriority) != 0 || fmod == kFmodOption;
  return sources;
}

std::span<const std::uint16_t> FeedbackRegisters(std::uint32_t input_instance) {
  const std::span<const std::uint16_t> all(kFeedbackRegisters);
  switch (input_instance) {
    case 70:
    case 150:
      return all.first(2);  // FD01, FD00
    case 71:
    case 151:
      return all;  // FD01, FD00, FE02
    default:
      return {};  // 152, 155: the scanner monitor words only
  }
}

DriveFeedback MakeFeedback(const DriveMonitors& monitors, SupervisorState state, const ControlSources& sources,
                           const FeedbackOptions& options) {
  DriveFeedback feedback;
  const bool running = (monitors.fd01 & status_bit::kRunning) != 0;
  const bool reverse = (monitors.fd01 & kFd01Reverse) != 0;
  feedback.state = state;
  feedback.faulted = state == SupervisorState::kFaultStop || state == SupervisorState::kFaulted;
  feedback.warning = (monitors.fd01 & status_bit::kAlarm) != 0;
  feedback.running_forward = running && !reverse;
  feedback.running_reverse = running && reverse;
  feedback.ready = AcceptsRun(state);
  feedback.ctrl_from_net = sources.ctrl_from_net;
  feedback.ref_from_net = sources.ref_from_net;
  const std::uint16_t difference = monitors.fd00 > monitors.fe02 ? static_cast<std::uint16_t>(monitors.fd00 - monitors.fe02)
                                                                 : static_cast<std::uint16_t>(monitors.fe02 - monitors.fd00);
  feedback.at_reference = state == SupervisorState::kEnabled && difference <= options.at_reference_tolerance;
  feedback.speed_actual_rpm = FrequencyToRpm(monitors.fd00, options.pole_pairs);
  feedback.status_word = monitors.fd01;
  feedback.output_frequency = monitors.fd00;
  return feedback;
}

}  // namespace cip::drive
