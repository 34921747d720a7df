// What lwIP needs from the platform: a millisecond clock, random numbers, diagnostics.
//
// lwIP calls sys_now() and LWIP_RAND() as free C functions with no context argument, so the clock and
// the random source have to be reachable from a file-scope binding. The composition root binds them
// once at start-up (before lwip_init) and nothing else touches them.
#pragma once

#include <cstdint>

#include "hal/clock.h"
#include "hal/random.h"

namespace firmware {

void BindLwipPlatform(const hal::Clock& clock, hal::RandomSource& random);

}  // namespace firmware
