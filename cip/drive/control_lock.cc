// The exclusive-owner write lock (control_lock.h, docs/security.md).
#include "cip/drive/control_lock.h"

#include <algorithm>

#include "cip/cip_status.h"
#include "cip/drive/ac_dc_drive_object.h"
#include "cip/drive/assembly_codec.h"
#include "cip/drive/cip_parameter_object.h"
#include "cip/drive/control_supervisor_object.h"
#include "cip/drive/parameter_object.h"
#include "drive_link/drive_registers.h"

namespace cip::drive {
namespace {

// Control Supervisor 0x29 and AC/DC Drive 0x2A attributes that command the drive.
constexpr std::uint32_t kRun1 = 3;
constexpr std::uint32_t kRun2 = 4;
constexpr std::uint32_t kNetCtrl = 5;
constexpr std::uint32_t kFaultRst = 12;
constexpr std::uint32_t kNetRef = 4;
constexpr std::uint32_t kSpeedRef = 8;
constexpr std::uint32_t kAssemblyData = 3;

bool IsOutputAssembly(std::uint32_t instance) {
  return std::find(kOutputInstances.begin(), kOutputInstances.end(), instance) != kOutputInstances.end();
}

bool SetsControlParameter(ParameterClass parameter_class, std::uint32_t instance) {
  const std::optional<std::uint16_t> number = ParameterNumber(parameter_class, instance);
  return number && drive_link::reg::IsControlRegister(*number);
}

// A Parameter object 0x0F instance is a row of the card's parameter table.
bool SetsControlTableParameter(std::uint32_t instance) {
  const std::span<const drive_link::ParameterInfo> rows = drive_link::CardParameters();
  return instance >= 1 && instance <= rows.size() && drive_link::reg::IsControlRegister(rows[instance - 1].number);
}

}  // namespace

bool IsControlRequest(const ServiceRequest& request) {
  const ApplicationPath& path = request.path;
  const bool set = request.service == kServiceSetAttributeSingle && path.instance != 0 && path.attribute;
  const std::uint32_t attribute = path.attribute.value_or(0);
  switch (path.class_id) {
    case kClassIdentity:
      return request.service == kServiceReset && path.instance != 0;
    case kClassAssembly:
      return set && attribute == kAssemblyData && IsOutputAssembly(path.instance);
    case kClassControlSupervisor:
      if (request.service == kServiceReset && path.instance != 0) return true;
      return set && (attribute == kRun1 || attribute == kRun2 || attribute == kNetCtrl || attribute == kFaultRst);
    case kClassAcDcDrive:
      return set && (attribute == kNetRef || attribute == kSpeedRef);
    case kClassParameter64:
      return set && attribute == kParameterValueAttribute && SetsControlParameter(ParameterClass::k64, path.instance);
    case kClassParameter65:
      return set && attribute == kParameterValueAttribute && SetsControlParameter(ParameterClass::k65, path.instance);
    case kClassParameter:
      return set && attribute == kParameterValue && SetsControlTableParameter(path.instance);
    default:
      return false;
  }
}

ServiceStatus ControlLock::Admit(const ServiceRequest& request) {
  if (!IsControlRequest(request)) return Success();
  const base::Ipv4Address originator = request.context != nullptr ? request.context->peer.address : base::Ipv4Address();
  if (!connections_.OwnedByAnotherOriginator(originator)) return Success();
  ++refusals_;
  return Error(GeneralStatus::kDeviceStateConflict);
}

}  // namespace cip::drive
