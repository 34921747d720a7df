// What the card reports of lwIP's insides: the names of its memory pools and the length of its TCP PCB
// lists. lwIP declares both only in private headers (lwip/priv/memp_std.h, lwip/priv/tcp_priv.h); this
// file's implementation is the one place of the firmware that includes them, so the rest of the card
// uses lwIP's public API only (docs/lwip.md).
#pragma once

#include <cstddef>
#include <cstdint>

#include "lwip/memp.h"

namespace firmware {

// lwIP's memory pools (MEMP_MAX): the indices of lwip_stats.memp.
inline constexpr std::size_t kLwipPoolCount = MEMP_MAX;

// The name of lwIP's memory pool `pool` (below kLwipPoolCount), as lwIP's
// pool list spells it (e.g. "TCP_PCB"). lwIP keeps the names itself only in debug builds.
const char* LwipPoolName(std::size_t pool);

// lwIP's TCP PCBs by list. A connection the card closed first stays in TIME_WAIT for 2 x TCP_MSL and
// keeps its TCP_PCB (docs/robustness.md "Exhaustion"): the lists tell those apart from a leak.
struct LwipTcpPcbCounts {
  std::uint64_t active = 0;
  std::uint64_t time_wait = 0;
  std::uint64_t listen = 0;
};
LwipTcpPcbCounts CountLwipTcpPcbs();

}  // namespace firmware
