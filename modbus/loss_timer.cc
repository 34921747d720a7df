#include "modbus/loss_timer.h"

namespace modbus {

void LossTimer::Configure(std::uint16_t timeout_tenths, bool io_scanning) {
  timeout_ = static_cast<hal::Micros>(timeout_tenths) * (hal::kMicrosPerSecond / 10);
  cause_ = io_scanning ? drive_link::LossCause::kModbusIoScanning : drive_link::LossCause::kModbusConnection;
  // Disabling stops a running timer; a loss already reported stays until traffic returns.
  if (timeout_ == 0 && phase_ == Phase::kRunning) phase_ = Phase::kWaiting;
}

void LossTimer::Communicated(hal::Micros now) {
  if (phase_ == Phase::kLost) supervision_.NetworkRestored(now);
  last_ = now;
  phase_ = timeout_ == 0 ? Phase::kWaiting : Phase::kRunning;
}

void LossTimer::Poll(hal::Micros now) {
  if (phase_ != Phase::kRunning) return;
  const hal::Micros expiry = last_ + timeout_;
  if (now < expiry) return;
  phase_ = Phase::kLost;
  supervision_.NetworkLost(cause_, expiry);
}

hal::Micros LossTimer::NextDeadline() const {
  return phase_ == Phase::kRunning ? last_ + timeout_ : hal::kNever;
}

LossState LossTimer::state() const {
  if (phase_ == Phase::kLost) return LossState::kLost;
  if (timeout_ == 0) return LossState::kDisabled;
  return phase_ == Phase::kRunning ? LossState::kRunning : LossState::kWaiting;
}

}  // namespace modbus
