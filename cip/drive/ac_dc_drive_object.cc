// AC/DC Drive object 0x2A (ac_dc_drive_object.h).
#include "cip/drive/ac_dc_drive_object.h"

#include <array>

#include "cip/drive/control_supervisor_object.h"
#include "cip/drive/drive_units.h"
#include "cip/drive/parameter_channel.h"
#include "drive_link/drive_registers.h"

namespace cip::drive {
namespace {

namespace reg = drive_link::reg;

constexpr std::array<std::uint16_t, 5> kClassAttributes = {1, 2, 3, 6, 7};
constexpr std::array<std::uint8_t, 1> kClassServices = {kServiceGetAttributeSingle};
constexpr std::array<std::uint8_t, 2> kInstanceServices = {kServiceGetAttributeSingle, kServiceSetAttributeSingle};
constexpr ClassSpec kAcDcDriveClass = {
    kClassAcDcDrive, 1, kClassAttributes, {}, {}, 7, 46, kClassServices, kInstanceServices,
};

enum Attribute : std::uint16_t {
  kNumAttr = 1,
  kAttributeList = 2,
  kAtReference = 3,
  kNetRef = 4,
  kDriveMode = 6,
  kSpeedActual = 7,
  kSpeedRef = 8,
  kCurrentActual = 9,
  kCurrentLimit = 10,
  kTorqueActual = 11,
  kPowerActual = 15,
  kAccelTime = 18,
  kDecelTime = 19,
  kLowSpdLimit = 20,
  kHighSpdLimit = 21,
  kPowerScaling = 26,
  kTimeScaling = 28,
  kRefFromNet = 29,
  kHoursOn = 46,
};

// §4.7's list, which attributes 1 and 2 report. No Get_Attributes_All (§4.7 lists none).
constexpr std::array<AttributeSpec, 19> kAttributes = {{
    {kNumAttr, Access::kGet, false},        {kAttributeList, Access::kGet, false},
    {kAtReference, Access::kGet, false},    {kNetRef, Access::kGetSet, false},
    {kDriveMode, Access::kGet, false},      {kSpeedActual, Access::kGet, false},
    {kSpeedRef, Access::kGetSet, false},    {kCurrentActual, Access::kGet, false},
    {kCurrentLimit, Access::kGetSet, false}, {kTorqueActual, Access::kGet, false},
    {kPowerActual, Access::kGet, false},    {kAccelTime, Access::kGetSet, false},
    {kDecelTime, Access::kGetSet, false},   {kLowSpdLimit, Access::kGetSet, false},
    {kHighSpdLimit, Access::kGetSet, false}, {kPowerScaling, Access::kGetSet, false},
    {kTimeScaling, Access::kGetSet, false}, {kRefFromNet, Access::kGet, false},
    {kHoursOn, Access::kGet, false},
}};

// The inverter registers behind the attributes (seed 000 §3.1, §3.2.4; fNNN is 0NNN).
constexpr std::uint16_t kLowerLimitFrequency = 0x0013;  // ll, 0.01 Hz
constexpr std::uint16_t kTimeUnit = 0x0519;             // f519: 0 = acc/dec in 0.1 s, 1 = 0.01 s
constexpr std::uint16_t kRatedMotorPower = 0x0405;      // f405, 0.01 kW
constexpr std::uint16_t kRatedMotorSpeed = 0x0417;      // f417, rpm
constexpr std::uint16_t kFrequencyCommand = 0xFE02;     // frequency command in force, 0.01 Hz
constexpr std::uint16_t kOutputCurrent = 0xFD03;        // 0.01 % of the drive's rated current
constexpr std::uint16_t kTorque = 0xFD18;               // 0.01 % of the motor's rated torque (signed)
constexpr std::uint16_t kOutputPower = 0xFD30;          // 0.01 kW
constexpr std::uint16_t kDriveRatedCurrent = 0xFE70;    // 0.1 A
constexpr std::uint16_t kTimeUnitHundredths = 1;

constexpr std::uint16_t Saturate16(std::uint32_t value) {
  return static_cast<std::uint16_t>(value > 0xFFFF ? 0xFFFFu : value);
}

}  // namespace

AcDcDriveObject::AcDcDriveObject(DriveProfileRuntime& runtime, DriveAccessJournal& journal)
    : RegisterAttributeHandler(journal, MissingRegister::kNoSuchAttribute),
      runtime_(runtime),
      object_(kAcDcDriveClass, *this) {}

std::span<const AttributeSpec> AcDcDriveObject::InstanceAttributes(std::uint32_t) const { return kAttributes; }

void AcDcDriveObject::GetInstanceAttribute(std::uint32_t, std::uint16_t id, base::ByteWriter& out) {
  switch (id) {
    case kNumAttr:
      out.U8(static_cast<std::uint8_t>(kAttributes.size()));
      return;
    case kAttributeList:
      for (const AttributeSpec& attribute : kAttributes) out.U8(static_cast<std::uint8_t>(attribute.id));
      return;
    case kNetRef:
      out.U8(runtime_.net_ref() ? 1 : 0);
      return;
    case kDriveMode:
      out.U8(kDriveModeOpenLoopSpeed);
      return;
    case kSpeedRef:
      out.U16Le(static_cast<std::uint16_t>(runtime_.speed_reference_rpm()));
      return;
    case kPowerScaling:
    case kTimeScaling:
      out.U16Le(0);
      return;
    case kRefFromNet:
      out.U8(runtime_.control_sources().ref_from_net ? 1 : 0);
      return;
    default:
      GetRegisterAttribute(id, out);
      return;
  }
}

// The register-backed attributes: every read of a service is started in its first pass (they then
// travel together), and nothing is written unless all the values are there.
void AcDcDriveObject::GetRegisterAttribute(std::uint16_t id, base::ByteWriter& out) {
  const std::uint16_t pole_pairs = runtime_.pole_pairs();
  switch (id) {
    case kAtReference: {
      const auto fd00 = ReadRegister(reg::kFd00);
      const auto fe02 = ReadRegister(kFrequencyCommand);
      if (!fd00 || !fe02) return;
      runtime_.Refresh();
      out.U8(runtime_.supervisor().state() == SupervisorState::kEnabled && *fd00 == *fe02 ? 1 : 0);
      return;
    }
    case kSpeedActual:
      if (const auto fd00 = ReadRegister(reg::kFd00)) out.U16Le(FrequencyToRpm(*fd00, pole_pairs));
      return;
    case kCurrentActual: {
      const auto fd03 = ReadRegister(kOutputCurrent);
      const auto fe70 = ReadRegister(kDriveRatedCurrent);
      if (fd03 && fe70) out.U16Le(CurrentTenthsOfAmp(*fd03, *fe70));
      return;
    }
    case kCurrentLimit: {
      const auto f601 = ReadRegister(reg::kF601);
      const auto fe70 = ReadRegister(kDriveRatedCurrent);
      if (f601 && fe70) out.U16Le(CurrentLimitTenths(*f601, *fe70));
      return;
    }
    case kTorqueActual: {
      const auto fd18 = ReadRegister(kTorque);
      const auto f405 = ReadRegister(kRatedMotorPower);
      const auto f417 = ReadRegister(kRatedMotorSpeed);
      if (fd18 && f405 && f417) out.U16Le(TorqueNewtonMetres(static_cast<std::int16_t>(*fd18), *f405, *f417));
      return;
    }
    case kPowerActual:
      if (const auto fd30 = ReadRegister(kOutputPower)) out.U16Le(Saturate16(static_cast<std::uint32_t>(*fd30) * 10u));
      return;
    case kAccelTime:
    case kDecelTime: {
      const auto ramp = ReadRegister(id == kAccelTime ? reg::kAcc : reg::kDec);
      const auto unit = ReadRegister(kTimeUnit);
      if (ramp && unit) out.U16Le(TimeParameterToMillis(*ramp, *unit == kTimeUnitHundredths));
      return;
    }
    case kLowSpdLimit:
    case kHighSpdLimit:
      if (const auto limit = ReadRegister(id == kLowSpdLimit ? kLowerLimitFrequency : reg::kUl)) {
        out.U16Le(FrequencyToRpm(*limit, pole_pairs));
      }
      return;
    case kHoursOn:
      if (const auto fe14 = ReadRegister(reg::kFe14)) out.U32Le(*fe14);
      return;
    default:
      return;
  }
}

ServiceStatus AcDcDriveObject::SetInstanceAttribute(std::uint32_t, std::uint16_t id, base::ByteReader& value) {
  if (id == kNetRef) {
    bool level = false;
    const ServiceStatus decoded = ReadExactBool(value, level);
    if (!decoded.ok()) return decoded;
    return runtime_.SetControl(ControlAttribute::kNetRef, level);
  }
  std::uint16_t data = 0;
  const ServiceStatus decoded = ReadExactU16(value, data);
  if (!decoded.ok()) return decoded;
  switch (id) {
    case kSpeedRef:
      return runtime_.SetSpeedReference(static_cast<std::int16_t>(data));
    case kCurrentLimit:
      return SetCurrentLimit(data);
    case kAccelTime:
      return SetRamp(reg::kAcc, data);
    case kDecelTime:
      return SetRamp(reg::kDec, data);
    case kLowSpdLimit:
    case kHighSpdLimit:
      return SetSpeedLimit(id == kLowSpdLimit ? kLowerLimitFrequency : reg::kUl, data);
    case kPowerScaling:
    case kTimeScaling:
      // Only the unscaled units of the table are offered.
      return data == 0 ? Success() : Error(GeneralStatus::kInvalidAttributeValue);
    default:
      return Error(GeneralStatus::kAttributeNotSettable);  // the table lets only the above through
  }
}

ServiceStatus AcDcDriveObject::SetRamp(std::uint16_t number, std::uint16_t millis) {
  // The unit first: the value written depends on it (a later pass has it from the journal).
  const auto unit = ReadRegister(kTimeUnit);
  if (!unit) return outcome();
  return WriteRegister(number, MillisToTimeParameter(millis, *unit == kTimeUnitHundredths), kParameterWriteMode);
}

ServiceStatus AcDcDriveObject::SetSpeedLimit(std::uint16_t number, std::uint16_t rpm) {
  // f856 from the inverter, not from the configuration in force: the value written must follow from
  // the request and the recorded results only, or a configuration reload between two passes would make
  // the retry write another value (the journal's mismatch, 0x1F).
  const auto f856 = ReadRegister(reg::kF856);
  if (!f856) return outcome();
  // At most 500.00 Hz (RpmToFrequency): the inverter itself keeps ul within fh.
  return WriteRegister(number, RpmToFrequency(rpm, *f856), kParameterWriteMode);
}

ServiceStatus AcDcDriveObject::SetCurrentLimit(std::uint16_t tenths) {
  const auto fe70 = ReadRegister(kDriveRatedCurrent);
  if (!fe70) return outcome();
  const std::optional<std::uint16_t> percent = CurrentLimitPercent(tenths, *fe70);
  if (!percent) return Error(GeneralStatus::kInvalidAttributeValue);
  return WriteRegister(reg::kF601, *percent, kParameterWriteMode);
}

}  // namespace cip::drive
