#include "cip/tcpip_interface_object.h"

#include <algorithm>
#include <array>

#include "cip/epath.h"

namespace cip {
namespace {

constexpr std::array<std::uint16_t, 7> kClassAttributes = {1, 2, 3, 4, 5, 6, 7};
constexpr std::array<std::uint16_t, 4> kOptionalAttributes = {8, 9, 10, 11};
constexpr std::array<std::uint8_t, 2> kClassServices = {kServiceGetAttributesAll, kServiceGetAttributeSingle};
constexpr std::array<std::uint8_t, 3> kInstanceServices = {kServiceGetAttributesAll, kServiceGetAttributeSingle,
                                                           kServiceSetAttributeSingle};
constexpr ClassSpec kTcpIpClass = {
    kClassTcpIpInterface, kTcpIpClassRevision, kClassAttributes, kOptionalAttributes, {}, 7, 11, kClassServices, kInstanceServices,
};
constexpr std::array<AttributeSpec, 11> kAttributes = {{
    {1, Access::kGet, true},
    {2, Access::kGet, true},
    {3, Access::kGetSet, true},
    {4, Access::kGet, true},
    {5, Access::kGetSet, true},
    {6, Access::kGetSet, true},
    {7, Access::kGetAllOnly, true},
    {8, Access::kGetSet, true},
    {9, Access::kGetSet, true},
    {10, Access::kGetSet, true},
    {11, Access::kGetSet, true},
}};

constexpr std::uint32_t kStatusConfigured = 0x01;
constexpr std::uint32_t kStatusAcdConflict = 0x40;
constexpr std::uint32_t kStartupMask = 0x0F;
constexpr std::size_t kSafetyNetworkNumberSize = 6;
constexpr std::size_t kLastConflictSize = 1 + 6 + 28;
constexpr std::size_t kMulticastSize = 8;

bool IsUsableHost(std::uint32_t address) {
  const std::uint32_t first_octet = address >> 24;
  return first_octet != 0 && first_octet != 127 && first_octet < 224;
}

bool IsMulticast(std::uint32_t address) { return address >> 28 == 0xE; }

// A CIP STRING with the TCP/IP object's pad byte; 0x13 / 0x15 on a length mismatch, 0x09 when longer
// than `max`.
template <std::size_t N>
ServiceStatus ReadPaddedString(base::ByteReader& in, FixedString<N>& out) {
  const std::uint16_t length = in.U16Le();
  const std::span<const std::uint8_t> text = in.Bytes(length);
  if (length % 2 != 0) in.Skip(1);
  if (!in.ok()) return Error(GeneralStatus::kNotEnoughData);
  if (!in.empty()) return Error(GeneralStatus::kTooMuchData);
  if (!out.Assign(text)) return Error(GeneralStatus::kInvalidAttributeValue);
  return Success();
}

}  // namespace

bool IsValidInterfaceConfiguration(const InterfaceConfiguration& c) {
  // All zero means "no address configured" (the factory state of c505-c516).
  if (c.ip_address == 0 && c.network_mask == 0 && c.gateway == 0) {
    return c.name_server == 0 && c.name_server_2 == 0;
  }
  const std::uint32_t host_bits = ~c.network_mask;
  const bool contiguous_mask = c.network_mask != 0 && (host_bits & (host_bits + 1)) == 0;
  if (!contiguous_mask || host_bits < 3) return false;  // at least two host bits
  if (!IsUsableHost(c.ip_address)) return false;
  const std::uint32_t host = c.ip_address & host_bits;
  if (host == 0 || host == host_bits) return false;  // network or broadcast address
  if (c.gateway != 0) {
    const std::uint32_t gateway_host = c.gateway & host_bits;
    if (!IsUsableHost(c.gateway) || c.gateway == c.ip_address) return false;
    if ((c.gateway & c.network_mask) != (c.ip_address & c.network_mask)) return false;
    if (gateway_host == 0 || gateway_host == host_bits) return false;
  }
  for (std::uint32_t server : {c.name_server, c.name_server_2}) {
    if (server != 0 && !IsUsableHost(server)) return false;
  }
  return true;
}

bool IsValidHostName(std::span<const std::uint8_t> name) {
  return std::all_of(name.begin(), name.end(), [](std::uint8_t c) {
    return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '-';
  });
}

TcpIpInterfaceObject::TcpIpInterfaceObject(TcpIpProvider& tcpip) : tcpip_(tcpip), object_(kTcpIpClass, *this) {}

std::span<const AttributeSpec> TcpIpInterfaceObject::InstanceAttributes(std::uint32_t) const { return kAttributes; }

void TcpIpInterfaceObject::GetInstanceAttribute(std::uint32_t, std::uint16_t id, base::ByteWriter& out) {
  switch (id) {
    case 1: {
      std::uint32_t status = tcpip_.ConfigurationValid() ? kStatusConfigured : 0;
      if (tcpip_.AddressConflictDetected()) status |= kStatusAcdConflict;
      out.U32Le(status);
      break;
    }
    case 2:
      out.U32Le(kTcpIpCapabilities);
      break;
    case 3:
      out.U32Le(static_cast<std::uint32_t>(tcpip_.StoredSettings().startup));
      break;
    case 4: {
      std::array<std::uint8_t, 8> path{};
      base::ByteWriter link(path);
      EncodeLogicalSegment(SegmentKind::kClass, kClassEthernetLink, link);
      EncodeLogicalSegment(SegmentKind::kInstance, 1, link);
      PutSizedPath(link.written(), out);
      break;
    }
    case 5: {
      const InterfaceConfiguration active = tcpip_.ActiveConfiguration();
      out.U32Le(active.ip_address);
      out.U32Le(active.network_mask);
      out.U32Le(active.gateway);
      out.U32Le(active.name_server);
      out.U32Le(active.name_server_2);
      PutPaddedString(active.domain_name.bytes(), out);
      break;
    }
    case 6:
      PutPaddedString(tcpip_.StoredSettings().host_name.bytes(), out);
      break;
    case 7:
      out.Zeros(kSafetyNetworkNumberSize);
      break;
    case 8:
      out.U8(tcpip_.StoredSettings().ttl);
      break;
    case 9: {
      const MulticastConfiguration multicast = tcpip_.StoredSettings().multicast;
      out.U8(multicast.allocation_control);
      out.U8(0);  // reserved
      out.U16Le(multicast.num_mcast);
      out.U32Le(multicast.start_address);
      break;
    }
    case 10:
      out.U8(tcpip_.StoredSettings().select_acd ? 1 : 0);
      break;
    case 11: {
      const AcdConflict conflict = tcpip_.LastConflict();
      out.U8(conflict.acd_activity);
      conflict.remote_mac.Write(out);
      out.Bytes(conflict.arp_pdu);
      break;
    }
    default:
      break;
  }
}

ServiceStatus TcpIpInterfaceObject::SetInstanceAttribute(std::uint32_t, std::uint16_t id, base::ByteReader& value) {
  TcpIpSettings settings = tcpip_.StoredSettings();
  ServiceStatus status;
  switch (id) {
    case 3:
      status = SetConfigurationControl(value, settings);
      break;
    case 5:
      status = SetInterfaceConfiguration(value, settings);
      break;
    case 6:
      status = SetHostName(value, settings);
      break;
    case 8:
      status = ReadExactU8(value, settings.ttl);
      if (status.ok() && settings.ttl == 0) status = Error(GeneralStatus::kInvalidAttributeValue);
      break;
    case 9:
      status = SetMulticast(value, settings);
      break;
    case 10: {
      std::uint8_t select = 0;
      status = ReadExactU8(value, select);
      if (status.ok() && select > 1) status = Error(GeneralStatus::kInvalidAttributeValue);
      settings.select_acd = select == 1;
      break;
    }
    case 11: {
      // Only clearing is possible: the card writes the conflict, a client may only erase it.
      status = ExpectSize(value, kLastConflictSize);
      if (!status.ok()) return status;
      const std::span<const std::uint8_t> bytes = value.Rest();
      if (!std::all_of(bytes.begin(), bytes.end(), [](std::uint8_t b) { return b == 0; })) {
        return Error(GeneralStatus::kInvalidAttributeValue);
      }
      tcpip_.ClearLastConflict();
      return Success();
    }
    default:
      return Error(GeneralStatus::kAttributeNotSettable);
  }
  if (!status.ok()) return status;
  return StoreResult(tcpip_.StoreSettings(settings));
}

ServiceStatus TcpIpInterfaceObject::SetConfigurationControl(base::ByteReader& value, TcpIpSettings& settings) {
  std::uint32_t control = 0;
  const ServiceStatus status = ReadExactU32(value, control);
  if (!status.ok()) return status;
  // Bit 4 (resolve names by DNS) is refused: the card has no resolver. Bits 5-31 are reserved.
  const std::uint32_t startup = control & kStartupMask;
  if ((control & ~kStartupMask) != 0 || startup > static_cast<std::uint32_t>(StartupConfiguration::kDhcp)) {
    return Error(GeneralStatus::kInvalidAttributeValue);
  }
  settings.startup = static_cast<StartupConfiguration>(startup);
  return Success();
}

ServiceStatus TcpIpInterfaceObject::SetInterfaceConfiguration(base::ByteReader& value, TcpIpSettings& settings) {
  // The static configuration only makes sense while the card is to use it (c504 = 0).
  if (settings.startup != StartupConfiguration::kStored) return Error(GeneralStatus::kObjectStateConflict);
  InterfaceConfiguration configuration;
  configuration.ip_address = value.U32Le();
  configuration.network_mask = value.U32Le();
  configuration.gateway = value.U32Le();
  configuration.name_server = value.U32Le();
  configuration.name_server_2 = value.U32Le();
  const ServiceStatus status = ReadPaddedString(value, configuration.domain_name);
  if (!status.ok()) return status;
  if (!IsValidInterfaceConfiguration(configuration)) return Error(GeneralStatus::kInvalidAttributeValue);
  settings.static_configuration = configuration;
  return Success();
}

ServiceStatus TcpIpInterfaceObject::SetHostName(base::ByteReader& value, TcpIpSettings& settings) {
  const ServiceStatus status = ReadPaddedString(value, settings.host_name);
  if (!status.ok()) return status;
  if (!IsValidHostName(settings.host_name.bytes())) return Error(GeneralStatus::kInvalidAttributeValue);
  return Success();
}

ServiceStatus TcpIpInterfaceObject::SetMulticast(base::ByteReader& value, TcpIpSettings& settings) {
  const ServiceStatus size = ExpectSize(value, kMulticastSize);
  if (!size.ok()) return size;
  MulticastConfiguration multicast;
  multicast.allocation_control = value.U8();
  const std::uint8_t reserved = value.U8();
  multicast.num_mcast = value.U16Le();
  multicast.start_address = value.U32Le();
  bool valid = reserved == 0;
  if (multicast.allocation_control == 0) {
    valid = valid && multicast.num_mcast == 0 && multicast.start_address == 0;
  } else if (multicast.allocation_control == 1) {
    const std::uint32_t last = multicast.start_address + multicast.num_mcast - 1U;
    valid = valid && multicast.num_mcast >= 1 && IsMulticast(multicast.start_address) && IsMulticast(last) &&
            last >= multicast.start_address && (multicast.start_address >> 8) != 0xE00000;  // not 224.0.0.x
  } else {
    valid = false;
  }
  if (!valid) return Error(GeneralStatus::kInvalidAttributeValue);
  settings.multicast = multicast;
  return Success();
}

}  // namespace cip
