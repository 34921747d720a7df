#include "sim/drive_command.h"

#include <cstddef>

namespace sim {
namespace {

bool Bit(std::uint16_t word, std::uint16_t mask) { return (word & mask) != 0; }

bool TerminalOn(const CommandInputs& in, std::size_t index) {
  // VIB (6) and VIA (7) are logic inputs only when f109 says so (seed 000 §3.2.4.14 note *1).
  if (index >= 6 && in.f109 == 0) return false;
  return (in.terminals & (1u << index)) != 0;
}

CommandSource CommandSourceFromCmod(std::int32_t cmod) {
  switch (cmod) {
    case 0:
      return CommandSource::kTerminal;
    case 2:
      return CommandSource::kRs485;
    case 3:
      return CommandSource::kCanOpen;
    case 4:
      return CommandSource::kOption;
    default:
      return CommandSource::kPanel;
  }
}

FrequencySource FrequencySourceFromFmod(std::int32_t fmod) {
  switch (fmod) {
    case 0:
    case 3:
      return FrequencySource::kPanel;
    case 1:
      return FrequencySource::kVia;
    case 2:
      return FrequencySource::kVib;
    case 4:
      return FrequencySource::kRs485;
    case 5:
      return FrequencySource::kUpDown;
    case 6:
      return FrequencySource::kCanOpen;
    case 7:
      return FrequencySource::kOption;
    case 8:
      return FrequencySource::kVic;
    case 11:
      return FrequencySource::kPulseTrain;
    case 14:
      return FrequencySource::kSr0;
    default:
      return FrequencySource::kNone;
  }
}

// Analog input (0.01 %) to frequency: 0-100 % is 0-fh (assumed; the VIA/VIB/VIC point parameters are
// not in the table). Negative VIB gives 0 Hz.
std::int32_t AnalogFrequency(std::int32_t percent, std::int32_t fh) {
  if (percent <= 0) return 0;
  return static_cast<std::int32_t>((static_cast<std::int64_t>(percent) * fh + 5000) / 10000);
}

std::int32_t SourceFrequency(const CommandInputs& in, FrequencySource source) {
  switch (source) {
    case FrequencySource::kPanel:
      return in.panel_frequency;
    case FrequencySource::kVia:
      return AnalogFrequency(in.analog[0], in.fh);
    case FrequencySource::kVib:
      return AnalogFrequency(in.analog[1], in.fh);
    case FrequencySource::kVic:
      return AnalogFrequency(in.analog[2], in.fh);
    case FrequencySource::kRs485:
      return in.fa01;
    case FrequencySource::kOption:
      return in.ignore_option ? 0 : in.fa07;
    case FrequencySource::kUpDown:
      return in.f268;
    default:
      return 0;
  }
}

// FA06 / FA00: the bits that belong to the source in command.
void ApplyCommandWord(std::uint16_t word, DriveCommand& cmd) {
  cmd.run = Bit(word, command_bit::kRun);
  cmd.reverse = Bit(word, command_bit::kReverse);
  cmd.jog = Bit(word, command_bit::kJog);
  cmd.standby = !Bit(word, command_bit::kCoastStop);
  cmd.dc_braking = Bit(word, command_bit::kDcBraking);
  cmd.thr2 = Bit(word, command_bit::kThr2);
  cmd.pid_off = Bit(word, command_bit::kPidOff);
  cmd.pattern = Bit(word, command_bit::kAd2) ? AccDecPattern::kAd2 : AccDecPattern::kAd1;
  cmd.preset = word & command_bit::kPresetMask;
}

}  // namespace

bool InputFunctionActive(const CommandInputs& in, std::int32_t function) {
  for (std::size_t i = 0; i < in.terminal_functions.size(); ++i) {
    const std::int32_t f = in.terminal_functions[i];
    const bool on = TerminalOn(in, i);
    if ((f == function && on) || (f == function + 1 && !on)) return true;
  }
  return false;
}

DriveCommand ResolveCommand(const CommandInputs& in) {
  DriveCommand cmd;
  const bool local = InputFunctionActive(in, input_function::kForcedLocal);
  const bool option_priority = !local && !in.ignore_option;

  // Command source.
  if (option_priority && Bit(in.fa06, command_bit::kCommandPriority)) {
    cmd.command_source = CommandSource::kOption;
  } else if (!local && Bit(in.fa00, command_bit::kCommandPriority)) {
    cmd.command_source = CommandSource::kRs485;
  } else if (InputFunctionActive(in, input_function::kCommandFromTerminal)) {
    cmd.command_source = CommandSource::kTerminal;
  } else {
    cmd.command_source = CommandSourceFromCmod(in.cmod);
  }

  // Frequency source.
  if (option_priority && Bit(in.fa06, command_bit::kFrequencyPriority)) {
    cmd.frequency_source = FrequencySource::kOption;
  } else if (!local && Bit(in.fa00, command_bit::kFrequencyPriority)) {
    cmd.frequency_source = FrequencySource::kRs485;
  } else {
    const bool fchg = InputFunctionActive(in, input_function::kFrequencyChange);
    cmd.frequency_source = FrequencySourceFromFmod(fchg ? in.f207 : in.fmod);
  }

  const bool terminal_standby = in.st_input || InputFunctionActive(in, input_function::kStandby);
  switch (cmd.command_source) {
    case CommandSource::kOption:
      if (in.ignore_option) {
        cmd.standby = terminal_standby;  // c101 = 0: the option's commands no longer count
        break;
      }
      ApplyCommandWord(in.fa06, cmd);
      // FA23 acts with the option in command (as VF-S11's FA20 needs FA00 bit 15; assumed for S15).
      if (Bit(in.fa23, command2_bit::kAccDec2)) {
        cmd.pattern = AccDecPattern::kAd3;
      } else if (Bit(in.fa23, command2_bit::kAccDec1)) {
        cmd.pattern = AccDecPattern::kAd2;
      }
      cmd.max_deceleration_stop = Bit(in.fa23, command2_bit::kMaxDecelerationStop);
      cmd.energy_reset = Bit(in.fa23, command2_bit::kEnergyReset);
      break;
    case CommandSource::kRs485:
      ApplyCommandWord(in.fa00, cmd);
      break;
    case CommandSource::kTerminal: {
      const bool forward = InputFunctionActive(in, input_function::kForward);
      const bool reverse = InputFunctionActive(in, input_function::kReverse);
      // F and R together: stop (assumed; the drive's f105 choice is not in the table).
      cmd.run = forward != reverse;
      cmd.reverse = reverse && !forward;
      cmd.standby = terminal_standby;
      for (int i = 0; i < 4; ++i) {
        if (InputFunctionActive(in, input_function::kPreset1 + 2 * i)) cmd.preset |= 1 << i;
      }
      break;
    }
    case CommandSource::kPanel:
      cmd.run = in.panel_run;
      cmd.reverse = in.panel_reverse;
      cmd.standby = terminal_standby;
      break;
    case CommandSource::kCanOpen:
      cmd.standby = terminal_standby;
      break;
  }

  if (cmd.jog) {
    cmd.frequency = kJogFrequency;
  } else if (cmd.preset != 0) {
    cmd.frequency = in.preset_speeds[static_cast<std::size_t>(cmd.preset - 1)];
  } else {
    cmd.frequency = SourceFrequency(in, cmd.frequency_source);
  }
  return cmd;
}

const char* CommandSourceName(CommandSource source) {
  switch (source) {
    case CommandSource::kTerminal:
      return "terminal";
    case CommandSource::kPanel:
      return "panel";
    case CommandSource::kRs485:
      return "rs485";
    case CommandSource::kCanOpen:
      return "canopen";
    case CommandSource::kOption:
      return "option";
  }
  return "?";
}

const char* FrequencySourceName(FrequencySource source) {
  switch (source) {
    case FrequencySource::kPanel:
      return "panel";
    case FrequencySource::kVia:
      return "via";
    case FrequencySource::kVib:
      return "vib";
    case FrequencySource::kRs485:
      return "rs485";
    case FrequencySource::kUpDown:
      return "up-down";
    case FrequencySource::kCanOpen:
      return "canopen";
    case FrequencySource::kOption:
      return "option";
    case FrequencySource::kVic:
      return "vic";
    case FrequencySource::kPulseTrain:
      return "pulse-train";
    case FrequencySource::kSr0:
      return "sr0";
    case FrequencySource::kNone:
      return "none";
  }
  return "?";
}

}  // namespace sim
