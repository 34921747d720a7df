// Memory-mapped register access: every peripheral register is a 32-bit word read and written whole.
#pragma once

#include <cstdint>

namespace hal::mps2 {

inline std::uint32_t Read32(std::uintptr_t address) { return *reinterpret_cast<volatile std::uint32_t*>(address); }

inline void Write32(std::uintptr_t address, std::uint32_t value) {
  *reinterpret_cast<volatile std::uint32_t*>(address) = value;
}

}  // namespace hal::mps2
