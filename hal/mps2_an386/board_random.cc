#include "board_random.h"

#include <array>

#include "mmio.h"
#include "mps2_an386.h"

namespace hal::mps2 {
namespace {

// Samples of the counter's low byte between slow accesses: an access to a device QEMU emulates leaves
// the CPU for the host, for a time the host's scheduling decides.
constexpr std::size_t kJitterSamples = 256;

void CollectJitter(const SystemClock& clock, std::span<std::uint8_t, kJitterSamples> out) {
  for (std::uint8_t& sample : out) {
    // A read of the Ethernet controller's free-running counter and byte-test register: each a round
    // trip to the emulator (on real hardware a fixed number of bus cycles).
    static_cast<void>(Read32(address::kEthernet + 0x9C));
    static_cast<void>(Read32(address::kEthernet + 0x64));
    sample = static_cast<std::uint8_t>(clock.NowTicks());
  }
}

}  // namespace

RandomSeeding BoardRandom::Seed(NvStore& store, NvRecordId seed_record, const SystemClock& clock) {
  RandomSeeding seeding;
  std::array<std::uint8_t, kRandomSeedBytes> seed{};
  const base::Result<std::size_t> read = store.Read(seed_record, seed);
  seeding.stored_seed = read.ok() && read.value() == seed.size();
  if (seeding.stored_seed) generator_.Mix(seed);

  std::array<std::uint8_t, kJitterSamples> jitter{};
  CollectJitter(clock, jitter);
  generator_.Mix(jitter);
  seeding.jitter_samples = kJitterSamples;
  // The time since reset to here (semihosting calls, flash file) is jitter too.
  const std::uint64_t now = clock.NowTicks();
  std::array<std::uint8_t, 8> time{};
  for (std::size_t i = 0; i < time.size(); ++i) time[i] = static_cast<std::uint8_t>(now >> (8 * i));
  generator_.Mix(time);

  // The next boot's seed: output of the generator, from which its key cannot be worked back.
  generator_.Fill(seed);
  seeding.seed_renewed = store.Write(seed_record, seed).ok();
  seed.fill(0);
  jitter.fill(0);
  return seeding;
}

}  // namespace hal::mps2
