// The simulated inverter's command-line settings, the same in both processes that run one: the host card
// (ipe002z-host, the inverter in-process) and the stand-alone inverter (ipe002z-inverter). One parser, so
// `--model`, `--param`, `--rs485-profile` and `--sim-processing-ms` mean exactly the same in both.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "sim/protocol_server.h"
#include "sim/register_table.h"

namespace sim {

// --param NAME|COMMNO=VALUE: a parameter preset for a new inverter, checked against the register table
// of the chosen model (an EEPROM parameter hosts may write, within its static limits).
struct ParamPreset {
  std::string text;          // as given ("acc=50"), for messages
  std::uint16_t number = 0;  // communication number
  std::int32_t value = 0;    // in the register's unit step
};

struct InverterOptions {
  Model model = Model::kVfMb1;
  std::vector<ParamPreset> params;  // in order; applied only to a new inverter (no EEPROM file yet)
  bool rs485_profile = false;       // 19200 baud 8E1, 20 ms processing (Rs485Profile())
  int sim_processing_ms = -1;       // the inverter's processing delay; -1: the profile's (2 ms or 20 ms)
};

enum class FlagOutcome { kNotOurs, kTaken, kInvalid };

// --rs485-profile, the one inverter flag without a value: true (and set) when `flag` is it.
bool TakeInverterSwitch(std::string_view flag, InverterOptions& options);

// --model, --param, --sim-processing-ms with their value. kInvalid when the value does not parse (the
// caller reports "invalid value for FLAG: 'VALUE'"); what a --param names is checked by CheckPresets.
FlagOutcome TakeInverterFlag(std::string_view flag, const std::string& value, InverterOptions& options);

// Once every flag is read (--model may come after --param): each preset must name an EEPROM parameter
// hosts may write, within the model's static limits; sets its number. False with `error`, e.g.
// "invalid value for --param: 'fmod=12' (out of range 0..11)".
bool CheckPresets(InverterOptions& options, std::string& error);

// The protocol server's settings these options ask for.
ServerConfig ServerConfigFromOptions(const InverterOptions& options);

// The --help lines of these flags.
extern const char kInverterOptionsUsage[];

}  // namespace sim
