// Facts of the board: the ARM MPS2 with the AN386 FPGA image (Cortex-M4F), as QEMU 7.2's mps2-an386
// models it (hw/arm/mps2.c). docs/board.md has the memory map.
#pragma once

#include <cstddef>
#include <cstdint>

namespace hal::mps2 {

// Every CMSDK peripheral, and the CPU, run from the 25 MHz system clock.
inline constexpr std::uint32_t kSystemClockHz = 25'000'000;
inline constexpr std::uint32_t kTicksPerMicro = kSystemClockHz / 1'000'000;

namespace address {
inline constexpr std::uintptr_t kTimer0 = 0x40000000;    // CMSDK APB timer: the clock
inline constexpr std::uintptr_t kTimer1 = 0x40001000;    // CMSDK APB timer: the waiter's deadline
inline constexpr std::uintptr_t kUart0 = 0x40004000;     // CMSDK APB UART: the console
inline constexpr std::uintptr_t kUart1 = 0x40005000;     // CMSDK APB UART: the drive link
inline constexpr std::uintptr_t kWatchdog = 0x40008000;  // CMSDK APB watchdog (interrupt = NMI)
inline constexpr std::uintptr_t kFpgaIo = 0x40028000;    // FPGA I/O: the two user LEDs
inline constexpr std::uintptr_t kEthernet = 0x40200000;  // SMSC LAN9118 (LAN9220 on the real board)
}  // namespace address

// External interrupt numbers (NVIC lines); the UART's transmit interrupt is its receive line + 1.
enum class Irq : std::uint8_t {
  kUart0Receive = 0,
  kUart0Transmit = 1,
  kUart1Receive = 2,
  kUart1Transmit = 3,
  kTimer0 = 8,
  kTimer1 = 9,
  kEthernet = 13,
};
inline constexpr std::size_t kIrqCount = 32;

}  // namespace hal::mps2
