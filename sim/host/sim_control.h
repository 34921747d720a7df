// The control socket's commands for the simulated inverter: read and write its registers as the panel
// would, work its terminals, trip it, damage its serial replies, report its state. Both control sockets
// that drive an inverter pass every command they do not know themselves here: the host card's
// (firmware/host/card_report.cc) and ipe002z-inverter's (standalone_control.cc). docs/simulator.md
// "Control commands" lists them.
#pragma once

#include <span>
#include <string>
#include <string_view>

#include "sim_inverter.h"

namespace sim {

// The lines `help` adds for these commands.
extern const char kSimControlHelp[];

// Runs `words` (the command split at spaces, words[0] the verb) when it is an inverter command and
// appends its answer: data lines, then "ok" or "error <reason>". False when the verb is not one of
// them (nothing appended).
bool HandleSimCommand(std::span<const std::string_view> words, std::string& reply, SimulatedInverter& inverter);

// The `status` line: one JSON object (state, model, output and target frequency, command and frequency
// source, priorities, FA06, FA07, FD01, trip code, EEPROM writes), without a newline.
std::string InverterStatusJson(SimulatedInverter& inverter);

}  // namespace sim
