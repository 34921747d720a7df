// Port object 0xF4 (manual §4.10): one instance, the card's EtherNet/IP port.
//
//   class attributes  1 revision 1, 2 max instance 1, 3 instances 1, 6 max class attribute 9,
//                     7 max instance attribute 7, 8 entry port (1: every request enters through the
//                     one port), 9 all ports (port type and number of instance 0 and 1:
//                     00 00 00 00 | 00 00 02 00)
//   class services    Get_Attributes_All 0x01, Get_Attribute_Single 0x0E
//   instance          1 port type 0, 2 port number 2, 3 link object (02 00 20 F5 24 01: the TCP/IP
//                     Interface object), 4 port name "EtherNet/IP", 7 node address (a port segment:
//                     port 2, the IP address in use as text, e.g. 12 09 "10.0.2.15" 00)
//   instance services Get_Attributes_All 0x01, Get_Attribute_Single 0x0E
//
// §4.10's note calls the "00 00 02 00" entry of attribute 9 "port type = 2"; its bytes, read as two
// UINTs, are type 0 and number 2, which is what attributes 1 and 2 say. The bytes are followed.
#pragma once

#include <cstdint>
#include <span>

#include "cip/object_model.h"
#include "cip/providers.h"

namespace cip {

inline constexpr std::uint16_t kPortType = 0;
inline constexpr std::uint16_t kPortNumber = 2;

class PortObject final : public AttributeHandler {
 public:
  explicit PortObject(const TcpIpProvider& tcpip);

  CipObject& object() { return object_; }

  std::uint32_t MaxInstance() const override { return 1; }
  std::span<const AttributeSpec> InstanceAttributes(std::uint32_t instance) const override;
  void GetInstanceAttribute(std::uint32_t instance, std::uint16_t id, base::ByteWriter& out) override;
  void GetClassAttribute(std::uint16_t id, base::ByteWriter& out) override;

 private:
  const TcpIpProvider& tcpip_;
  AttributeObject object_;
};

// "10.0.2.15" for 0x0A00020F into `out`; returns the number of characters (at most 15).
std::size_t FormatIpv4(std::uint32_t address, std::span<std::uint8_t, 15> out);

}  // namespace cip
