// Registers of the CMSDK APB UART (ARM DDI0479C; QEMU hw/char/cmsdk-apb-uart.c): one byte deep each
// way, 8 data bits, no parity, one stop bit, baud = system clock / BAUDDIV (BAUDDIV >= 16).
#pragma once

#include <cstdint>

namespace hal::mps2::uart_reg {

inline constexpr std::uintptr_t kData = 0x00;
inline constexpr std::uintptr_t kState = 0x04;      // bit 0 TX full, 1 RX full, 2 TX overrun, 3 RX overrun (W1C)
inline constexpr std::uintptr_t kCtrl = 0x08;
inline constexpr std::uintptr_t kIntStatus = 0x0C;  // read: pending; write 1: clear
inline constexpr std::uintptr_t kBaudDiv = 0x10;

inline constexpr std::uint32_t kStateTxFull = 1U << 0;
inline constexpr std::uint32_t kStateRxFull = 1U << 1;
inline constexpr std::uint32_t kStateTxOverrun = 1U << 2;
inline constexpr std::uint32_t kStateRxOverrun = 1U << 3;

inline constexpr std::uint32_t kCtrlTxEnable = 1U << 0;
inline constexpr std::uint32_t kCtrlRxEnable = 1U << 1;
inline constexpr std::uint32_t kCtrlTxInterrupt = 1U << 2;
inline constexpr std::uint32_t kCtrlRxInterrupt = 1U << 3;
inline constexpr std::uint32_t kCtrlTxOverrunInterrupt = 1U << 4;
inline constexpr std::uint32_t kCtrlRxOverrunInterrupt = 1U << 5;

inline constexpr std::uint32_t kIntTx = 1U << 0;
inline constexpr std::uint32_t kIntRx = 1U << 1;
inline constexpr std::uint32_t kIntTxOverrun = 1U << 2;
inline constexpr std::uint32_t kIntRxOverrun = 1U << 3;

inline constexpr std::uint32_t kMinBaudDiv = 16;

}  // namespace hal::mps2::uart_reg
