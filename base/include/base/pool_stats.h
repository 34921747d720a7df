// The occupancy of one of the card's fixed-size pools (sessions, connection slots, queues), as the host
// card's control socket reports it (`stats`: pool.<name>.used/capacity/high_water/refused;
// docs/robustness.md "Exhaustion").
//
// `used` is always counted from the pool's own slots when asked, never kept as a separate number that
// could drift from them: a slot that is never given back shows as used, which is what the exhaustion
// test looks for. What the slots cannot tell afterwards, the most ever in use at once and how many
// requests found the pool full, a PoolWatermark beside the pool keeps.
#pragma once

#include <cstddef>
#include <cstdint>

namespace base {

struct PoolStats {
  std::size_t used = 0;        // slots in use now
  std::size_t capacity = 0;    // slots in all
  std::size_t high_water = 0;  // the most slots in use at once since start
  std::uint32_t refused = 0;   // requests refused because every slot was taken (wraps)

  constexpr bool operator==(const PoolStats&) const = default;
};

class PoolWatermark {
 public:
  // A slot was just taken; `used` counts the slots in use now, that one included.
  constexpr void NoteTaken(std::size_t used) {
    if (used > high_water_) high_water_ = used;
  }
  // A request found every slot taken and was refused.
  constexpr void NoteRefused() { ++refused_; }

  constexpr PoolStats Stats(std::size_t used, std::size_t capacity) const {
    return PoolStats{used, capacity, high_water_ > used ? high_water_ : used, refused_};
  }

 private:
  std::size_t high_water_ = 0;
  std::uint32_t refused_ = 0;
};

}  // namespace base
