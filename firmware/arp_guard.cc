#include "arp_guard.h"

#include <algorithm>

namespace firmware {
namespace {

constexpr std::uint16_t kEtherTypeArp = 0x0806;
constexpr std::uint16_t kHardwareEthernet = 1;
constexpr std::uint16_t kProtocolIpv4 = 0x0800;
constexpr std::uint16_t kOpRequest = 1;
constexpr std::uint16_t kOpReply = 2;

// Offsets in an Ethernet frame carrying ARP for IPv4 over Ethernet.
constexpr std::size_t kEtherType = 12;
constexpr std::size_t kArp = 14;
constexpr std::size_t kOperation = kArp + 6;
constexpr std::size_t kSenderMac = kArp + 8;
constexpr std::size_t kSenderIp = kArp + 14;
constexpr std::size_t kTargetMac = kArp + 18;
constexpr std::size_t kTargetIp = kArp + 24;

std::uint16_t U16(std::span<const std::uint8_t> bytes, std::size_t at) {
  return static_cast<std::uint16_t>(bytes[at] << 8 | bytes[at + 1]);
}
std::uint32_t U32(std::span<const std::uint8_t> bytes, std::size_t at) {
  return static_cast<std::uint32_t>(bytes[at]) << 24 | static_cast<std::uint32_t>(bytes[at + 1]) << 16 |
         static_cast<std::uint32_t>(bytes[at + 2]) << 8 | bytes[at + 3];
}
void PutU16(std::span<std::uint8_t> bytes, std::size_t at, std::uint16_t value) {
  bytes[at] = static_cast<std::uint8_t>(value >> 8);
  bytes[at + 1] = static_cast<std::uint8_t>(value);
}
void PutU32(std::span<std::uint8_t> bytes, std::size_t at, std::uint32_t value) {
  for (std::size_t i = 0; i < 4; ++i) bytes[at + i] = static_cast<std::uint8_t>(value >> (24 - 8 * i));
}

// ARP for IPv4 over Ethernet, whole (a longer frame is padding).
bool IsIpv4Arp(std::span<const std::uint8_t> frame) {
  return frame.size() >= ArpGuard::kArpFrameBytes && U16(frame, kEtherType) == kEtherTypeArp &&
         U16(frame, kArp) == kHardwareEthernet && U16(frame, kArp + 2) == kProtocolIpv4 && frame[kArp + 4] == 6 &&
         frame[kArp + 5] == 4;
}

}  // namespace

void ArpGuard::SetIdentity(const std::array<std::uint8_t, 6>& mac, std::uint32_t address) {
  mac_ = mac;
  address_ = address;
}

ArpGuard::Verdict ArpGuard::Inspect(std::span<const std::uint8_t> frame, const ArpCacheQuery& cache,
                                    std::uint32_t now_ms) {
  if (address_ == 0 || !IsIpv4Arp(frame)) return Verdict::kPass;
  const std::uint16_t operation = U16(frame, kOperation);
  const std::uint32_t sender = U32(frame, kSenderIp);
  const std::uint32_t target = U32(frame, kTargetIp);
  // Only frames lwIP would learn from need a decision: addressed to us, from a real sender.
  if (target != address_ || sender == 0 || sender == address_) return Verdict::kPass;
  if (cache.Has(sender) || IsAwaited(sender, now_ms)) return Verdict::kPass;
  if (operation == kOpReply) {
    ++counters_.dropped;
    return Verdict::kDrop;
  }
  if (operation != kOpRequest) return Verdict::kPass;
  // The reply lwIP would send (etharp_raw), without the cache entry.
  const std::span<std::uint8_t> out(reply_);
  std::copy_n(frame.begin() + kSenderMac, 6, out.begin());  // destination: the asker
  std::copy(mac_.begin(), mac_.end(), out.begin() + 6);
  PutU16(out, kEtherType, kEtherTypeArp);
  PutU16(out, kArp, kHardwareEthernet);
  PutU16(out, kArp + 2, kProtocolIpv4);
  out[kArp + 4] = 6;
  out[kArp + 5] = 4;
  PutU16(out, kOperation, kOpReply);
  std::copy(mac_.begin(), mac_.end(), out.begin() + kSenderMac);
  PutU32(out, kSenderIp, address_);
  std::copy_n(frame.begin() + kSenderMac, 6, out.begin() + kTargetMac);
  PutU32(out, kTargetIp, sender);
  ++counters_.answered;
  return Verdict::kAnswer;
}

void ArpGuard::NoteSent(std::span<const std::uint8_t> frame, std::uint32_t now_ms) {
  if (address_ == 0 || !IsIpv4Arp(frame) || U16(frame, kOperation) != kOpRequest) return;
  if (U32(frame, kSenderIp) != address_) return;  // an ACD probe (sender 0) awaits no reply into the cache
  const std::uint32_t target = U32(frame, kTargetIp);
  // The entry of that address, else a free one, else the one asked for longest ago.
  Awaited* slot = nullptr;
  for (Awaited& awaited : awaited_) {
    if (awaited.address == target) {
      slot = &awaited;
      break;
    }
    if (slot == nullptr || (slot->address != 0 && (awaited.address == 0 || now_ms - awaited.sent_ms >
                                                                               now_ms - slot->sent_ms))) {
      slot = &awaited;
    }
  }
  *slot = Awaited{target, now_ms};
}

bool ArpGuard::IsAwaited(std::uint32_t address, std::uint32_t now_ms) const {
  return std::any_of(awaited_.begin(), awaited_.end(),
                     [&](const Awaited& a) { return a.address == address && now_ms - a.sent_ms < kAwaitMs; });
}

}  // namespace firmware
