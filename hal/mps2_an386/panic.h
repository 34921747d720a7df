// The firmware's last words: written to the console UART by polling (interrupts may be masked, and the
// interrupt-driven console may be what failed), then the MCU resets. Used by the fault handlers, the
// trapping operator new, __cxa_pure_virtual and the console's FatalHandler.
#pragma once

#include <cstdint>
#include <string_view>

#include "hal/text_line.h"

namespace hal::mps2 {

// Writes `text` to UART0 byte by byte, waiting for the transmitter (bounded: a stuck UART cannot hang
// the caller); programs UART0 for 115200 baud first if nobody has.
void WriteConsolePolled(std::string_view text);

// `line` plus "\r\n" on the console, the transmitter drained, then SYSRESETREQ.
[[noreturn]] void Panic(std::string_view line);

// "0x" and eight lowercase hex digits.
void AppendHex32(TextLine& line, std::uint32_t value);

}  // namespace hal::mps2
