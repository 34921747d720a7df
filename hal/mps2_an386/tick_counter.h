// A 64-bit count of timer ticks from a 32-bit hardware counter that counts down from 0xFFFFFFFF and
// wraps (a CMSDK timer with RELOAD = 0xFFFFFFFF). Each Update() adds the ticks since the previous one,
// modulo 2^32, so the count is right as long as Update() runs at least once per wrap (2^32 ticks: 171 s
// at 25 MHz); the clock's wrap interrupt guarantees that even when nothing else reads the time.
#pragma once

#include <cstdint>

namespace hal::mps2 {

class DownCounterTicks {
 public:
  explicit DownCounterTicks(std::uint32_t first_value) : last_(first_value) {}

  std::uint64_t Update(std::uint32_t value) {
    total_ += static_cast<std::uint32_t>(last_ - value);
    last_ = value;
    return total_;
  }
  std::uint64_t total() const { return total_; }

 private:
  std::uint32_t last_;
  std::uint64_t total_ = 0;
};

}  // namespace hal::mps2
