// A hal::Clock that moves only when the test says so.
#pragma once

#include "hal/clock.h"

namespace hal::test {

class FakeClock final : public Clock {
 public:
  explicit FakeClock(Micros start = 0) : now_(start) {}
  Micros NowMicros() const override { return now_; }
  void Advance(Micros delta) { now_ += delta; }
  void Set(Micros now) { now_ = now; }

 private:
  Micros now_;
};

}  // namespace hal::test
