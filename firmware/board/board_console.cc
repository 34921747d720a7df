#include "board_console.h"

#include "drive_link/link_client.h"
#include "hal/text_line.h"
#include "startup.h"

namespace firmware::board {
namespace {

constexpr std::string_view kHelp =
    "help           this list\n"
    "stats          counters: stack, event loop, waiter, console, netif, port, drive link\n"
    "leds           what the LEDs show\n"
    "reset          restart the card (queued replies and parameter writes first)\n"
    "watchdog-test  stop the event loop: the watchdog must reset the card\n";

std::string_view Trim(std::string_view text) {
  while (!text.empty() && text.front() == ' ') text.remove_prefix(1);
  while (!text.empty() && text.back() == ' ') text.remove_suffix(1);
  return text;
}

}  // namespace

void BoardConsole::Poll(hal::Micros) {
  std::array<std::uint8_t, 32> bytes;
  for (;;) {
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

void BoardConsole::Value(std::string_view name, std::uint64_t value) {
  hal::TextLine line;
  line.Text(name).Text("=").Unsigned(value).Text("\n");
  Print(line.view());
}

void BoardConsole::Execute(std::string_view command) {
  if (command.empty()) return;
  if (command == "help") {
    Print(kHelp);
  } else if (command == "stats") {
    Stats();
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

void BoardConsole::Stats() {
  const hal::mps2::StackUsage stack = hal::mps2::MainStackUsage();
  Value("stack.size", stack.size);
  Value("stack.high_water", stack.high_water);
  const LoopStats& loop = devices_.card.loop().stats();
  Value("loop.passes", loop.passes);
  Value("loop.frames_in", loop.frames_in);
  Value("loop.bounded_passes", loop.bounded_passes);
  Value("loop.link_changes", loop.link_changes);
  Value("waiter.sleeps", devices_.waiter.counters().sleeps);
  Value("waiter.woken_early", devices_.waiter.counters().woken_early);
  Value("console.dropped", devices_.console.dropped());
  const CardNetif& netif = devices_.card.netif();
  Print(netif.link_up() ? "netif.link=up\n" : "netif.link=down\n");
  const NetifCounters& n = netif.counters();
  Value("netif.rx_frames", n.rx_frames);
  Value("netif.rx_dropped_no_pbuf", n.rx_dropped_no_pbuf);
  Value("netif.rx_port_errors", n.rx_port_errors);
  Value("netif.tx_frames", n.tx_frames);
  Value("netif.tx_dropped", n.tx_dropped);
  const hal::PortCounters c = devices_.card.netif().port().Counters(hal::PortId::kLeft);
  Value("port.L.rx_frames", c.rx_frames);
  Value("port.L.rx_octets", c.rx_octets);
  Value("port.L.rx_errors", c.rx_errors);
  Value("port.L.tx_frames", c.tx_frames);
  Value("port.L.tx_octets", c.tx_octets);
  Value("port.L.tx_errors", c.tx_errors);
  hal::TextLine drive;
  drive.Text("drive.link=").Text(drive_link::LinkStateName(devices_.card.proxy().link().state())).Text("\n");
  Print(drive.view());
}

}  // namespace firmware::board
