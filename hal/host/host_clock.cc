#include "host_clock.h"

#include <time.h>

namespace hal::host {

Micros HostClock::NowMicros() const {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<Micros>(ts.tv_sec) * kMicrosPerSecond + static_cast<Micros>(ts.tv_nsec) / 1000;
}

}  // namespace hal::host
