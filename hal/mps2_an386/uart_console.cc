#include "uart_console.h"

#include "panic.h"

namespace hal::mps2 {

void UartConsole::Put(std::string_view bytes) {
  const std::span<const std::uint8_t> data(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
  const base::Result<std::size_t> queued = uart_.Write(data);
  const std::size_t taken = queued.ok() ? queued.value() : 0;
  dropped_ += bytes.size() - taken;
}

void UartConsole::Write(std::string_view text) {
  while (!text.empty()) {
    const std::size_t newline = text.find('\n');
    if (newline == std::string_view::npos) {
      Put(text);
      return;
    }
    Put(text.substr(0, newline));
    Put("\r\n");
    text.remove_prefix(newline + 1);
  }
}

void UartConsole::Fatal(std::string_view message) {
  // What the interrupt-driven console still holds goes first, so the last line is really the last.
  {
    CriticalSection masked;
    for (unsigned spins = 0; uart_.transmit_pending() != 0 && spins < 1000000; ++spins) {
      static_cast<void>(uart_.Write({}));  // feeds the transmitter from the queue
    }
  }
  Panic(message);
}

}  // namespace hal::mps2
