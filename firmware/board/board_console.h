// The board's console service: commands typed on UART0, one per line (CR or LF ends it), answered like
// the host's control socket: zero or more `name=value` lines, then `ok` or `error <reason>`.
//
//   help           the commands
//   stats          stack.size, stack.high_water (from the stack painted at reset), the event loop, the
//                  waiter, the console, the netif and the port's counters, the drive link's state
//   leds           LNK-L=... LNK-R=... MS=... NS=... (what the LEDs show)
//   reset          Identity-Reset-like restart (through the card's ResetControl: queued replies first)
//   watchdog-test  stops the event loop for good (interrupts stay on), to show that the watchdog resets
//                  the card: a warning line after one timeout, the reset after the second
//
// A line longer than kMaxLine is refused whole ("error line too long"), and so is a line during which
// received bytes were lost ("error input lost"). Device code: no allocation.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "card.h"
#include "event_loop.h"
#include "fpgaio_leds.h"
#include "hal/console.h"
#include "hal/serial_port.h"
#include "timer_waiter.h"
#include "uart_console.h"

namespace firmware::board {

// What the console reports on besides the card.
struct BoardConsoleDevices {
  hal::SerialPort& input;  // UART0's receive side
  hal::ConsoleOutput& output;
  Card& card;
  const hal::mps2::FpgaioLeds& leds;
  const hal::mps2::TimerWaiter& waiter;
  const hal::mps2::UartConsole& console;
};

class BoardConsole final : public Service {
 public:
  static constexpr std::size_t kMaxLine = 80;

  explicit BoardConsole(const BoardConsoleDevices& devices) : devices_(devices) {}

  void Poll(hal::Micros now) override;
  hal::Micros NextDeadline() const override { return hal::kNever; }  // input wakes the loop

 private:
  void Execute(std::string_view line);
  void Stats();
  void Print(std::string_view text);
  void Value(std::string_view name, std::uint64_t value);

  BoardConsoleDevices devices_;
  std::array<char, kMaxLine> line_{};
  std::size_t length_ = 0;
  enum class Refusal : std::uint8_t { kNone, kTooLong, kInputLost };
  Refusal refusal_ = Refusal::kNone;  // why the line being typed will be refused
};

}  // namespace firmware::board
