// Device Level Ring object 0x47 (CIP Vol 2 ch 5-6; docs/network.md "Ring (DLR)") for a ring node that is
// neither supervisor nor redundant gateway. The values come from the card's ring node through
// DlrProvider, so cip/ does not depend on net/.
//
//   class attributes  1 revision 3, 2 max instance 1, 3 instances 1, 6 max class attribute 7,
//                     7 max instance attribute 12
//   class services    Get_Attributes_All 0x01, Get_Attribute_Single 0x0E
//   instance 1        1 network topology USINT (0 linear, 1 ring), 2 network status USINT (0 normal,
//                     1 ring fault, 2 unexpected loop, 3 partial network fault, 4 rapid fault/restore),
//                     10 active supervisor address STRUCT of IP UDINT, MAC USINT[6],
//                     12 capability flags DWORD = 0x82 (bit 1 beacon-based ring node, bit 7
//                     Flush_Tables frame capable)
//   instance services Get_Attributes_All 0x01, Get_Attribute_Single 0x0E, Set_Attribute_Single 0x10
//
// Attributes 3-9 and 11 belong to supervisor-capable devices and are not implemented by a node (as
// OpENer's DLR object states): Get_Attribute_Single and Set_Attribute_Single answer 0x14 for them.
// Get_Attributes_All still lays out 1-8, 10, 11, 12 (9 is never in it), 54 bytes, the unimplemented ones
// with placeholder values: 3 ring supervisor status 0xFF, 4 ring supervisor config 12 zero bytes,
// 5 ring faults count 0, 6/7 last active node on port 1/2 (10 zero bytes each), 8 participants count
// 0xFFFF, 11 active supervisor precedence (the node's value, 0 before a supervisor is known).
// Set_Attribute_Single on 1, 2, 10 or 12 answers 0x0E (not settable). The supervisor services
// Verify_Fault_Location 0x4B, Clear_Rapid_Faults 0x4C, Restart_Sign_On 0x4D and
// Clear_Gateway_Partial_Fault 0x4E are not supported by a node: 0x08.
#pragma once

#include <cstdint>
#include <span>

#include "base/addresses.h"
#include "cip/object_model.h"

namespace cip {

inline constexpr std::uint16_t kClassDlr = 0x47;
inline constexpr std::uint16_t kDlrClassRevision = 3;

// Capability flags (attribute 12). Announce-based and beacon-based exclude each other.
inline constexpr std::uint32_t kDlrCapabilityAnnounceBased = 0x01;
inline constexpr std::uint32_t kDlrCapabilityBeaconBased = 0x02;
inline constexpr std::uint32_t kDlrCapabilitySupervisor = 0x20;
inline constexpr std::uint32_t kDlrCapabilityRedundantGateway = 0x40;
inline constexpr std::uint32_t kDlrCapabilityFlushTables = 0x80;
inline constexpr std::uint32_t kDlrNodeCapabilities = kDlrCapabilityBeaconBased | kDlrCapabilityFlushTables;

// What the object shows; the firmware fills it from net::DlrRingNode::status().
struct DlrObjectValues {
  std::uint8_t network_topology = 0;  // attribute 1
  std::uint8_t network_status = 0;    // attribute 2
  std::uint32_t supervisor_ip = 0;    // attribute 10, host order (192.168.0.10 = 0xC0A8000A); 0 = none
  base::MacAddress supervisor_mac;    // attribute 10; zeros = none
  std::uint8_t supervisor_precedence = 0;  // attribute 11 (Get_Attributes_All only)
};

class DlrProvider {
 public:
  virtual ~DlrProvider() = default;
  virtual DlrObjectValues DlrValues() const = 0;
};

class DlrObject final : public AttributeHandler {
 public:
  explicit DlrObject(const DlrProvider& dlr);

  CipObject& object() { return object_; }

  std::uint32_t MaxInstance() const override { return 1; }
  std::span<const AttributeSpec> InstanceAttributes(std::uint32_t instance) const override;
  void GetInstanceAttribute(std::uint32_t instance, std::uint16_t id, base::ByteWriter& out) override;

 private:
  const DlrProvider& dlr_;
  AttributeObject object_;
};

}  // namespace cip
