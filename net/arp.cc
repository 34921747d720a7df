#include "net/arp.h"

namespace net {
namespace {

constexpr std::uint8_t kHardwareLength = 6;
constexpr std::uint8_t kProtocolLength = 4;

}  // namespace

ArpPacket ArpProbe(const base::MacAddress& own_mac, base::Ipv4Address probed) {
  return ArpPacket{.destination = base::kBroadcastMac,
                   .source = own_mac,
                   .operation = ArpOperation::kRequest,
                   .sender_mac = own_mac,
                   .sender_ip = base::Ipv4Address(),
                   .target_mac = base::kZeroMac,
                   .target_ip = probed};
}

ArpPacket ArpAnnouncement(const base::MacAddress& own_mac, base::Ipv4Address claimed) {
  ArpPacket packet = ArpProbe(own_mac, claimed);
  packet.sender_ip = claimed;
  return packet;
}

void EncodeArpFrame(const ArpPacket& packet, std::span<std::uint8_t, kArpFrameSize> out) {
  // 42 bytes into 42: cannot fail.
  base::ByteWriter writer(out);
  packet.destination.Write(writer);
  packet.source.Write(writer);
  writer.U16Be(kEtherTypeArp);
  writer.U16Be(kArpHardwareEthernet);
  writer.U16Be(kEtherTypeIpv4);
  writer.U8(kHardwareLength);
  writer.U8(kProtocolLength);
  writer.U16Be(static_cast<std::uint16_t>(packet.operation));
  packet.sender_mac.Write(writer);
  packet.sender_ip.Write(writer);
  packet.target_mac.Write(writer);
  packet.target_ip.Write(writer);
}

ArpFrame EncodeArpFrame(const ArpPacket& packet) {
  ArpFrame frame{};
  EncodeArpFrame(packet, frame);
  return frame;
}

base::Result<ArpPacket> ParseArpFrame(std::span<const std::uint8_t> frame) {
  if (frame.size() < kArpFrameSize) return base::OutOfRange();
  // Every field lies in the first 42 bytes, which are there: the reader cannot fail.
  base::ByteReader arp(frame.first(kArpFrameSize));
  ArpPacket packet;
  packet.destination = base::MacAddress::Read(arp);
  packet.source = base::MacAddress::Read(arp);
  const std::uint16_t ether_type = arp.U16Be();
  const std::uint16_t hardware = arp.U16Be();
  const std::uint16_t protocol = arp.U16Be();
  const std::uint8_t hardware_length = arp.U8();
  const std::uint8_t protocol_length = arp.U8();
  const std::uint16_t operation = arp.U16Be();
  packet.sender_mac = base::MacAddress::Read(arp);
  packet.sender_ip = base::Ipv4Address::Read(arp);
  packet.target_mac = base::MacAddress::Read(arp);
  packet.target_ip = base::Ipv4Address::Read(arp);
  if (ether_type != kEtherTypeArp) return base::NotFound();
  if (hardware != kArpHardwareEthernet || protocol != kEtherTypeIpv4 || hardware_length != kHardwareLength ||
      protocol_length != kProtocolLength) {
    return base::InvalidArgument();
  }
  if (operation != static_cast<std::uint16_t>(ArpOperation::kRequest) &&
      operation != static_cast<std::uint16_t>(ArpOperation::kReply)) {
    return base::InvalidArgument();
  }
  packet.operation = static_cast<ArpOperation>(operation);
  return packet;
}

}  // namespace net
