#include "panic.h"

#include "cmsdk_uart_registers.h"
#include "cortex_m.h"
#include "mmio.h"
#include "mps2_an386.h"

namespace hal::mps2 {
namespace {

// A byte at 115200 baud takes 87 µs; this many status reads is far more than that at 25 MHz.
constexpr unsigned kTransmitSpins = 100000;

}  // namespace

void WriteConsolePolled(std::string_view text) {
  const std::uintptr_t uart = address::kUart0;
  if (Read32(uart + uart_reg::kBaudDiv) < uart_reg::kMinBaudDiv) {
    Write32(uart + uart_reg::kBaudDiv, kSystemClockHz / 115200);
  }
  Write32(uart + uart_reg::kCtrl, Read32(uart + uart_reg::kCtrl) | uart_reg::kCtrlTxEnable);
  for (const char c : text) {
    for (unsigned spin = 0; spin < kTransmitSpins && (Read32(uart + uart_reg::kState) & uart_reg::kStateTxFull) != 0;
         ++spin) {
    }
    Write32(uart + uart_reg::kData, static_cast<std::uint8_t>(c));
  }
}

void Panic(std::string_view line) {
  MaskInterrupts();
  WriteConsolePolled(line);
  WriteConsolePolled("\r\n");
  for (unsigned spin = 0;
       spin < kTransmitSpins && (Read32(address::kUart0 + uart_reg::kState) & uart_reg::kStateTxFull) != 0; ++spin) {
  }
  SystemReset();
}

void AppendHex32(TextLine& line, std::uint32_t value) {
  line.Text("0x");
  for (int shift = 24; shift >= 0; shift -= 8) line.Hex(static_cast<std::uint8_t>(value >> shift));
}

}  // namespace hal::mps2
