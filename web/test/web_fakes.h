// Fakes for the web server's password store and access control: a random source whose bytes count up
// (so salts and tokens are known exactly) and the HAL's NV store in memory that can be told to fail.
#pragma once

#include <cstdint>
#include <span>

#include "hal/random.h"
#include "memory_nv_store.h"

namespace web::test {

// Byte n of all the bytes ever handed out is (n mod 256) xor (n / 256 mod 256): the first Fill of 16
// gives 00..0f, the next 10..1f, and so on; after 256 bytes the values go on in another order, so
// that tokens drawn later do not repeat earlier ones.
class CountingRandom final : public hal::RandomSource {
 public:
  void Fill(std::span<std::uint8_t> out) override {
    for (std::uint8_t& byte : out) {
      byte = static_cast<std::uint8_t>(next_ ^ (next_ >> 8));
      ++next_;
    }
  }

 private:
  std::uint32_t next_ = 0;
};

// The NV store is the HAL's fake (one copy for every module's tests).
using MemoryNvStore = hal::test::MemoryNvStore;

}  // namespace web::test
