// hal::RandomSource on the host: getrandom(2), the kernel's CSPRNG.
#pragma once

#include "hal/random.h"

namespace hal::host {

class HostRandom final : public RandomSource {
 public:
  void Fill(std::span<std::uint8_t> out) override;
};

}  // namespace hal::host
