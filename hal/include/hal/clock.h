// Monotonic microsecond clock.
//
// Contract: NowMicros() never goes backwards, counts real elapsed time (not process CPU time) from an
// arbitrary origin (boot), and is 64 bits wide so it does not wrap during the life of a card.
// Every timer in the firmware is an absolute deadline on this clock, so periodic work (RPI production)
// keeps its base time and does not drift. Tests inject a fake clock.
#pragma once

#include <cstdint>

namespace hal {

using Micros = std::uint64_t;
inline constexpr Micros kMicrosPerMilli = 1000;
inline constexpr Micros kMicrosPerSecond = 1000 * 1000;
// A deadline that never arrives ("no timer pending").
inline constexpr Micros kNever = UINT64_MAX;

class Clock {
 public:
  virtual ~Clock() = default;
  virtual Micros NowMicros() const = 0;
};

}  // namespace hal
