// QoS object 0x48 (CIP Vol. 2 §5-7): one instance, the DSCP the card writes into the IP header of what it
// sends per traffic class, and whether it sends those frames with an 802.1Q priority tag.
//
//   class attributes  1 revision 1, 2 max instance 1, 3 instances 1, 4 optional attributes (1, 2, 3),
//                     5 optional services (none), 6 max class attribute 7, 7 max instance attribute 8
//   class services    Get_Attributes_All 0x01, Get_Attribute_Single 0x0E
//   instance          1 802.1Q Tag Enable USINT (0 off, 1 on; default 0)
//                     2 DSCP PTP Event 59, 3 DSCP PTP General 47 (kept for a tool; the card has no PTP)
//                     4 DSCP Urgent 55, 5 DSCP Scheduled 47, 6 DSCP High 43, 7 DSCP Low 31 (class 1
//                       productions by the T->O priority of their Forward_Open)
//                     8 DSCP Explicit 27 (everything on TCP and UDP 44818)
//                     all USINT, all Get/Set; a DSCP above 63 or a tag enable above 1 is 0x09
//   instance services Get_Attributes_All 0x01 (attributes 1-8), Get_Attribute_Single 0x0E,
//                     Set_Attribute_Single 0x10
//
// A set is stored (QosProvider) and takes effect at the next reset, as the CIP QoS object and every
// stored setting of the card do (docs/network.md "QoS (DSCP)"); Get reads the stored value back.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "cip/forward_open.h"
#include "cip/object_model.h"
#include "cip/providers.h"

namespace cip {

inline constexpr std::uint16_t kClassQos = 0x48;
// Class attribute 1.
inline constexpr std::uint16_t kQosClassRevision = 1;

class QosObject final : public AttributeHandler {
 public:
  explicit QosObject(QosProvider& qos);

  CipObject& object() { return object_; }

  std::uint32_t MaxInstance() const override { return 1; }
  std::span<const AttributeSpec> InstanceAttributes(std::uint32_t instance) const override;
  void GetInstanceAttribute(std::uint32_t instance, std::uint16_t id, base::ByteWriter& out) override;
  ServiceStatus SetInstanceAttribute(std::uint32_t instance, std::uint16_t id, base::ByteReader& value) override;

 private:
  QosProvider& qos_;
  AttributeObject object_;
};

// The DSCP of a class 1 production whose T->O network connection parameters ask for `priority`.
std::uint8_t DscpForPriority(const QosSettings& settings, ConnectionPriority priority);
// The IPv4 TOS byte of a DSCP (the two ECN bits stay 0).
constexpr std::uint8_t TosOfDscp(std::uint8_t dscp) { return static_cast<std::uint8_t>(dscp << 2); }

// ---- 802.1Q priority tag -----------------------------------------------------------------------------

inline constexpr std::size_t kVlanTagBytes = 4;

// The 802.1D priority (PCP) of a frame whose IPv4 DSCP is `dscp`, or -1 when `dscp` is 0 or none of
// the object's classes: PTP event 7, urgent 6, PTP general, scheduled and high 5, low and explicit 3,
// looked up in that order when two classes share a value.
int PriorityOfDscp(const QosSettings& settings, std::uint8_t dscp);

// Inserts a priority tag (TPID 0x8100, VLAN ID 0, the priority of the frame's DSCP) after the source MAC
// of the Ethernet II frame in buffer[0, length) when tagging is on and the frame is an IPv4 packet of a
// CIP class. Returns the frame's new length: length + 4 when tagged, length when left alone (tagging off,
// not IPv4, already tagged, too short, no room in the buffer).
std::size_t InsertPriorityTag(const QosSettings& settings, std::span<std::uint8_t> buffer, std::size_t length);

}  // namespace cip
