// lwIP is a process-wide singleton (NO_SYS): initialise it once for the whole unit-test binary, with a
// fake clock and a deterministic random source, before any test touches a netif.
#pragma once

#include <gtest/gtest.h>

#include "fake_clock.h"
#include "hal/random.h"

namespace hal::test {

class CountingRandom final : public RandomSource {
 public:
  void Fill(std::span<std::uint8_t> out) override {
    for (auto& b : out) b = static_cast<std::uint8_t>(++state_);
  }

 private:
  std::uint8_t state_ = 0;
};

// The clock lwIP's sys_now() reads in every unit test.
FakeClock& LwipTestClock();
void EnsureLwipInitialised();

}  // namespace hal::test
