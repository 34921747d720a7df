// What lwIP needs from the platform: a millisecond clock, random numbers, diagnostics and an end for a
// failed assertion.
//
// lwIP calls sys_now(), LWIP_RAND(), LWIP_PLATFORM_DIAG and LWIP_PLATFORM_ASSERT as free C functions with
// no context argument, so what they use has to be reachable from a file-scope binding. The composition
// root binds them once at start-up (before lwip_init) and nothing else touches them. No stdio here: the
// diagnostics are formatted into a fixed buffer (diag_format.h) and go to the console the main gives
// (host: stderr; board: its console UART); a failed assertion goes to the fatal handler (host: abort;
// board: console line and reset).
#pragma once

#include <cstdint>

#include "hal/clock.h"
#include "hal/console.h"
#include "hal/random.h"

namespace firmware {

void BindLwipPlatform(const hal::Clock& clock, hal::RandomSource& random, hal::ConsoleOutput& diagnostics,
                      hal::FatalHandler& fatal);

}  // namespace firmware
