// A random source for timing tests: hands out the pushed 32-bit values (little-endian) first, then 0, so
// every random wait not scripted is at its minimum.
#pragma once

#include <cstdint>
#include <deque>
#include <span>

#include "hal/random.h"

namespace hal::test {

class QueuedRandom final : public RandomSource {
 public:
  void Push(std::uint32_t value) { values_.push_back(value); }
  void Fill(std::span<std::uint8_t> out) override {
    std::uint32_t value = 0;
    if (!values_.empty()) {
      value = values_.front();
      values_.pop_front();
    }
    for (std::size_t i = 0; i < out.size(); ++i) out[i] = static_cast<std::uint8_t>(value >> (8 * (i % 4)));
  }

 private:
  std::deque<std::uint32_t> values_;
};

}  // namespace hal::test
