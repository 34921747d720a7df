#include "lwip_internals.h"

#include "lwip/priv/tcp_priv.h"

namespace firmware {
namespace {

constexpr const char* kPoolNames[] = {
#define LWIP_MEMPOOL(name, num, size, desc) #name,
#include "lwip/priv/memp_std.h"
};
static_assert(sizeof(kPoolNames) / sizeof(kPoolNames[0]) == kLwipPoolCount);

std::uint64_t CountPcbs(const tcp_pcb* list) {
  std::uint64_t count = 0;
  for (const tcp_pcb* pcb = list; pcb != nullptr; pcb = pcb->next) ++count;
  return count;
}

}  // namespace

const char* LwipPoolName(std::size_t pool) { return pool < kLwipPoolCount ? kPoolNames[pool] : "?"; }

LwipTcpPcbCounts CountLwipTcpPcbs() {
  LwipTcpPcbCounts counts;
  counts.active = CountPcbs(tcp_active_pcbs);
  counts.time_wait = CountPcbs(tcp_tw_pcbs);
  for (const tcp_pcb_listen* pcb = tcp_listen_pcbs.listen_pcbs; pcb != nullptr; pcb = pcb->next) ++counts.listen;
  return counts;
}

}  // namespace firmware
