// ipe002z-inverter: the simulated inverter as its own process, the composition root of that process.
//
// It listens on the serial endpoint (hal/host/listening_serial_port.h), creates the SimulatedInverter on
// it with its EEPROM file in the state dir, keys --ip into it, opens the control socket, prints
// `inverter-ready serial=... control=... model=... state=...` on stdout, then runs one single-threaded
// poll loop that never blocks on a peer: the line, the protocol server's timers, the store check, the
// control socket and SIGINT/SIGTERM. On a stop signal it stores the EEPROM image and returns.
#pragma once

#include <cstdio>
#include <string>

#include "standalone_options.h"

namespace sim {

enum class StandaloneExit {
  kStopped,  // SIGINT/SIGTERM: the image is stored; exit 0
  kFailed,   // start-up failed (the endpoint cannot be bound, a preset refused...); `error` says why
};

// `out` receives the ready line, `log` the warnings and the serial line's client events.
StandaloneExit RunStandaloneInverter(const StandaloneOptions& options, std::FILE* out, std::FILE* log,
                                     std::string& error);

}  // namespace sim
