#include "net/arp.h"

namespace net {
namespace {

constexpr std::uint8_t kHardwareLength = 6;
constexpr std::uint8_t kProtocolLength = 4;

}  // namespace

ArpPacket ArpProbe(const MacAddress& own_mac, Ipv4Address probed) {
  return ArpPacket{.destination = kBroadcastMac,
                   .source = own_mac,
                   .operation = ArpOperation::kRequest,
                   .sender_mac = own_mac,
                   .sender_ip = 0,
                   .target_mac = kZeroMac,
                   .target_ip = probed};
}

ArpPacket ArpAnnouncement(const MacAddress& own_mac, Ipv4Address claimed) {
  ArpPacket packet = ArpProbe(own_mac, claimed);
  packet.sender_ip = claimed;
  return packet;
}

void EncodeArpFrame(const ArpPacket& packet, std::span<std::uint8_t, kArpFrameSize> out) {
  StoreMac(packet.destination, out.subspan<0, 6>());
  StoreMac(packet.source, out.subspan<6, 6>());
  StoreBe16(kEtherTypeArp, out.subspan<12, 2>());
  StoreBe16(kArpHardwareEthernet, out.subspan<14, 2>());
  StoreBe16(kEtherTypeIpv4, out.subspan<16, 2>());
  out[18] = kHardwareLength;
  out[19] = kProtocolLength;
  StoreBe16(static_cast<std::uint16_t>(packet.operation), out.subspan<20, 2>());
  StoreMac(packet.sender_mac, out.subspan<22, 6>());
  StoreBe32(packet.sender_ip, out.subspan<28, 4>());
  StoreMac(packet.target_mac, out.subspan<32, 6>());
  StoreBe32(packet.target_ip, out.subspan<38, 4>());
}

ArpFrame EncodeArpFrame(const ArpPacket& packet) {
  ArpFrame frame{};
  EncodeArpFrame(packet, frame);
  return frame;
}

base::Result<ArpPacket> ParseArpFrame(std::span<const std::uint8_t> frame) {
  if (frame.size() < kArpFrameSize) return base::OutOfRange();
  // From here on every field lies in the first 42 bytes, which `arp` proves by its type.
  const std::span<const std::uint8_t, kArpFrameSize> arp = frame.first<kArpFrameSize>();
  if (LoadBe16(arp.subspan<12, 2>()) != kEtherTypeArp) return base::NotFound();
  if (LoadBe16(arp.subspan<14, 2>()) != kArpHardwareEthernet || LoadBe16(arp.subspan<16, 2>()) != kEtherTypeIpv4 ||
      arp[18] != kHardwareLength || arp[19] != kProtocolLength) {
    return base::InvalidArgument();
  }
  const std::uint16_t operation = LoadBe16(arp.subspan<20, 2>());
  if (operation != static_cast<std::uint16_t>(ArpOperation::kRequest) &&
      operation != static_cast<std::uint16_t>(ArpOperation::kReply)) {
    return base::InvalidArgument();
  }
  return ArpPacket{.destination = LoadMac(arp.subspan<0, 6>()),
                   .source = LoadMac(arp.subspan<6, 6>()),
                   .operation = static_cast<ArpOperation>(operation),
                   .sender_mac = LoadMac(arp.subspan<22, 6>()),
                   .sender_ip = LoadBe32(arp.subspan<28, 4>()),
                   .target_mac = LoadMac(arp.subspan<32, 6>()),
                   .target_ip = LoadBe32(arp.subspan<38, 4>())};
}

}  // namespace net
