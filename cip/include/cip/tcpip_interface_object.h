// TCP/IP Interface object 0xF5 (manual §4.11, §3.2.2): one instance.
//
//   class attributes  1 revision 1, 2 max instance 1, 3 instances 1, 4 optional attributes
//                     (8, 9, 10, 11), 5 optional services (none), 6 max class attribute 7,
//                     7 max instance attribute 11
//   class services    Get_Attributes_All 0x01, Get_Attribute_Single 0x0E
//   instance          1 status DWORD (bits 0-3: 1 = valid configuration; bit 6: address conflict)
//                     2 configuration capability DWORD 0x9D (BOOTP, DHCP, DHCP host name, settable,
//                       ACD capable; no DNS)
//                     3 configuration control DWORD (set: 0 stored, 1 BOOTP, 2 DHCP = c504)
//                     4 physical link object: 02 00 20 F6 24 01 (Ethernet Link instance 1)
//                     5 interface configuration (set: IP, mask, gateway = c505-c516, name servers,
//                       domain name; reads back the configuration in use)
//                     6 host name STRING (set: = c081-c096, at most 16 characters)
//                     8 TTL USINT (set: 1-255)
//                     9 multicast configuration (set)
//                     10 SelectAcd BOOL (set)
//                     11 LastConflictDetected (set: all zeros clears it)
//   instance services Get_Attributes_All 0x01, Get_Attribute_Single 0x0E, Set_Attribute_Single 0x10
//
// Every set is stored through TcpIpProvider and takes effect at the next reset (§3.2.2). Get_Attributes_All
// returns attributes 1-11 in order with 6 zero bytes for attribute 7 (safety network number, not
// implemented), the way other adapters do, so that the fields after it keep their places.
// §4.11 lists only 8 and 9 as optional and 9 as the highest instance attribute; 10 and 11 exist too
// (§4.11 lists them), so the class attributes name them.
#pragma once

#include <cstdint>
#include <span>

#include "cip/object_model.h"
#include "cip/providers.h"

namespace cip {

// Class attribute 1 (also the EDS's [TCP/IP Interface Class] Revision).
inline constexpr std::uint16_t kTcpIpClassRevision = 1;

inline constexpr std::uint32_t kTcpIpCapabilities = 0x01 | 0x04 | 0x08 | 0x10 | 0x80;

class TcpIpInterfaceObject final : public AttributeHandler {
 public:
  explicit TcpIpInterfaceObject(TcpIpProvider& tcpip);

  CipObject& object() { return object_; }

  std::uint32_t MaxInstance() const override { return 1; }
  std::span<const AttributeSpec> InstanceAttributes(std::uint32_t instance) const override;
  void GetInstanceAttribute(std::uint32_t instance, std::uint16_t id, base::ByteWriter& out) override;
  ServiceStatus SetInstanceAttribute(std::uint32_t instance, std::uint16_t id, base::ByteReader& value) override;

 private:
  ServiceStatus SetConfigurationControl(base::ByteReader& value, TcpIpSettings& settings);
  ServiceStatus SetInterfaceConfiguration(base::ByteReader& value, TcpIpSettings& settings);
  ServiceStatus SetHostName(base::ByteReader& value, TcpIpSettings& settings);
  ServiceStatus SetMulticast(base::ByteReader& value, TcpIpSettings& settings);

  TcpIpProvider& tcpip_;
  AttributeObject object_;
};

// The checks attribute 5 applies (exposed for tests): a usable host address, a contiguous mask, a
// gateway that is 0 or on the subnet, name servers that are 0 or usable hosts.
bool IsValidInterfaceConfiguration(const InterfaceConfiguration& configuration);
// Host name characters: letters, digits, '-' (RFC 1123 labels); empty is allowed.
bool IsValidHostName(std::span<const std::uint8_t> name);

}  // namespace cip
