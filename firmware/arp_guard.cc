#include "arp_guard.h"

#include <algorithm>

namespace firmware {

void ArpGuard::SetIdentity(const base::MacAddress& mac, base::Ipv4Address address) {
  mac_ = mac;
  address_ = address;
}

ArpGuard::Verdict ArpGuard::Inspect(std::span<const std::uint8_t> frame, const ArpCacheQuery& cache,
                                    std::uint32_t now_ms) {
  if (address_.IsUnspecified()) return Verdict::kPass;
  // Not ARP for IPv4 over Ethernet, cut short, or another operation: lwIP's to ignore or use.
  const base::Result<net::ArpPacket> parsed = net::ParseArpFrame(frame);
  if (!parsed.ok()) return Verdict::kPass;
  const net::ArpPacket& arp = *parsed;
  // Only frames lwIP would learn from need a decision: addressed to us, from a real sender.
  if (arp.target_ip != address_ || arp.sender_ip.IsUnspecified() || arp.sender_ip == address_) return Verdict::kPass;
  if (cache.Has(arp.sender_ip) || IsAwaited(arp.sender_ip, now_ms)) return Verdict::kPass;
  if (arp.operation == net::ArpOperation::kReply) {
    ++counters_.dropped;
    return Verdict::kDrop;
  }
  // The reply lwIP would send (etharp_raw), without the cache entry.
  net::EncodeArpFrame(net::ArpPacket{.destination = arp.sender_mac,
                                     .source = mac_,
                                     .operation = net::ArpOperation::kReply,
                                     .sender_mac = mac_,
                                     .sender_ip = address_,
                                     .target_mac = arp.sender_mac,
                                     .target_ip = arp.sender_ip},
                      reply_);
  ++counters_.answered;
  return Verdict::kAnswer;
}

void ArpGuard::NoteSent(std::span<const std::uint8_t> frame, std::uint32_t now_ms) {
  if (address_.IsUnspecified()) return;
  const base::Result<net::ArpPacket> parsed = net::ParseArpFrame(frame);
  // Only the card's own requests await a reply for the cache (an ACD probe has sender 0).
  if (!parsed.ok() || parsed->operation != net::ArpOperation::kRequest || parsed->sender_ip != address_) return;
  const base::Ipv4Address target = parsed->target_ip;
  // The entry of that address, else a free one, else the one asked for longest ago.
  Awaited* slot = nullptr;
  for (Awaited& awaited : awaited_) {
    if (awaited.address == target) {
      slot = &awaited;
      break;
    }
    if (slot == nullptr || (!slot->address.IsUnspecified() &&
                            (awaited.address.IsUnspecified() || now_ms - awaited.sent_ms > now_ms - slot->sent_ms))) {
      slot = &awaited;
    }
  }
  *slot = Awaited{target, now_ms};
}

bool ArpGuard::IsAwaited(base::Ipv4Address address, std::uint32_t now_ms) const {
  return std::any_of(awaited_.begin(), awaited_.end(),
                     [&](const Awaited& a) { return a.address == address && now_ms - a.sent_ms < kAwaitMs; });
}

}  // namespace firmware
