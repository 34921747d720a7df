#include "cip/dlr_object.h"

#include <array>

namespace cip {
namespace {

constexpr std::array<std::uint16_t, 7> kClassAttributes = {1, 2, 3, 4, 5, 6, 7};
constexpr std::array<std::uint8_t, 2> kClassServices = {kServiceGetAttributesAll, kServiceGetAttributeSingle};
constexpr std::array<std::uint8_t, 3> kInstanceServices = {kServiceGetAttributesAll, kServiceGetAttributeSingle,
                                                           kServiceSetAttributeSingle};
constexpr ClassSpec kDlrClass = {
    kClassDlr, kDlrClassRevision, kClassAttributes, {}, {}, 7, 12, kClassServices, kInstanceServices,
};
// Table order is the Get_Attributes_All order.
constexpr std::array<AttributeSpec, 11> kAttributes = {{
    {1, Access::kGet, true},
    {2, Access::kGet, true},
    {3, Access::kGetAllOnly, true},
    {4, Access::kGetAllOnly, true},
    {5, Access::kGetAllOnly, true},
    {6, Access::kGetAllOnly, true},
    {7, Access::kGetAllOnly, true},
    {8, Access::kGetAllOnly, true},
    {10, Access::kGet, true},
    {11, Access::kGetAllOnly, true},
    {12, Access::kGet, true},
}};

constexpr std::uint8_t kNoSupervisorStatus = 0xFF;       // attribute 3 placeholder
constexpr std::size_t kSupervisorConfigSize = 12;        // attribute 4 placeholder
constexpr std::size_t kNodeAddressSize = 10;             // attributes 6, 7 placeholders
constexpr std::uint16_t kUnknownParticipants = 0xFFFF;   // attribute 8 placeholder

}  // namespace

DlrObject::DlrObject(const DlrProvider& dlr) : dlr_(dlr), object_(kDlrClass, *this) {}

std::span<const AttributeSpec> DlrObject::InstanceAttributes(std::uint32_t) const { return kAttributes; }

void DlrObject::GetInstanceAttribute(std::uint32_t, std::uint16_t id, base::ByteWriter& out) {
  const DlrObjectValues values = dlr_.DlrValues();
  switch (id) {
    case 1:
      out.U8(values.network_topology);
      break;
    case 2:
      out.U8(values.network_status);
      break;
    case 3:
      out.U8(kNoSupervisorStatus);
      break;
    case 4:
      out.Zeros(kSupervisorConfigSize);
      break;
    case 5:
      out.U16Le(0);
      break;
    case 6:
    case 7:
      out.Zeros(kNodeAddressSize);
      break;
    case 8:
      out.U16Le(kUnknownParticipants);
      break;
    case 10:
      out.U32Le(values.supervisor_ip);
      values.supervisor_mac.Write(out);
      break;
    case 11:
      out.U8(values.supervisor_precedence);
      break;
    case 12:
      out.U32Le(kDlrNodeCapabilities);
      break;
    default:
      break;
  }
}

}  // namespace cip
