#include "net/frame_switch.h"

namespace net {
namespace {

constexpr std::size_t kHeaderSize = 14;

base::MacAddress Destination(std::span<const std::uint8_t> frame) {
  base::ByteReader header(frame);
  return base::MacAddress::Read(header);
}

base::MacAddress Source(std::span<const std::uint8_t> frame) {
  base::ByteReader header(frame);
  header.Skip(base::MacAddress::kSize);
  return base::MacAddress::Read(header);
}

// 01-80-C2-00-00-00 .. 0F: IEEE 802.1D reserved addresses, filtered by every bridge.
bool IsBridgeReserved(const base::MacAddress& address) {
  const base::MacAddress::Octets& mac = address.octets();
  return mac[0] == 0x01 && mac[1] == 0x80 && mac[2] == 0xC2 && mac[3] == 0x00 && mac[4] == 0x00 &&
         (mac[5] & 0xF0) == 0x00;
}

}  // namespace

SwitchDelivery FrameSwitch::Ingress(std::span<const std::uint8_t> frame, std::size_t port) {
  SwitchDelivery delivery;
  if (frame.size() < kHeaderSize || port >= port_count_) return delivery;
  const base::MacAddress destination = Destination(frame.first<kHeaderSize>());
  const base::MacAddress source = Source(frame.first<kHeaderSize>());
  if (!source.IsMulticast() && source != own_mac_) Learn(source, port);

  if (destination == own_mac_) {
    delivery.to_card = true;
    return delivery;
  }
  const bool group = destination.IsMulticast();
  delivery.to_card = group;
  if (group && IsBridgeReserved(destination)) return delivery;
  const std::size_t learned_on = group ? kSwitchPorts : PortOf(destination);
  if (learned_on == port) return delivery;  // both stations are on the ingress side
  for (std::size_t out = 0; out < port_count_; ++out) delivery.to_port[out] = out != port;
  return delivery;
}

std::array<bool, kSwitchPorts> FrameSwitch::Egress(std::span<const std::uint8_t> frame) const {
  std::array<bool, kSwitchPorts> out{};
  const std::size_t learned_on =
      frame.size() < kHeaderSize ? kSwitchPorts : PortOf(Destination(frame.first<kHeaderSize>()));
  for (std::size_t i = 0; i < port_count_; ++i) out[i] = learned_on == kSwitchPorts || learned_on == i;
  return out;
}

void FrameSwitch::PortDown(std::size_t port) {
  std::size_t kept = 0;
  for (std::size_t i = 0; i < count_; ++i) {
    if (entries_[i].port != port) entries_[kept++] = entries_[i];
  }
  count_ = kept;
  oldest_ = 0;
}

std::size_t FrameSwitch::PortOf(const base::MacAddress& mac) const {
  // Group addresses are never learned, so they are never found.
  for (std::size_t i = 0; i < count_; ++i) {
    if (entries_[i].mac == mac) return entries_[i].port;
  }
  return kSwitchPorts;
}

void FrameSwitch::Learn(const base::MacAddress& mac, std::size_t port) {
  for (std::size_t i = 0; i < count_; ++i) {
    if (entries_[i].mac == mac) {
      entries_[i].port = static_cast<std::uint8_t>(port);
      return;
    }
  }
  if (count_ < entries_.size()) {
    entries_[count_++] = {mac, static_cast<std::uint8_t>(port)};
    return;
  }
  entries_[oldest_] = {mac, static_cast<std::uint8_t>(port)};
  oldest_ = (oldest_ + 1) % entries_.size();
}

}  // namespace net
