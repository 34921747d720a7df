#include "cip/ethernet_link_object.h"

#include <array>
#include <string_view>

namespace cip {
namespace {

// 4 and 5 (empty lists) are present so that class Get_Attributes_All has the standard layout.
constexpr std::array<std::uint16_t, 7> kClassAttributes = {1, 2, 3, 4, 5, 6, 7};
constexpr std::array<std::uint8_t, 2> kClassServices = {kServiceGetAttributesAll, kServiceGetAttributeSingle};
constexpr std::array<std::uint8_t, 4> kInstanceServices = {kServiceGetAttributesAll, kServiceGetAttributeSingle,
                                                           kServiceSetAttributeSingle, kServiceGetAndClear};
constexpr ClassSpec kEthernetLinkClass = {
    kClassEthernetLink, kEthernetLinkClassRevision, kClassAttributes, {}, {}, 7, 10, kClassServices, kInstanceServices,
};
constexpr std::array<AttributeSpec, 10> kAttributes = {{
    {1, Access::kGet, true},
    {2, Access::kGet, true},
    {3, Access::kGet, true},
    {4, Access::kGet, true},
    {5, Access::kGet, true},
    {6, Access::kGetSet, true},
    {7, Access::kGet, true},
    {8, Access::kGet, true},
    {9, Access::kGet, true},
    {10, Access::kGet, true},
}};

constexpr std::uint16_t kAttributeInterfaceCounters = 4;
constexpr std::uint16_t kAttributeMediaCounters = 5;
constexpr std::uint8_t kInterfaceTypeTwistedPair = 2;
constexpr std::uint8_t kInterfaceStateEnabled = 1;  // attribute 8: enabled, ready to send and receive
constexpr std::uint8_t kAdminStateEnabled = 1;      // attribute 9: the card never disables a port
constexpr std::uint32_t kFlagLinkUp = 0x01;
constexpr std::uint32_t kFlagFullDuplex = 0x02;
constexpr std::uint32_t kFlagManualSettingRequiresReset = 0x20;
constexpr std::uint32_t kFlagLocalHardwareFault = 0x40;
constexpr std::uint16_t kControlAutoNegotiate = 0x0001;
constexpr std::uint16_t kControlFullDuplex = 0x0002;

LinkPort PortOf(std::uint32_t instance) { return instance == 2 ? LinkPort::kRight : LinkPort::kLeft; }

void PutCounters(const InterfaceCounters& c, base::ByteWriter& out) {
  for (std::uint32_t value : {c.in_octets, c.in_ucast_packets, c.in_nucast_packets, c.in_discards, c.in_errors,
                              c.in_unknown_protos, c.out_octets, c.out_ucast_packets, c.out_nucast_packets,
                              c.out_discards, c.out_errors}) {
    out.U32Le(value);
  }
}

void PutMedia(const MediaCounters& m, base::ByteWriter& out) {
  for (std::uint32_t value : {m.alignment_errors, m.fcs_errors, m.single_collisions, m.multiple_collisions,
                              m.sqe_test_errors, m.deferred_transmissions, m.late_collisions,
                              m.excessive_collisions, m.mac_transmit_errors, m.carrier_sense_errors,
                              m.frame_too_long, m.mac_receive_errors}) {
    out.U32Le(value);
  }
}

void PutInterfaceControl(LinkSetting setting, base::ByteWriter& out) {
  switch (setting) {
    case LinkSetting::kAuto:
      out.U16Le(kControlAutoNegotiate);
      out.U16Le(0);
      return;
    case LinkSetting::k10Full:
      out.U16Le(kControlFullDuplex);
      out.U16Le(10);
      return;
    case LinkSetting::k10Half:
      out.U16Le(0);
      out.U16Le(10);
      return;
    case LinkSetting::k100Full:
      out.U16Le(kControlFullDuplex);
      out.U16Le(100);
      return;
    case LinkSetting::k100Half:
      out.U16Le(0);
      out.U16Le(100);
      return;
  }
}

}  // namespace

std::uint32_t EncodeInterfaceFlags(const LinkState& state) {
  std::uint32_t flags = kFlagManualSettingRequiresReset;
  if (state.up) flags |= kFlagLinkUp;
  if (state.full_duplex) flags |= kFlagFullDuplex;
  flags |= static_cast<std::uint32_t>(state.negotiation) << 2;
  if (state.hardware_fault) flags |= kFlagLocalHardwareFault;
  return flags;
}

EthernetLinkObject::EthernetLinkObject(const DeviceInfoProvider& device, EthernetLinkProvider& links)
    : device_(device), links_(links), object_(kEthernetLinkClass, *this) {}

std::span<const AttributeSpec> EthernetLinkObject::InstanceAttributes(std::uint32_t) const { return kAttributes; }

void EthernetLinkObject::GetInstanceAttribute(std::uint32_t instance, std::uint16_t id, base::ByteWriter& out) {
  const LinkPort port = PortOf(instance);
  switch (id) {
    case 1:
      out.U32Le(links_.State(port).speed_mbps);
      break;
    case 2:
      out.U32Le(EncodeInterfaceFlags(links_.State(port)));
      break;
    case 3:
      device_.Mac().Write(out);
      break;
    case kAttributeInterfaceCounters:
      PutCounters(links_.Counters(port), out);
      break;
    case kAttributeMediaCounters:
      PutMedia(links_.Media(port), out);
      break;
    case 6:
      PutInterfaceControl(links_.StoredSetting(), out);
      break;
    case 7:
      out.U8(kInterfaceTypeTwistedPair);
      break;
    case 8:
      out.U8(kInterfaceStateEnabled);
      break;
    case 9:
      out.U8(kAdminStateEnabled);
      break;
    case 10: {
      const std::string_view label = port == LinkPort::kRight ? "Right" : "Left";
      PutShortString(std::span(reinterpret_cast<const std::uint8_t*>(label.data()), label.size()), out);
      break;
    }
    default:
      break;
  }
}

ServiceStatus EthernetLinkObject::SetInstanceAttribute(std::uint32_t, std::uint16_t id, base::ByteReader& value) {
  if (id != 6) return Error(GeneralStatus::kAttributeNotSettable);
  const ServiceStatus size = ExpectSize(value, 4);
  if (!size.ok()) return size;
  const std::uint16_t control = value.U16Le();
  const std::uint16_t speed = value.U16Le();
  const bool full = (control & kControlFullDuplex) != 0;
  LinkSetting setting = LinkSetting::kAuto;
  if (control == kControlAutoNegotiate && speed == 0) {
    setting = LinkSetting::kAuto;
  } else if ((control & ~kControlFullDuplex) == 0 && speed == 10) {
    setting = full ? LinkSetting::k10Full : LinkSetting::k10Half;
  } else if ((control & ~kControlFullDuplex) == 0 && speed == 100) {
    setting = full ? LinkSetting::k100Full : LinkSetting::k100Half;
  } else {
    return Error(GeneralStatus::kInvalidAttributeValue);
  }
  return StoreResult(links_.StoreSetting(setting));
}

ServiceStatus EthernetLinkObject::ExecuteOther(const ServiceRequest& request, base::ByteWriter& reply) {
  if (request.service != kServiceGetAndClear) return Error(GeneralStatus::kServiceNotSupported);
  const std::uint32_t id = request.path.attribute.value_or(0);
  if (id != kAttributeInterfaceCounters && id != kAttributeMediaCounters) {
    return Error(GeneralStatus::kAttributeNotSupported);
  }
  if (!request.data.empty()) return Error(GeneralStatus::kTooMuchData);
  const LinkPort port = PortOf(request.path.instance);
  if (id == kAttributeInterfaceCounters) {
    PutCounters(links_.Counters(port), reply);
    if (reply.ok()) links_.ClearCounters(port);
  } else {
    PutMedia(links_.Media(port), reply);
    if (reply.ok()) links_.ClearMedia(port);
  }
  return Success();
}

}  // namespace cip
