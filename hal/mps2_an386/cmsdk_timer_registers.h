// Registers of the CMSDK APB timer (ARM DDI0479C; QEMU hw/timer/cmsdk-apb-timer.c): a 32-bit counter
// that counts down at the system clock from RELOAD to 0, raises its interrupt there and reloads.
// Writing RELOAD also sets the current value.
#pragma once

#include <cstdint>

namespace hal::mps2::timer_reg {

inline constexpr std::uintptr_t kCtrl = 0x00;
inline constexpr std::uintptr_t kValue = 0x04;
inline constexpr std::uintptr_t kReload = 0x08;
inline constexpr std::uintptr_t kIntStatus = 0x0C;  // write 1: clear

inline constexpr std::uint32_t kCtrlEnable = 1U << 0;
inline constexpr std::uint32_t kCtrlInterruptEnable = 1U << 3;

}  // namespace hal::mps2::timer_reg
