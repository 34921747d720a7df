// Control Supervisor object 0x29 (control_supervisor_object.h).
#include "cip/drive/control_supervisor_object.h"

#include <array>

namespace cip::drive {
namespace {

constexpr std::array<std::uint16_t, 5> kClassAttributes = {1, 2, 3, 6, 7};
constexpr std::array<std::uint8_t, 1> kClassServices = {kServiceGetAttributeSingle};
constexpr std::array<std::uint8_t, 3> kInstanceServices = {kServiceReset, kServiceGetAttributeSingle,
                                                           kServiceSetAttributeSingle};
constexpr ClassSpec kControlSupervisorClass = {
    kClassControlSupervisor, 1, kClassAttributes, {}, {}, 7, 15, kClassServices, kInstanceServices,
};

enum Attribute : std::uint16_t {
  kNumAttr = 1,
  kAttrList = 2,
  kRun1 = 3,
  kRun2 = 4,
  kNetCtrl = 5,
  kState = 6,
  kRunning1 = 7,
  kRunning2 = 8,
  kReady = 9,
  kFaulted = 10,
  kWarning = 11,
  kFaultRst = 12,
  kCtrlFromNet = 15,
};

// §4.6's list, which attributes 1 and 2 report. No Get_Attributes_All (§4.6 lists none).
constexpr std::array<AttributeSpec, 13> kAttributes = {{
    {kNumAttr, Access::kGet, false},
    {kAttrList, Access::kGet, false},
    {kRun1, Access::kGetSet, false},
    {kRun2, Access::kGetSet, false},
    {kNetCtrl, Access::kGetSet, false},
    {kState, Access::kGet, false},
    {kRunning1, Access::kGet, false},
    {kRunning2, Access::kGet, false},
    {kReady, Access::kGet, false},
    {kFaulted, Access::kGet, false},
    {kWarning, Access::kGet, false},
    {kFaultRst, Access::kGetSet, false},
    {kCtrlFromNet, Access::kGet, false},
}};

void PutBool(bool value, base::ByteWriter& out) { out.U8(value ? 1 : 0); }

}  // namespace

ServiceStatus ReadExactBool(base::ByteReader& in, bool& value) {
  std::uint8_t byte = 0;
  const ServiceStatus size = ReadExactU8(in, byte);
  if (!size.ok()) return size;
  if (byte > 1) return Error(GeneralStatus::kInvalidAttributeValue);
  value = byte == 1;
  return Success();
}

ControlSupervisorObject::ControlSupervisorObject(DriveProfileRuntime& runtime)
    : runtime_(runtime), object_(kControlSupervisorClass, *this) {}

std::span<const AttributeSpec> ControlSupervisorObject::InstanceAttributes(std::uint32_t) const {
  return kAttributes;
}

void ControlSupervisorObject::GetInstanceAttribute(std::uint32_t, std::uint16_t id, base::ByteWriter& out) {
  // The state follows the newest FD01 even when nothing else stepped the supervisor since it changed.
  runtime_.Refresh();
  const ControlSupervisor& supervisor = runtime_.supervisor();
  switch (id) {
    case kNumAttr:
      out.U16Le(static_cast<std::uint16_t>(kAttributes.size()));
      return;
    case kAttrList:
      for (const AttributeSpec& attribute : kAttributes) out.U8(static_cast<std::uint8_t>(attribute.id));
      return;
    case kRun1:
      PutBool(runtime_.run1(), out);
      return;
    case kRun2:
      PutBool(runtime_.run2(), out);
      return;
    case kNetCtrl:
      PutBool(runtime_.net_ctrl(), out);
      return;
    case kState:
      out.U8(static_cast<std::uint8_t>(supervisor.state()));
      return;
    case kRunning1:
      PutBool(supervisor.running1(), out);
      return;
    case kRunning2:
      PutBool(supervisor.running2(), out);
      return;
    case kReady:
      PutBool(supervisor.ready(), out);
      return;
    case kFaulted:
      PutBool(supervisor.faulted(), out);
      return;
    case kWarning:
      PutBool(supervisor.warning(), out);
      return;
    case kFaultRst:
      PutBool(runtime_.fault_reset_attribute(), out);
      return;
    case kCtrlFromNet:
      PutBool(runtime_.control_sources().ctrl_from_net, out);
      return;
    default:
      return;
  }
}

ServiceStatus ControlSupervisorObject::SetInstanceAttribute(std::uint32_t, std::uint16_t id, base::ByteReader& value) {
  bool level = false;
  const ServiceStatus decoded = ReadExactBool(value, level);
  if (!decoded.ok()) return decoded;
  switch (id) {
    case kRun1:
      return runtime_.SetControl(ControlAttribute::kRun1, level);
    case kRun2:
      return runtime_.SetControl(ControlAttribute::kRun2, level);
    case kNetCtrl:
      return runtime_.SetControl(ControlAttribute::kNetCtrl, level);
    case kFaultRst:
      return runtime_.SetControl(ControlAttribute::kFaultReset, level);
    default:
      return Error(GeneralStatus::kAttributeNotSettable);  // the table lets only the above through
  }
}

ServiceStatus ControlSupervisorObject::ExecuteOther(const ServiceRequest& request, base::ByteWriter&) {
  if (request.service != kServiceReset) return Error(GeneralStatus::kServiceNotSupported);
  if (!request.data.empty()) return Error(GeneralStatus::kTooMuchData);  // §4.6's Reset has no parameter
  return runtime_.ResetSupervisor();
}

}  // namespace cip::drive
