// The stand-alone inverter's control socket (ipe002z-inverter --sim-control PATH): the inverter commands
// the host card offers (sim_control.h: get, set, terminal, trip, inject, status), and its own help,
// stats (the serial line and the protocol server) and power-cycle (the inverter alone: the card runs
// elsewhere, under QEMU). Same line protocol as the host card's (hal/host/control_server.h).
#pragma once

#include <string>
#include <string_view>

#include "listening_serial_port.h"
#include "sim_inverter.h"

namespace sim {

// Runs one control command and appends its answer: data lines, then "ok" or "error <reason>".
void HandleStandaloneCommand(std::string_view command, std::string& reply, SimulatedInverter& inverter,
                             const hal::host::ListeningSerialPort& line);

}  // namespace sim
