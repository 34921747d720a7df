#include "board_console.h"

#include "card_lines.h"
#include "hal/text_line.h"
#include "startup.h"

namespace firmware::board {
namespace {

constexpr std::string_view kHelp =
    "help           this list\n"
    "stats          counters: stack, event loop, waiter, console, then the card's (as on the host)\n"
    "config         the configuration read from the inverter and its problems\n"
    "address        IP mode, phase, address in use, ACD duplicate flag, attribute 11 (hex)\n"
    "led-inputs     what the MS/NS model is given now\n"
    "leds           what the LEDs show\n"
    "reset          restart the card (queued replies and parameter writes first)\n"
    "watchdog-test  stop the event loop: the watchdog must reset the card\n";

std::string_view Trim(std::string_view text) {
  while (!text.empty() && text.front() == ' ') text.remove_prefix(1);
  while (!text.empty() && text.back() == ' ') text.remove_suffix(1);
  return text;
}

}  // namespace

// Writes the lines after the first `skip` while the console takes them whole; counts what it wrote.
class BoardConsole::PageSink final : public ReportSink {
 public:
  PageSink(const hal::mps2::UartConsole& console, hal::ConsoleOutput& output, std::size_t skip)
      : console_(console), output_(output), skip_(skip) {}
  void Line(std::string_view line) override {
    if (seen_++ < skip_ || full_) return;
    if (!console_.Fits(line)) {
      full_ = true;
      return;
    }
    output_.Write(line);
    output_.Write("\n");
    ++written_;
  }
  bool full() const { return full_; }
  std::size_t written() const { return written_; }

 private:
  const hal::mps2::UartConsole& console_;
  hal::ConsoleOutput& output_;
  std::size_t skip_;
  std::size_t seen_ = 0;
  std::size_t written_ = 0;
  bool full_ = false;
};

void BoardConsole::Poll(hal::Micros now) {
  last_poll_ = now;
  if (answer_ != Answer::kNone) {
    ContinueAnswer();
    if (answer_ != Answer::kNone) return;  // input waits for the answer
  }
  // One byte at a time: a command that starts a long answer leaves what follows it unread until the
  // answer is out.
  std::array<std::uint8_t, 1> bytes;
  while (answer_ == Answer::kNone) {
    const base::Result<std::size_t> read = devices_.input.Read(bytes);
    if (read.status().code() == base::StatusCode::kUnavailable) return;
    if (!read.ok()) {
      // Bytes were lost: the line they belonged to is not what was typed.
      refusal_ = Refusal::kInputLost;
      continue;
    }
    for (std::size_t i = 0; i < read.value(); ++i) {
      const char c = static_cast<char>(bytes[i]);
      if (c == '\r' || c == '\n') {
        if (refusal_ == Refusal::kTooLong) {
          Print("error line too long\n");
        } else if (refusal_ == Refusal::kInputLost) {
          Print("error input lost\n");
        } else if (length_ > 0) {
          Execute(Trim(std::string_view(line_.data(), length_)));
        }
        length_ = 0;
        refusal_ = Refusal::kNone;
      } else if (length_ == line_.size()) {
        if (refusal_ == Refusal::kNone) refusal_ = Refusal::kTooLong;
      } else {
        line_[length_++] = c;
      }
    }
  }
}

void BoardConsole::Print(std::string_view text) { devices_.output.Write(text); }

void BoardConsole::ContinueAnswer() {
  PageSink page(devices_.console, devices_.output, lines_sent_);
  Report(page);
  lines_sent_ += page.written();
  if (page.full() || !devices_.console.Fits("ok")) return;
  answer_ = Answer::kNone;
  Print("ok\n");
}

void BoardConsole::Report(ReportSink& sink) {
  if (answer_ == Answer::kConfig) {
    ReportCardConfig(devices_.card, sink);
    return;
  }
  const hal::mps2::StackUsage stack = hal::mps2::MainStackUsage();
  sink.Value({"stack.size"}, stack.size);
  sink.Value({"stack.high_water"}, stack.high_water);
  ReportLoopStats(devices_.card.loop(), sink);
  sink.Value({"waiter.sleeps"}, devices_.waiter.counters().sleeps);
  sink.Value({"waiter.woken_early"}, devices_.waiter.counters().woken_early);
  sink.Value({"console.dropped"}, devices_.console.dropped());
  ReportNetifStats(devices_.card.netif(), sink);
  ReportCardStats(devices_.card, sink);
}

void BoardConsole::Execute(std::string_view command) {
  if (command.empty()) return;
  if (command == "help") {
    Print(kHelp);
  } else if (command == "stats" || command == "config") {
    answer_ = command == "stats" ? Answer::kStats : Answer::kConfig;
    lines_sent_ = 0;
    ContinueAnswer();
    return;  // "ok" comes with the last page
  } else if (command == "address") {
    hal::TextLine line;
    DescribeAddress(devices_.card.addressing(), line);
    line.Text("\n");
    Print(line.view());
  } else if (command == "led-inputs") {
    hal::TextLine line;
    DescribeLedInputs(devices_.card, line);
    line.Text("\n");
    Print(line.view());
  } else if (command == "leds") {
    hal::TextLine line;
    hal::DescribeLeds(devices_.leds.colors(), line);
    line.Text("\n");
    Print(line.view());
  } else if (command == "reset") {
    devices_.card.reset_control().RequestReset(hal::ResetKind::kRestart);
  } else if (command == "watchdog-test") {
    Print("watchdog-test: the event loop stops here; the watchdog resets the card\nok\n");
    for (;;) __asm__ volatile("wfi");
  } else {
    Print("error unknown command (help lists them)\n");
    return;
  }
  Print("ok\n");
}

}  // namespace firmware::board
