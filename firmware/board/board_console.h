// The board's console service: commands typed on UART0, one per line (CR or LF ends it), answered like
// the host's control socket: zero or more `name=value` lines, then `ok` or `error <reason>`.
//
//   help           the commands
//   stats          stack.size, stack.high_water (from the stack painted at reset), the event loop, the
//                  waiter, the console, then the card's report (firmware/card/card_report.h: netif,
//                  ports, lwIP, drive link, front ends, addressing, pools), named as on the host
//   config         the configuration read from the inverter (as the host's `config`)
//   address        the address line (as the host's `address`)
//   led-inputs     what the MS/NS model is given now
//   leds           LNK-L=... LNK-R=... MS=... NS=... (what the LEDs show)
//   reset          Identity-Reset-like restart (through the card's ResetControl: queued replies first)
//   watchdog-test  stops the event loop for good (interrupts stay on), to show that the watchdog resets
//                  the card: a warning line after one timeout, the reset after the second
//
// A line longer than kMaxLine is refused whole ("error line too long"), and so is a line during which
// received bytes were lost ("error input lost"). Device code: no allocation.
//
// A long answer (stats is ~7 KB) never blocks the loop and is never cut: it goes out a page at a time,
// as much as the console's transmit queue takes, and the next page when it has drained (the report is
// run again and the lines already sent are skipped, so a page is a snapshot of its moment). Input
// waits until the answer is complete.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "card.h"
#include "card_report.h"
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
  // Input wakes the loop; an answer still going out is continued once its queue had time to drain.
  hal::Micros NextDeadline() const override {
    return answer_ == Answer::kNone ? hal::kNever : last_poll_ + kPageInterval;
  }

 private:
  static constexpr hal::Micros kPageInterval = 2 * hal::kMicrosPerMilli;
  enum class Answer : std::uint8_t { kNone, kStats, kConfig };
  class PageSink;

  void Execute(std::string_view line);
  // Sends the next page of the answer in progress; ends it with "ok" once every line is out.
  void ContinueAnswer();
  void Report(ReportSink& sink);
  void Print(std::string_view text);

  BoardConsoleDevices devices_;
  std::array<char, kMaxLine> line_{};
  std::size_t length_ = 0;
  enum class Refusal : std::uint8_t { kNone, kTooLong, kInputLost };
  Refusal refusal_ = Refusal::kNone;  // why the line being typed will be refused
  Answer answer_ = Answer::kNone;     // a long answer going out
  std::size_t lines_sent_ = 0;        // of that answer
  hal::Micros last_poll_ = 0;
};

}  // namespace firmware::board
