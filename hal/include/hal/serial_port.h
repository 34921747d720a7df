// Serial byte port: the card's link to the inverter (Toshiba inverter protocol, seed 003).
//
// Contract: never blocks. Read() returns the bytes already received (kUnavailable when none yet);
// Write() queues bytes and returns how many it accepted (fewer than asked when the transmit buffer is
// full; the caller retries the rest). A framing or parity error is reported once as kDataLoss by the
// Read() that would have returned the damaged byte; the byte is discarded.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

#include "base/status.h"

namespace hal {

enum class Parity : std::uint8_t { kNone, kEven, kOdd };

struct SerialConfig {
  std::uint32_t baud = 19200;
  Parity parity = Parity::kEven;
  std::uint8_t stop_bits = 1;
};

class SerialPort {
 public:
  virtual ~SerialPort() = default;
  virtual base::Status Configure(const SerialConfig& config) = 0;
  virtual base::Result<std::size_t> Read(std::span<std::uint8_t> buffer) = 0;
  virtual base::Result<std::size_t> Write(std::span<const std::uint8_t> bytes) = 0;
};

}  // namespace hal
