// The drive profile between the assemblies and the inverter's registers (seed 000 §4.6, §4.7, §5;
// docs/drive-profile.md). Neutral structs and pure functions, no I/O:
//
//   output assembly --DecodeOutput--> DriveCommand --OutputEdgeTracker--> OutputEvents
//        DriveCommand + events + ControlSupervisor --> DriveContext --CommandRegisters--> FA06/FA07/scanner
//   FD01/FD00/FE02 + supervisor state --MakeFeedback--> DriveFeedback --EncodeInput--> input assembly
//
// FA06 bits the card sets for the CIP speed-control assemblies (20, 21, 101), drive_registers.h
// command_bit:
//   Run1 (Run Fwd)  -> bit 10 run                     0x0400
//   Run2 (Run Rev)  -> bit 10 run + bit 9 reverse      0x0600
//   FaultRst 0->1   -> bit 13 fault reset, one write   0x2000
//   NetCtrl = 1     -> bit 15 command priority         0x8000 (run/stop from the card whatever cmod)
//   NetRef = 1      -> bit 14 frequency priority       0x4000 (FA07 in force whatever fmod)
// With NetCtrl/NetRef = 0 the run bits and FA07 are still written: they are in force when cmod = 4 /
// fmod = 7 (communication option), and ignored otherwise (§5.1.3 "according to cmod/fmod").
// Instance 100's word 0 IS FA06 bit for bit (byte 1 bit 7 NetCtrl = bit 15, bit 6 NetRef = bit 14 ...),
// word 1 IS FA07; only its fault-reset bit is turned into a one-shot.
#pragma once

#include <array>
#include <cstdint>
#include <span>

#include "cip/drive/control_supervisor.h"
#include "cip/drive/parameter_channel.h"
#include "drive_link/register_access.h"

namespace cip::drive {

enum class CommandProfile : std::uint8_t {
  kNone,      // nothing decoded
  kCipSpeed,  // 20, 21, 101: Run Fwd/Run Rev, FaultRst, NetCtrl/NetRef (21, 101), speed in rpm
  kNative,    // 100: FA06 and FA07 as words, then up to 6 scanner words
  kScanner,   // 102, 105: scanner words only (105: and the parameter channel)
};

// A decoded output assembly: levels as the master sent them.
struct DriveCommand {
  CommandProfile profile = CommandProfile::kNone;
  std::uint16_t instance = 0;
  // kCipSpeed
  bool run_forward = false;    // Run1
  bool run_reverse = false;    // Run2 (21, 101)
  bool fault_reset = false;    // level (kNative: FA06 bit 13)
  bool has_net_bits = false;   // 21, 100, 101 carry NetCtrl/NetRef; 20 does not (attributes apply)
  bool net_ctrl = false;       // kNative: FA06 bit 15
  bool net_ref = false;        // kNative: FA06 bit 14
  std::int16_t speed_reference_rpm = 0;  // INT as received
  // kNative
  std::uint16_t native_command = 0;    // word 0: FA06
  std::uint16_t native_frequency = 0;  // word 1: FA07, 0.01 Hz
  // Scanner words c001-c006: 100 words 3-8, 102 words 1-6, 105 words 4-9. Only the first
  // scanner_count words were in the assembly (100 at less than 8 words).
  std::uint8_t scanner_count = 0;
  drive_link::ScannerWords scanner_words{};
  // 101, 105
  ParameterRequest parameter;
};

// One-shot events of a connection's output levels. The first packet after Reset() is compared with
// all-zero levels, so a bit already set in it is an edge (the attributes' default is 0).
struct OutputEvents {
  bool fault_reset = false;  // FaultRst / FA06 bit 13 went 0 -> 1
};

class OutputEdgeTracker {
 public:
  OutputEvents Track(const DriveCommand& command);
  void Reset() { fault_reset_ = false; }

