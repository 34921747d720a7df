#include "cip/qos_object.h"

#include <algorithm>
#include <array>

namespace cip {
namespace {

constexpr std::array<std::uint16_t, 7> kClassAttributes = {1, 2, 3, 4, 5, 6, 7};
// Attribute 1 is for devices that can tag, 2 and 3 for devices with PTP; 4-8 are required.
constexpr std::array<std::uint16_t, 3> kOptionalAttributes = {1, 2, 3};
constexpr std::array<std::uint8_t, 2> kClassServices = {kServiceGetAttributesAll, kServiceGetAttributeSingle};
constexpr std::array<std::uint8_t, 3> kInstanceServices = {kServiceGetAttributesAll, kServiceGetAttributeSingle,
                                                           kServiceSetAttributeSingle};
constexpr ClassSpec kQosClass = {
    kClassQos, kQosClassRevision, kClassAttributes, kOptionalAttributes, {}, 7, kQosAttributes,
    kClassServices, kInstanceServices,
};
constexpr std::array<AttributeSpec, kQosAttributes> kAttributes = [] {
  std::array<AttributeSpec, kQosAttributes> attributes = GettableAttributes<kQosAttributes>();
  for (AttributeSpec& attribute : attributes) attribute.access = Access::kGetSet;
  return attributes;
}();

constexpr std::uint8_t kMaxDscp = 63;
constexpr std::uint16_t kEtherTypeIpv4 = 0x0800;
constexpr std::uint16_t kEtherTypeVlan = 0x8100;
constexpr std::size_t kMacAddressesBytes = 12;
constexpr std::size_t kIpv4TosOffset = 14 + 1;

// The classes a tag is looked up for, in the order that decides when two share a DSCP, with the 802.1D
// priority each maps to.
struct TaggedClass {
  QosAttribute dscp;
  std::uint8_t priority;
};
constexpr std::array<TaggedClass, 7> kTaggedClasses = {{
    {QosAttribute::kDscpPtpEvent, 7},
    {QosAttribute::kDscpUrgent, 6},
    {QosAttribute::kDscpPtpGeneral, 5},
    {QosAttribute::kDscpScheduled, 5},
    {QosAttribute::kDscpHigh, 5},
    {QosAttribute::kDscpLow, 3},
    {QosAttribute::kDscpExplicit, 3},
}};

// The EtherType of a frame of `length` bytes in `buffer` (0 when it has none).
std::uint16_t EtherType(std::span<const std::uint8_t> buffer, std::size_t length) {
  base::ByteReader in(buffer.first(std::min(length, buffer.size())));
  in.Skip(kMacAddressesBytes);
  const std::uint16_t type = in.U16Be();
  return in.ok() ? type : 0;
}

}  // namespace

QosObject::QosObject(QosProvider& qos) : qos_(qos), object_(kQosClass, *this) {}

std::span<const AttributeSpec> QosObject::InstanceAttributes(std::uint32_t) const { return kAttributes; }

void QosObject::GetInstanceAttribute(std::uint32_t, std::uint16_t id, base::ByteWriter& out) {
  out.U8(qos_.StoredQos()[static_cast<QosAttribute>(id)]);
}

ServiceStatus QosObject::SetInstanceAttribute(std::uint32_t, std::uint16_t id, base::ByteReader& value) {
  std::uint8_t wanted = 0;
  const ServiceStatus status = ReadExactU8(value, wanted);
  if (!status.ok()) return status;
  const auto attribute = static_cast<QosAttribute>(id);
  const std::uint8_t limit = attribute == QosAttribute::kTagEnable ? 1 : kMaxDscp;
  if (wanted > limit) return Error(GeneralStatus::kInvalidAttributeValue);
  QosSettings settings = qos_.StoredQos();
  settings.values[id - 1U] = wanted;
  return StoreResult(qos_.StoreQos(settings));
}

std::uint8_t DscpForPriority(const QosSettings& settings, ConnectionPriority priority) {
  switch (priority) {
    case ConnectionPriority::kUrgent:
      return settings[QosAttribute::kDscpUrgent];
    case ConnectionPriority::kScheduled:
      return settings[QosAttribute::kDscpScheduled];
    case ConnectionPriority::kHigh:
      return settings[QosAttribute::kDscpHigh];
    case ConnectionPriority::kLow:
      break;
  }
  return settings[QosAttribute::kDscpLow];
}

int PriorityOfDscp(const QosSettings& settings, std::uint8_t dscp) {
  if (dscp == 0) return -1;  // Modbus TCP, HTTP and everything else the card sends unmarked
  const auto* found = std::find_if(kTaggedClasses.begin(), kTaggedClasses.end(),
                                   [&](const TaggedClass& c) { return settings[c.dscp] == dscp; });
  return found == kTaggedClasses.end() ? -1 : found->priority;
}

std::size_t InsertPriorityTag(const QosSettings& settings, std::span<std::uint8_t> buffer, std::size_t length) {
  if (!settings.tag_enabled() || length > buffer.size() || length <= kIpv4TosOffset ||
      buffer.size() - length < kVlanTagBytes || EtherType(buffer, length) != kEtherTypeIpv4) {
    return length;
  }
  const int priority = PriorityOfDscp(settings, static_cast<std::uint8_t>(buffer[kIpv4TosOffset] >> 2));
  if (priority < 0) return length;
  std::copy_backward(buffer.begin() + kMacAddressesBytes, buffer.begin() + static_cast<std::ptrdiff_t>(length),
                     buffer.begin() + static_cast<std::ptrdiff_t>(length + kVlanTagBytes));
  // TCI: priority in bits 15-13, DEI 0, VLAN ID 0 (a priority tag, IEEE 802.1Q §9.6).
  const std::array<std::uint8_t, kVlanTagBytes> tag = {kEtherTypeVlan >> 8, kEtherTypeVlan & 0xFF,
                                                       static_cast<std::uint8_t>(priority << 5), 0x00};
  std::copy(tag.begin(), tag.end(), buffer.begin() + kMacAddressesBytes);
  return length + kVlanTagBytes;
}

}  // namespace cip
