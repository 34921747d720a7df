#include "net/lldp_frame.h"

#include "base/byte_reader.h"
#include "base/byte_writer.h"

namespace net {
namespace {

enum TlvType : std::uint8_t {
  kEnd = 0,
  kChassisId = 1,
  kPortId = 2,
  kTtl = 3,
  kPortDescription = 4,
  kSystemName = 5,
  kSystemDescription = 6,
  kSystemCapabilities = 7,
  kManagementAddress = 8,
};

constexpr std::size_t kMaxTlvLength = 511;  // 9 bits
constexpr std::size_t kMaxStringLength = 255;
constexpr std::uint8_t kAddressFamilyIpv4 = 1;   // IANA address family numbers
constexpr std::uint8_t kInterfaceIfIndex = 2;    // Management Address interface numbering subtype

void TlvHeader(base::ByteWriter& out, std::uint8_t type, std::size_t length) {
  out.U16Be(static_cast<std::uint16_t>(std::size_t{type} << 9 | (length & kMaxTlvLength)));
}

std::span<const std::uint8_t> AsBytes(std::string_view text) {
  const std::size_t size = text.size() < kMaxStringLength ? text.size() : kMaxStringLength;
  return {reinterpret_cast<const std::uint8_t*>(text.data()), size};
}

void StringTlv(base::ByteWriter& out, std::uint8_t type, std::string_view text) {
  const std::span<const std::uint8_t> bytes = AsBytes(text);
  TlvHeader(out, type, bytes.size());
  out.Bytes(bytes);
}

// A Chassis ID or Port ID: 1 subtype byte and 1..255 ID bytes.
bool ReadId(base::ByteReader& value, LldpId& id) {
  if (value.remaining() < 2 || value.remaining() > 256) return false;
  id.subtype = value.U8();
  id.id.Assign(value.Rest());
  return true;
}

// Management Address (802.1AB §8.5.9): address string length (subtype + address, 2..32), subtype,
// address, interface numbering subtype, interface number (4), OID string length (0..128), OID.
bool ReadManagement(base::ByteReader value, base::Ipv4Address& address) {
  const std::uint8_t string_length = value.U8();
  if (string_length < 2 || string_length > 32) return false;
  base::ByteReader string = value.Take(string_length);
  value.Skip(1 + 4);
  const std::uint8_t oid_length = value.U8();
  if (oid_length > 128) return false;
  value.Skip(oid_length);
  if (!value.ok() || !value.empty()) return false;
  if (string.U8() == kAddressFamilyIpv4 && string.remaining() == base::Ipv4Address::kSize) {
    address = base::Ipv4Address::Read(string);
  }
  return true;
}

}  // namespace

base::Result<std::size_t> BuildLldpFrame(const LldpAdvert& advert, std::span<std::uint8_t> out) {
  base::ByteWriter writer(out);
  kLldpNearestBridge.Write(writer);
  advert.mac.Write(writer);
  writer.U16Be(kEtherTypeLldp);

  TlvHeader(writer, kChassisId, 1 + base::MacAddress::kSize);
  writer.U8(kLldpChassisMac);
  advert.mac.Write(writer);
  const std::span<const std::uint8_t> port_id = AsBytes(advert.port_id);
  TlvHeader(writer, kPortId, 1 + port_id.size());
  writer.U8(kLldpPortLocal);
  writer.Bytes(port_id);
  TlvHeader(writer, kTtl, 2);
  writer.U16Be(advert.ttl_seconds);

  StringTlv(writer, kPortDescription, advert.port_description);
  StringTlv(writer, kSystemName, advert.system_name);
  StringTlv(writer, kSystemDescription, advert.system_description);
  TlvHeader(writer, kSystemCapabilities, 4);
  writer.U16Be(kLldpCapabilityBridge);  // capabilities the card has ...
  writer.U16Be(kLldpCapabilityBridge);  // ... and those enabled
  if (!advert.management.IsUnspecified()) {
    TlvHeader(writer, kManagementAddress, 1 + 1 + base::Ipv4Address::kSize + 1 + 4 + 1);
    writer.U8(1 + base::Ipv4Address::kSize);
    writer.U8(kAddressFamilyIpv4);
    advert.management.Write(writer);
    writer.U8(kInterfaceIfIndex);
    writer.U32Be(advert.interface_number);
    writer.U8(0);  // no OID
  }
  TlvHeader(writer, kEnd, 0);
  return writer.Finish();
}

bool IsLldpFrame(std::span<const std::uint8_t> frame) {
  base::ByteReader reader(frame);
  const base::MacAddress destination = base::MacAddress::Read(reader);
  reader.Skip(base::MacAddress::kSize);
  const std::uint16_t ether_type = reader.U16Be();
  return reader.ok() && destination == kLldpNearestBridge && ether_type == kEtherTypeLldp;
}

base::Result<LldpNeighbourInfo> ParseLldpFrame(std::span<const std::uint8_t> frame) {
  if (!IsLldpFrame(frame)) return base::NotFound();
  base::ByteReader reader(frame);
  reader.Skip(2 * base::MacAddress::kSize + 2);

  LldpNeighbourInfo info;
  bool have_name = false;
  bool have_description = false;
  bool have_management = false;
  std::size_t index = 0;
  for (; !reader.empty(); ++index) {
    const std::uint16_t header = reader.U16Be();
    const auto type = static_cast<std::uint8_t>(header >> 9);
    base::ByteReader value = reader.Take(header & kMaxTlvLength);
    if (!reader.ok()) return base::DataLoss();
    // The mandatory three: exactly once each, first, in order.
    const bool mandatory = type >= kChassisId && type <= kTtl;
    if (index < 3 ? static_cast<std::size_t>(type) != index + 1 : mandatory) return base::DataLoss();
    switch (type) {
      case kEnd:
        if (!value.empty()) return base::DataLoss();
        return info;
      case kChassisId:
        if (!ReadId(value, info.chassis)) return base::DataLoss();
        break;
      case kPortId:
        if (!ReadId(value, info.port)) return base::DataLoss();
        break;
      case kTtl:
        if (value.remaining() != 2) return base::DataLoss();
        info.ttl_seconds = value.U16Be();
        break;
      case kPortDescription:
        if (!have_description) info.port_description.Assign(value.Rest());
        have_description = true;
        break;
      case kSystemName:
        if (!have_name) info.system_name.Assign(value.Rest());
        have_name = true;
        break;
      case kManagementAddress: {
        base::Ipv4Address address;
        if (!ReadManagement(value, address)) return base::DataLoss();
        if (!have_management && !address.IsUnspecified()) {
          info.management = address;
          have_management = true;
        }
        break;
      }
      default:
        break;  // skipped by its length
    }
  }
  // The frame ended without an End TLV: accepted if the mandatory TLVs were all there.
  if (index < 3) return base::DataLoss();
  return info;
}

}  // namespace net
