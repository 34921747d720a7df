// hal::RandomSource of the mps2-an386 board, which has no TRNG: a ChaCha20 generator (chacha20.h)
// seeded at every boot from
//   1. a 256-bit seed kept in the NV store, written back renewed (from generator output) at once, so
//      no two boots of one card start alike even when everything else repeats;
//   2. timer jitter: the low bits of the 25 MHz counter around semihosting and register accesses whose
//      duration depends on the host QEMU runs on;
//   3. what makes this card different from another: its MAC (Mix()ed in once it is known).
// On QEMU that is as good as the host's timing noise; on a real MCU with one crystal, (2) is close to
// nothing and (1) is only as secret as the flash. docs/board.md "Random numbers" says what a real board
// must provide instead (a TRNG, or a factory-unique secret seed).
#pragma once

#include <cstdint>
#include <span>

#include "base/status.h"
#include "chacha20.h"
#include "hal/nv_store.h"
#include "hal/random.h"
#include "system_clock.h"

namespace hal::mps2 {

inline constexpr std::size_t kRandomSeedBytes = 32;

struct RandomSeeding {
  bool stored_seed = false;  // a seed was read from the store
  bool seed_renewed = false;  // the next boot's seed was written
  std::uint32_t jitter_samples = 0;
};

class BoardRandom final : public RandomSource {
 public:
  // Seeds from the stored seed (record `seed_record`) and timer jitter, then stores the next seed.
  // A store that cannot be read or written still leaves a seeded generator (RandomSeeding says what it
  // had). Call once, before anything draws numbers.
  RandomSeeding Seed(NvStore& store, NvRecordId seed_record, const SystemClock& clock);
  // More seed material (the MAC, anything card-specific).
  void Mix(std::span<const std::uint8_t> material) { generator_.Mix(material); }

  void Fill(std::span<std::uint8_t> out) override { generator_.Fill(out); }

 private:
  ChaChaGenerator generator_;
};

}  // namespace hal::mps2
