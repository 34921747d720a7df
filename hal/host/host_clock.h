// hal::Clock on the host: CLOCK_MONOTONIC in microseconds.
#pragma once

#include "hal/clock.h"

namespace hal::host {

class HostClock final : public Clock {
 public:
  Micros NowMicros() const override;
};

}  // namespace hal::host
