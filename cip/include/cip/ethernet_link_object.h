// Ethernet Link object 0xF6 (manual §4.12): instance 1 is port L ("Left"), instance 2 port R ("Right").
//
//   class attributes  1 revision 3, 2 max instance 2, 3 instances 2, 6 max class attribute 7,
//                     7 max instance attribute 10
//   class services    Get_Attributes_All 0x01, Get_Attribute_Single 0x0E
//   instance          1 interface speed UDINT (0, 10, 100), 2 interface flags DWORD (bit 0 link,
//                     1 full duplex, 2-4 negotiation status, 5 manual setting requires reset = 1,
//                     6 local hardware fault), 3 physical address (the card's one MAC), 4 interface
//                     counters (11 UDINT), 5 media counters (12 UDINT), 6 interface control (WORD
//                     control bits, UINT forced speed; settable = c501), 7 interface type 2 (twisted
//                     pair), 10 interface label "Left" / "Right"
//   instance services Get_Attributes_All 0x01, Get_Attribute_Single 0x0E, Set_Attribute_Single 0x10,
//                     Get_and_Clear 0x4C (attributes 4 and 5; any other attribute: 0x14)
//
// §4.12's table for instance 2 leaves out attributes 4 and 5 while offering Get_and_Clear for them;
// both instances have them (NET-3: per-port counters). Interface control is the card's one rate setting
// c501, so setting it on either instance sets both, after a reset (flags bit 5 is always 1).
// Attribute 6 set: control bits 0x0001 (auto-negotiate) with speed 0, or bit 0 clear with speed 10 or
// 100 and bit 1 the duplex (1 full); anything else is 0x09.
#pragma once

#include <cstdint>
#include <span>

#include "cip/object_model.h"
#include "cip/providers.h"

namespace cip {

// Class attribute 1 (also the EDS's [Ethernet Link Class] Revision).
inline constexpr std::uint16_t kEthernetLinkClassRevision = 3;
// One instance per port of the card's switch (Port 1, Port 2).
inline constexpr std::uint32_t kEthernetLinkInstances = 2;

class EthernetLinkObject final : public AttributeHandler {
 public:
  EthernetLinkObject(const DeviceInfoProvider& device, EthernetLinkProvider& links);

  CipObject& object() { return object_; }

  std::uint32_t MaxInstance() const override { return kEthernetLinkInstances; }
  std::span<const AttributeSpec> InstanceAttributes(std::uint32_t instance) const override;
  void GetInstanceAttribute(std::uint32_t instance, std::uint16_t id, base::ByteWriter& out) override;
  ServiceStatus SetInstanceAttribute(std::uint32_t instance, std::uint16_t id, base::ByteReader& value) override;
  ServiceStatus ExecuteOther(const ServiceRequest& request, base::ByteWriter& reply) override;

 private:
  const DeviceInfoProvider& device_;
  EthernetLinkProvider& links_;
  AttributeObject object_;
};

std::uint32_t EncodeInterfaceFlags(const LinkState& state);

}  // namespace cip
