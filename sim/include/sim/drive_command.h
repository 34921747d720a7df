// The simulated inverter's command resolution: which source runs the drive and sets its frequency, and
// what that source asks for. A pure function of the register values and the terminal/panel inputs; the
// behaviour model (inverter_model.h) feeds it and acts on the answer.
//
// Sources (docs/simulator.md, "Behaviour model"):
// - FA06 bit 15 (command priority) / bit 14 (frequency priority) put the communication option in control
//   regardless of cmod/fmod (seed 000 §3.2.4.2). FA00 bits 15/14 do the same for the RS485 path (seed 003
//   §8.0). Without them cmod/fmod decide: cmod 4 / fmod 7 = communication option, cmod 2 / fmod 4 = RS485
//   (seed 000 §3.1).
// - A terminal with input function 48 (SC/LC, "forced local from communication") that is active makes the
//   priority bits ineffective, so cmod/fmod decide (seed 000 §11); 108 (CMTB) replaces cmod by the
//   terminal board and 104 (FCHG) replaces fmod by f207 (seed 000 §11 diagram).
// - Preset speed bits of the source in command (FA06 bits 0-3, FA00 bits 0-3, terminals SS1-SS4) select
//   sr1-sr7 / f287-f294 and override the frequency source (seed 000 §5.1.6 example 4: FA06 = 0x8401 runs
//   at sr1 without frequency priority).
#pragma once

#include <array>
#include <cstdint>

#include "drive_link/drive_registers.h"

namespace sim {

enum class CommandSource : std::uint8_t { kTerminal, kPanel, kRs485, kCanOpen, kOption };
enum class FrequencySource : std::uint8_t {
  kPanel,       // fmod 0/3: the panel setting dial (SetPanelFrequency)
  kVia,         // fmod 1
  kVib,         // fmod 2
  kRs485,       // fmod 4: FA01
  kUpDown,      // fmod 5: UP/DOWN from logic inputs (modelled as its initial value f268)
  kCanOpen,     // fmod 6: no CANopen in the simulator, 0 Hz
  kOption,      // fmod 7: FA07
  kVic,         // fmod 8
  kPulseTrain,  // fmod 11: 0 Hz (no pulse input)
  kSr0,         // fmod 14 (VF-S15): preset speed 0, no communication number, 0 Hz
  kNone,        // fmod 9, 10, 12, 13 ("-"): 0 Hz
};

// Acceleration/deceleration pattern: AD1 = acc/dec, AD2 = f500/f501, AD3 = f510/f511.
enum class AccDecPattern : std::uint8_t { kAd1, kAd2, kAd3 };

// Physical input terminals in FD06 bit order, then the standby signal. VIB/VIA act as logic inputs only
// when f109 selects it.
enum class Terminal : std::uint8_t { kF, kR, kRes, kS1, kS2, kS3, kVib, kVia, kSt };
inline constexpr int kPhysicalTerminals = 8;

// Input terminal functions (f111-f118). Even = active when the terminal is on, the next odd number = the
// same function with inverted logic (active when off).
namespace input_function {
inline constexpr std::int32_t kForward = 2;
inline constexpr std::int32_t kReverse = 4;
inline constexpr std::int32_t kStandby = 6;
inline constexpr std::int32_t kReset = 8;
inline constexpr std::int32_t kPreset1 = 10;  // SS1; SS2 = 12, SS3 = 14, SS4 = 16
inline constexpr std::int32_t kForcedLocal = 48;           // SC/LC
inline constexpr std::int32_t kFrequencyChange = 104;      // FCHG: fmod -> f207
inline constexpr std::int32_t kCommandFromTerminal = 108;  // CMTB
}  // namespace input_function

// FA06 / FA00 bits (seed 000 §3.2.4.2): the card's definition, so both ends of the link agree.
namespace command_bit = drive_link::reg::command_bit;

// FA23 bits (seed 000 §3.2.4.3). Every other bit is reserved and must be written 0.
namespace command2_bit {
inline constexpr std::uint16_t kEnergyReset = 1u << 1;
inline constexpr std::uint16_t kMaxDecelerationStop = 1u << 7;
inline constexpr std::uint16_t kAccDec1 = 1u << 8;
inline constexpr std::uint16_t kAccDec2 = 1u << 9;
inline constexpr std::uint16_t kOcStall2 = 1u << 12;
inline constexpr std::uint16_t kDefined = kEnergyReset | kMaxDecelerationStop | kAccDec1 | kAccDec2 | kOcStall2;
}  // namespace command2_bit

// What the command resolution reads. Frequencies in 0.01 Hz, analog inputs in 0.01 %.
struct CommandInputs {
  std::uint16_t fa06 = 0;
  std::uint16_t fa07 = 0;
  std::uint16_t fa23 = 0;
  std::uint16_t fa00 = 0;
  std::uint16_t fa01 = 0;
  std::int32_t cmod = 1;
  std::int32_t fmod = 0;
  std::int32_t f207 = 1;
  std::int32_t f109 = 0;
  std::array<std::int32_t, kPhysicalTerminals> terminal_functions{};  // f111-f118
  std::uint8_t terminals = 0;  // physical terminal states, FD06 bit order
  bool st_input = false;       // the standby (ST) signal of the terminal board
  bool panel_run = false;
  bool panel_reverse = false;
  std::int32_t panel_frequency = 0;
  std::array<std::int32_t, 3> analog{};  // VIA, VIB, VIC (FE35-FE37)
  std::int32_t fh = 8000;
  std::int32_t f268 = 0;
  std::array<std::int32_t, 15> preset_speeds{};  // sr1-sr7, f287-f294
  bool ignore_option = false;    // communication loss with c101 = 0: FA06/FA07 ignored
};

// What the source in command asks for, before limits, trips and ramps.
struct DriveCommand {
  CommandSource command_source = CommandSource::kPanel;
  FrequencySource frequency_source = FrequencySource::kPanel;
  bool run = false;
  bool reverse = false;
  bool jog = false;
  bool standby = false;  // ST = ON: the drive may output (FD01 bit 11 is its inverse)
  bool dc_braking = false;
  bool thr2 = false;
  bool pid_off = false;
  bool max_deceleration_stop = false;
  bool energy_reset = false;
  AccDecPattern pattern = AccDecPattern::kAd1;
  int preset = 0;              // 0 none, 1-15: overrides the frequency source
  std::int32_t frequency = 0;  // 0.01 Hz, unsigned, before ll/ul: jog, else the preset, else the source
};

// True when the input function `function` (even number) is active on some terminal.
bool InputFunctionActive(const CommandInputs& in, std::int32_t function);

DriveCommand ResolveCommand(const CommandInputs& in);

const char* CommandSourceName(CommandSource source);
const char* FrequencySourceName(FrequencySource source);

// The jog frequency (the drive's f260 has no communication number in the seeds): 5.00 Hz, the JOG
// default of seed 004 §2 (c154/c155).
inline constexpr std::int32_t kJogFrequency = 500;

}  // namespace sim
