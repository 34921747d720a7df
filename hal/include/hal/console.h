// The console: where the firmware's own text goes (lwIP's diagnostics, a board's LED and ready lines),
// and what ends the firmware when it finds itself in a state it cannot go on from.
//
// Contract:
// - ConsoleOutput::Write() never blocks for long: text that does not fit the backend's buffer is
//   dropped and counted by the backend (a card must not stall its event loop for a log line). Lines
//   end with the backend's line end, written by the caller as "\n"; a serial backend may send "\r\n".
// - FatalHandler::Fatal() does not return. It reports `message` (one line, no line end) as well as it
//   still can and stops the firmware: the host writes it to stderr and aborts (a core dump for the
//   developer); a board writes it to its console UART, polled, and resets the MCU.
#pragma once

#include <string_view>

namespace hal {

class ConsoleOutput {
 public:
  virtual ~ConsoleOutput() = default;
  virtual void Write(std::string_view text) = 0;
};

class FatalHandler {
 public:
  virtual ~FatalHandler() = default;
  [[noreturn]] virtual void Fatal(std::string_view message) = 0;
};

}  // namespace hal
