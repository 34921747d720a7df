// Motor Data object 0x28 (seed 000 §4.5; docs/drive-objects.md "Motor Data"): one instance whose
// motor attributes are inverter parameters, in the units of the CIP Motor Data object.
//
//   class      1 revision 1, 2 max instance 1, 3 instances 1, 6 max class attribute 7,
//              7 max instance attribute 15; service Get_Attribute_Single 0x0E
//   instance 1 (services 0x0E, 0x10)
//     1  AttrNb        UINT      9                                   Get
//     2  AttrList      USINT[9]  1 2 3 6 7 8 9 12 15                  Get
//     3  MotorType     USINT     7 squirrel cage induction motor     Get
//     6  RatedCurrent  UINT      100 mA  = f415 (0.1 A), as it is     Get/Set
//     7  RatedVoltage  UINT      V       = vlv (0.1 V) / 10           Get/Set
//     8  RatedPower    UDINT     W       = f405 (0.01 kW) x 10        Get/Set
//     9  RatedFreq     UINT      Hz      = vl (0.01 Hz) / 100         Get/Set
//     12 PoleCount     UINT      poles   = f856 (pole pairs) x 2      Get
//     15 BaseSpeed     UINT      rpm     = f417 (1 rpm), as it is     Get/Set
//
// §4.5 names the parameters but not the units; the CIP units are the Motor Data object's (ODVA), the
// inverter's those of its parameter table. Reads round to the nearest unit (halves up); a Set converts
// back (RatedPower rounds to the nearest 10 W) and a value the parameter cannot hold in 16 bits is 0x09
// without asking the inverter; everything else about the value is the inverter's to judge. Sets are a
// user's explicit parameter writes: RAM and EEPROM. A parameter the inverter lacks makes its attribute
// 0x14 (the instance itself exists).
#pragma once

#include <cstdint>
#include <optional>
#include <span>

#include "cip/drive/drive_access_journal.h"
#include "cip/drive/register_attribute_object.h"
#include "cip/object_model.h"
#include "drive_link/drive_registers.h"

namespace cip::drive {

inline constexpr std::uint16_t kClassMotorData = 0x28;
inline constexpr std::uint8_t kMotorTypeSquirrelCage = 7;

// The parameters behind the attributes (communication numbers, seed 000 §3 fNNN -> 0NNN).
inline constexpr std::uint16_t kMotorRatedCurrentParameter = 0x0415;  // f415, 0.1 A
inline constexpr std::uint16_t kMotorRatedVoltageParameter = drive_link::reg::kVlv;  // vlv, 0.1 V
inline constexpr std::uint16_t kMotorRatedPowerParameter = 0x0405;    // f405, 0.01 kW
inline constexpr std::uint16_t kMotorBaseFrequencyParameter = 0x0014;  // vl, 0.01 Hz
inline constexpr std::uint16_t kMotorPolePairsParameter = drive_link::reg::kF856;
inline constexpr std::uint16_t kMotorBaseSpeedParameter = 0x0417;     // f417, 1 rpm

// Unit conversions (saturating; a Set's inverse is nothing when the parameter cannot hold the value).
constexpr std::uint16_t VoltsFromVlv(std::uint16_t vlv) { return static_cast<std::uint16_t>((vlv + 5u) / 10u); }
constexpr std::optional<std::uint16_t> VlvFromVolts(std::uint16_t volts) {
  if (volts > 0xFFFFu / 10u) return std::nullopt;
  return static_cast<std::uint16_t>(volts * 10u);
}
constexpr std::uint32_t WattsFromF405(std::uint16_t f405) { return static_cast<std::uint32_t>(f405) * 10u; }
constexpr std::optional<std::uint16_t> F405FromWatts(std::uint32_t watts) {
  const std::uint64_t f405 = (static_cast<std::uint64_t>(watts) + 5u) / 10u;
  if (f405 > 0xFFFFu) return std::nullopt;
  return static_cast<std::uint16_t>(f405);
}
constexpr std::uint16_t HertzFromVl(std::uint16_t vl) { return static_cast<std::uint16_t>((vl + 50u) / 100u); }
constexpr std::optional<std::uint16_t> VlFromHertz(std::uint16_t hertz) {
  if (hertz > 0xFFFFu / 100u) return std::nullopt;
  return static_cast<std::uint16_t>(hertz * 100u);
}
constexpr std::uint16_t PoleCountFromF856(std::uint16_t f856) {
  const std::uint32_t poles = static_cast<std::uint32_t>(f856) * 2u;
  return static_cast<std::uint16_t>(poles > 0xFFFFu ? 0xFFFFu : poles);
}

class MotorDataObject final : public RegisterAttributeHandler {
 public:
  explicit MotorDataObject(DriveAccessJournal& journal);

  CipObject& object() { return object_; }

  std::uint32_t MaxInstance() const override { return 1; }
  std::span<const AttributeSpec> InstanceAttributes(std::uint32_t instance) const override;
  void GetInstanceAttribute(std::uint32_t instance, std::uint16_t id, base::ByteWriter& out) override;
  ServiceStatus SetInstanceAttribute(std::uint32_t instance, std::uint16_t id, base::ByteReader& value) override;

 private:
  RegisterAttributeObject object_;
};

}  // namespace cip::drive
