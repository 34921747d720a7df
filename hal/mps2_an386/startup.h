// What the reset handler leaves behind for the firmware: the main stack, painted with a pattern at
// reset so that its deepest use so far can be read at any time (the console's `stats`).
#pragma once

#include <cstddef>
#include <cstdint>

namespace hal::mps2 {

inline constexpr std::uint32_t kStackPaint = 0xA5A5A5A5;

struct StackUsage {
  std::size_t size = 0;        // bytes reserved for the main stack (the linker script's .stack)
  std::size_t high_water = 0;  // the most of it ever used since reset (bytes no longer painted)
};
StackUsage MainStackUsage();

// Whether a semihosting call (BKPT 0xAB) found no debugger or emulator to serve it: the HardFault
// handler then makes the call return -1 instead of stopping the card (semihosting.h).
bool SemihostingTrapped();

}  // namespace hal::mps2
