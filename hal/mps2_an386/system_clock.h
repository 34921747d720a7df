// hal::Clock on CMSDK timer 0: a free-running 32-bit down-counter at 25 MHz (RELOAD 0xFFFFFFFF, one
// wrap every 171.8 s), extended to 64 bits (DownCounterTicks) by every reading and by the wrap
// interrupt, so the count stays right when nothing reads the time for longer than a wrap. Microseconds
// are ticks / 25: 64 bits of them last 23 000 years.
#pragma once

#include <cstdint>

#include "hal/clock.h"
#include "interrupts.h"
#include "tick_counter.h"

namespace hal::mps2 {

class SystemClock final : public Clock, private InterruptHandler {
 public:
  SystemClock() = default;
  SystemClock(const SystemClock&) = delete;
  SystemClock& operator=(const SystemClock&) = delete;

  // Starts the counter at 0 µs. Before Start(), NowMicros() is 0.
  void Start();
  Micros NowMicros() const override;
  // The raw 25 MHz count since Start() (the random source samples its low bits).
  std::uint64_t NowTicks() const;

 private:
  bool OnInterrupt() override;

  mutable DownCounterTicks ticks_{0xFFFFFFFFU};
  bool started_ = false;
};

}  // namespace hal::mps2
