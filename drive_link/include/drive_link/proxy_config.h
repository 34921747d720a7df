// The register proxy's settings and counters, shared by its parts (register_proxy.h).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "drive_link/register_access.h"
#include "hal/clock.h"

namespace drive_link {

// Every value is documented with its reason in docs/drive-link.md.
struct ProxyConfig {
  // A new exchange cycle starts at most this often (on a fixed base time); 0 = back to back, as fast as
  // the link allows.
  hal::Micros min_cycle_period = 0;
  // A command word in use is written again this long after its last write even when unchanged: the
  // inverter forgets FA06/FA07 when a panel or terminal reset clears a trip, and the panel may change a
  // parameter target (acc, ul...). A changed word is written at once.
  hal::Micros command_refresh_interval = 500 * hal::kMicrosPerMilli;
  // The display values c041-c046 / c061-c066 are sampled this often and written when they changed.
  hal::Micros display_interval = hal::kMicrosPerSecond;
  // Read monitors by block (X) where the F875-F879 selections in force cover them (binary mode only).
  bool use_block_reads = true;
};

inline constexpr std::size_t kAccessErrorCount = static_cast<std::size_t>(AccessError::kNetworkLost) + 1;

struct ProxyCounters {
  std::uint32_t config_loads = 0;      // configurations read and parsed
  std::uint32_t cycles = 0;            // exchange cycles completed (every monitor word read once)
  hal::Micros cycle_period_last = 0;   // between the ends of the last two cycles
  hal::Micros cycle_period_min = 0;    // 0 until two cycles have ended
  hal::Micros cycle_period_max = 0;
  std::uint32_t command_writes = 0;    // P writes of command words (changes and refreshes): scanner
                                       // words and the drive command
  std::uint32_t command_errors = 0;    // ... refused by the inverter or unanswered
  std::uint32_t drive_command_writes = 0;  // the part of command_writes that wrote the drive command
  std::uint32_t monitor_reads = 0;     // R reads of monitor sources, FD01 and the drive feedback
  std::uint32_t block_reads = 0;       // X requests reading monitor sources
  std::uint32_t monitor_errors = 0;    // monitor reads (R or X) that failed
  std::uint32_t owned_writes = 0;      // write-backs of c502-c536, c555, c041-c066
  std::uint32_t owned_errors = 0;
  std::uint32_t loss_actions = 0;      // c101 actions started (c103 allowing)
  std::uint32_t loss_action_writes = 0;  // writes carrying them out (FA06 or FA30)
  std::uint32_t loss_action_errors = 0;  // ... refused by the inverter or unanswered
  std::uint32_t accesses = 0;          // on-demand accesses accepted
  std::uint32_t accesses_ok = 0;       // ... completed without error
  std::uint32_t pool_full = 0;         // Read/Write refused with kResourceExhausted
  // On-demand accesses that ended in each AccessError (index = the enum value; [0] is unused).
  std::array<std::uint32_t, kAccessErrorCount> access_errors{};
};

}  // namespace drive_link
