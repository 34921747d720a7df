// The console on UART0 (115200 baud): hal::ConsoleOutput for the firmware's lines and hal::FatalHandler
// for its last words. Lines go out with "\r\n" (a serial terminal's line end) for each "\n" written.
// Output never blocks the loop: what does not fit the transmit queue is dropped and counted (dropped()).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string_view>

#include "cmsdk_uart.h"
#include "hal/console.h"

namespace hal::mps2 {

inline constexpr std::uint32_t kConsoleBaud = 115200;
// 1 KiB of transmit queue: a line always fits; the long answers (stats, ~7 KB) go out a page at a time
// as the queue drains (firmware/board/board_console.h).
using ConsoleUart = CmsdkUart<128, 1024>;

class UartConsole final : public ConsoleOutput, public FatalHandler {
 public:
  explicit UartConsole(ConsoleUart& uart) : uart_(uart) {}

  void Write(std::string_view text) override;
  // Panic(): the message polled out of UART0 after what is still queued, then SYSRESETREQ.
  [[noreturn]] void Fatal(std::string_view message) override;

  std::uint64_t dropped() const { return dropped_; }
  // Whether `line` and its "\r\n" fit the transmit queue now, so that Write() drops nothing of it.
  bool Fits(std::string_view line) const { return line.size() + 2 <= uart_.transmit_room(); }

 private:
  void Put(std::string_view bytes);

  ConsoleUart& uart_;
  std::uint64_t dropped_ = 0;
};

}  // namespace hal::mps2
