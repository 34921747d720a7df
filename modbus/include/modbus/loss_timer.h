// The Modbus side of network loss detection (seed 000 §3.2.3, MB-5): the c523 timer. When no counted
// communication arrives for c523 after the last one, it reports NetworkLost; the c100 delay, the c103
// condition and the c101 action happen behind drive_link::LossSupervision. The next counted
// communication reports NetworkRestored.
//
// What counts is the server's decision (docs/modbus.md "Loss supervision"); the timer only keeps time.
// It is armed by the first counted communication, not at start-up: a card nobody has commanded yet has
// no connection to lose (the Yaskawa card of seed 001 starts its timer at the first command write too).
#pragma once

#include <cstdint>

#include "drive_link/register_access.h"
#include "hal/clock.h"
#include "modbus/option_board.h"

namespace modbus {

class LossTimer {
 public:
  explicit LossTimer(drive_link::LossSupervision& supervision) : supervision_(supervision) {}

  // c523 in 0.1 s (0: disabled) and whether IO scanning is in use (c604), which picks the cause
  // reported: kModbusIoScanning (c536 = 1) or kModbusConnection.
  void Configure(std::uint16_t timeout_tenths, bool io_scanning);

  // A counted communication arrived at `now`.
  void Communicated(hal::Micros now);

  // Reports NetworkLost with the instant the timer expired (last communication + c523), however late
  // Poll runs.
  void Poll(hal::Micros now);
  hal::Micros NextDeadline() const;

  LossState state() const;

 private:
  enum class Phase : std::uint8_t { kWaiting, kRunning, kLost };

  drive_link::LossSupervision& supervision_;
  hal::Micros timeout_ = 0;
  drive_link::LossCause cause_ = drive_link::LossCause::kModbusConnection;
  Phase phase_ = Phase::kWaiting;
  hal::Micros last_ = 0;
};

}  // namespace modbus