 private:
  bool fault_reset_ = false;
};

// What CommandRegisters needs besides the command itself.
struct DriveContext {
  std::uint16_t pole_pairs = 2;  // f856
  // Control Supervisor attribute 5 NetCtrl and AC/DC Drive attribute 4 NetRef: used by 20, which has no
  // such bits. After 21/100/101 the caller stores the assembly's bits into them (ApplyNetBits).
  bool net_ctrl_attribute = false;
  bool net_ref_attribute = false;
  RunType run = RunType::kStop;  // the supervisor's run type (kCipSpeed)
  bool fault_reset = false;      // kCipSpeed: SupervisorOutputs::send_fault_reset; kNative: the edge
  // c001-c006: a scanner word of 100 whose menu targets FA06 or FA07 is not written (words 1-2 own them).
  std::array<std::uint16_t, drive_link::kScannerWordCount> command_menus{1, 3, 0, 0, 0, 0};
};

// The registers one command writes. Scanner word i+1 is written when bit i of scanner_mask is set
// (to the register its c00(i+1) menu selects; menu 0: not exchanged).
struct CommandWrites {
  bool write_fa06 = false;
  std::uint16_t fa06 = 0;
  bool write_fa07 = false;
  std::uint16_t fa07 = 0;
  std::uint8_t scanner_mask = 0;
  drive_link::ScannerWords scanner_words{};
};

CommandWrites CommandRegisters(const DriveCommand& command, const DriveContext& context);

// 21/100/101: the assembly's NetCtrl/NetRef become the objects' attributes (what attribute 5 of 0x29 and
// attribute 4 of 0x2A read). 20, 102, 105 leave them.
void ApplyNetBits(const DriveCommand& command, bool& net_ctrl_attribute, bool& net_ref_attribute);

// Whether run/stop and the frequency reference come from the card: the priority bits of the FA06 last
// written, or cmod = 4 / fmod = 7 (communication option). A panel LOC key or an SC/LC terminal (§11)
// is invisible to the card and not reflected.
struct ControlSources {
  bool ctrl_from_net = false;  // 71/151 byte 0 bit 5; attribute 15 of 0x29
  bool ref_from_net = false;   // 71/151 byte 0 bit 6; attribute 29 of 0x2A
};
ControlSources ControlSourcesOf(std::uint16_t fa06_written, std::uint16_t cmod, std::uint16_t fmod);

// The monitors the input assemblies are made of, as read from the inverter.
struct DriveMonitors {
  std::uint16_t fd01 = 0;  // status word 1
  std::uint16_t fd00 = 0;  // output frequency, 0.01 Hz
  std::uint16_t fe02 = 0;  // frequency command in force, 0.01 Hz (for "at reference")
};

// The registers to read for the feedback of each input instance (besides the scanner monitor words of
// 150/152/155, which come from the cyclic exchange). FD01 is read by the cyclic exchange in any case.
inline constexpr std::array<std::uint16_t, 3> kFeedbackRegisters{0xFD01, 0xFD00, 0xFE02};
std::span<const std::uint16_t> FeedbackRegisters(std::uint32_t input_instance);

// The neutral content of every input assembly.
struct DriveFeedback {
  SupervisorState state = SupervisorState::kStartup;
  bool faulted = false;          // FaultStop / Faulted
  bool warning = false;          // FD01 bit 2 (alarm)
  bool running_forward = false;  // FD01 bit 10 and not bit 9 (Running1)
  bool running_reverse = false;  // FD01 bits 10 + 9 (Running2)
  bool ready = false;            // Ready / Enabled / Stopping
  bool ctrl_from_net = false;
  bool ref_from_net = false;
  bool at_reference = false;     // Enabled and |FD00 - FE02| <= tolerance
  std::uint16_t speed_actual_rpm = 0;  // FD00 in rpm (magnitude; the direction is Running1/Running2)
  std::uint16_t status_word = 0;       // FD01 as read (150)
  std::uint16_t output_frequency = 0;  // FD00 (150)
  drive_link::ScannerWords monitor_words{};  // c021-c026 (150 words 3-8, 152, 155)
  ParameterResponse parameter;               // 151, 155
};

struct FeedbackOptions {
  std::uint16_t pole_pairs = 2;              // f856
  std::uint16_t at_reference_tolerance = 0;  // 0.01 Hz; 0 = "the same as the frequency command" (§5.1.4)
};

// The status part of DriveFeedback (monitor_words and parameter are the caller's).
DriveFeedback MakeFeedback(const DriveMonitors& monitors, SupervisorState state, const ControlSources& sources,
                           const FeedbackOptions& options);

}  // namespace cip::drive
