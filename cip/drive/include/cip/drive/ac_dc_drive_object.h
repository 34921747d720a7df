// AC/DC Drive object 0x2A (seed 000 §4.7; docs/drive-objects.md "AC/DC Drive"): the speed reference
// and NetRef over DriveProfileRuntime (the path of assemblies 20/21/101), and the drive's monitors and
// ramp/limit parameters read and written through the DriveAccessJournal (deferred replies).
//
//   class      1 revision 1, 2 max instance 1, 3 instances 1, 6 max class attribute 7,
//              7 max instance attribute 46; service Get_Attribute_Single 0x0E
//   instance 1 (services Get_Attribute_Single 0x0E, Set_Attribute_Single 0x10)
//     1  NumAttr        USINT      19                                                     Get
//     2  Attributes     USINT[19]  1 2 3 4 6 7 8 9 10 11 15 18 19 20 21 26 28 29 46        Get
//     3  AtReference    BOOL   state Enabled and FD00 = FE02                              Get
//     4  NetRef         BOOL   FA06 bit 14 frequency priority                             Get/Set
//     6  DriveMode      USINT  1 open-loop speed (frequency) control                      Get
//     7  SpeedActual    INT    rpm   = FD00 (0.01 Hz) at f856 pole pairs                  Get
//     8  SpeedRef       INT    rpm   -> FA07 (0.01 Hz); reads the reference asked for      Get/Set
//     9  CurrentActual  UINT   0.1 A = FD03 (0.01 %) x FE70 (0.1 A) / 10000               Get
//     10 CurrentLimit   UINT   0.1 A = f601 (%) x FE70 / 100                              Get/Set
//     11 TorqueActual   UINT   Nm    = |FD18| (0.01 % of rated) x f405 / f417 rated torque  Get
//     15 PowerActual    UINT   W     = FD30 (0.01 kW) x 10                                Get
//     18 AccelTime      UINT   ms    = acc (0.1 s, 0.01 s when f519 = 1)                  Get/Set
//     19 DecelTime      UINT   ms    = dec (same unit)                                    Get/Set
//     20 LowSpdLimit    UINT   rpm   = ll (0.01 Hz)                                       Get/Set
//     21 HighSpdLimit   UINT   rpm   = ul (0.01 Hz)                                       Get/Set
//     26 PowerScaling   UINT   0 (only 0 may be set)                                      Get/Set
//     28 TimeScaling    UINT   0 (only 0 may be set)                                      Get/Set
//     29 RefFromNet     BOOL   FA06 bit 14 written, or fmod = 7                           Get
//     46 HoursOn        UDINT  h     = FE14 (cumulative operation time)                   Get
//
// NetRef and SpeedRef follow the Control Supervisor's rule: refused with 0x10 while an exclusive owner
// consumes 20/21/100/101. Register-backed Sets are a user's explicit parameter writes: RAM and EEPROM
// (kParameterWriteMode); the value is converted first (0x09 when the parameter cannot hold it) and
// everything else about it is the inverter's to judge. Access errors map as for Motor Data
// (AccessErrorStatus with MissingRegister::kNoSuchAttribute). Gets convert rpm with f856 of the card
// configuration in force (DriveProfileRuntime::pole_pairs, as the assemblies do); a Set of 20/21 reads
// f856 first, so that the value written depends only on the request and the journal's results.
#pragma once

#include <cstdint>
#include <optional>
#include <span>

#include "cip/drive/drive_access_journal.h"
#include "cip/drive/drive_profile_runtime.h"
#include "cip/drive/register_attribute_object.h"
#include "cip/object_model.h"

namespace cip::drive {

inline constexpr std::uint16_t kClassAcDcDrive = 0x2A;
// ODVA DriveMode: 1 = open-loop speed (frequency) control, what a VF-S15/VF-MB1 does in every pt mode.
inline constexpr std::uint8_t kDriveModeOpenLoopSpeed = 1;

// Rated torque share -> Nm: |fd18| (0.01 %) x rated power (f405, 0.01 kW) / rated angular speed (f417
// rpm), i.e. T = 600 x f405 / (2 pi x f417) x fd18 / 10000, rounded, at most 65535; 0 when f417 is 0.
constexpr std::uint16_t TorqueNewtonMetres(std::int16_t fd18, std::uint16_t f405, std::uint16_t f417) {
  if (f417 == 0) return 0;
  const std::uint64_t share = fd18 < 0 ? static_cast<std::uint64_t>(-static_cast<std::int32_t>(fd18))
                                       : static_cast<std::uint64_t>(fd18);
  // 600 / (2 pi x 10000) = 60000 / 6283185, with 2 pi in millionths to stay in integers.
  const std::uint64_t numerator = 60000u * static_cast<std::uint64_t>(f405) * share;
  const std::uint64_t denominator = 6283185u * static_cast<std::uint64_t>(f417);
  const std::uint64_t torque = (numerator + denominator / 2) / denominator;
  return static_cast<std::uint16_t>(torque > 0xFFFF ? 0xFFFFu : torque);
}

// f601 (% of the drive's rated current) <-> 0.1 A with FE70 (rated, 0.1 A), rounded to the nearest.
constexpr std::uint16_t CurrentLimitTenths(std::uint16_t f601, std::uint16_t fe70) {
  const std::uint32_t tenths = (static_cast<std::uint32_t>(f601) * fe70 + 50u) / 100u;
  return static_cast<std::uint16_t>(tenths > 0xFFFF ? 0xFFFFu : tenths);
}
constexpr std::optional<std::uint16_t> CurrentLimitPercent(std::uint16_t tenths, std::uint16_t fe70) {
  if (fe70 == 0) return std::nullopt;
  const std::uint32_t percent = (static_cast<std::uint32_t>(tenths) * 100u + fe70 / 2u) / fe70;
  if (percent > 0xFFFF) return std::nullopt;
  return static_cast<std::uint16_t>(percent);
}

class AcDcDriveObject final : public RegisterAttributeHandler {
 public:
  AcDcDriveObject(DriveProfileRuntime& runtime, DriveAccessJournal& journal);
  AcDcDriveObject(const AcDcDriveObject&) = delete;
  AcDcDriveObject& operator=(const AcDcDriveObject&) = delete;

  CipObject& object() { return object_; }

  std::uint32_t MaxInstance() const override { return 1; }
  std::span<const AttributeSpec> InstanceAttributes(std::uint32_t instance) const override;
  void GetInstanceAttribute(std::uint32_t instance, std::uint16_t id, base::ByteWriter& out) override;
  ServiceStatus SetInstanceAttribute(std::uint32_t instance, std::uint16_t id, base::ByteReader& value) override;

 private:
  void GetRegisterAttribute(std::uint16_t id, base::ByteWriter& out);
  ServiceStatus SetRamp(std::uint16_t number, std::uint16_t millis);
  ServiceStatus SetSpeedLimit(std::uint16_t number, std::uint16_t rpm);
  ServiceStatus SetCurrentLimit(std::uint16_t tenths);

  DriveProfileRuntime& runtime_;
  RegisterAttributeObject object_;
};

}  // namespace cip::drive
