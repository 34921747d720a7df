// The Parameter objects (seed 000 §4.8, §4.9; docs/drive-objects.md "Parameter objects"): every
// communication number of the inverter as an instance whose attribute 3 is the register's value (UINT).
//
//   0x64  instance = number + 0x4000 for 0000-0FFF (basic and extended parameters: cmod 0003 -> 4003,
//         f268 0268 -> 4268, au1 0000 -> 4000), number - 0x8000 for F000-FFFF (fe03 FE03 -> 7E03).
//         Instances 4000-4FFF and 7000-7FFF. Class: revision 1, max instance 32767, instances 8190 (the
//         manual's figures), max class attribute 7, max instance attribute 3.
//   0x65  instance = number, 0001-FFFF (0000, au1, only through 0x64: instance 0 is the class). Class:
//         revision 1, max instance 65535, instances 65535, 7, 3.
//   both  class service Get_Attribute_Single 0x0E; instance services 0x0E and Set_Attribute_Single
//         0x10; instance attribute 3 only. A number ending in A-F is no register (§8.9 (5)): its
//         instance does not exist (0x16, without asking the inverter). A monitor (FC00-FEFF, "Get only")
//         has attribute 3 read-only: Set answers 0x0E. Other refusals come from the inverter or the
//         register proxy and are mapped by AccessErrorStatus (a register the inverter lacks: 0x16).
//
// Values are passed as they are (the parameter's own unit: acc 5 s = 50 = 0x0032 at 4009 / 0009). A Set
// is a user's explicit parameter write: RAM and EEPROM (kParameterWriteMode), as through 101/105.
#pragma once

#include <cstdint>
#include <optional>
#include <span>

#include "cip/drive/drive_access_journal.h"
#include "cip/drive/register_attribute_object.h"
#include "cip/object_model.h"

namespace cip::drive {

inline constexpr std::uint16_t kClassParameter64 = 0x64;
inline constexpr std::uint16_t kClassParameter65 = 0x65;
inline constexpr std::uint16_t kParameterValueAttribute = 3;

// 0x64's two windows.
inline constexpr std::uint32_t kParameter64BasicFirst = 0x4000;  // -> 0000-0FFF
inline constexpr std::uint32_t kParameter64BasicLast = 0x4FFF;
inline constexpr std::uint32_t kParameter64MonitorFirst = 0x7000;  // -> F000-FFFF
inline constexpr std::uint32_t kParameter64MonitorLast = 0x7FFF;

enum class ParameterClass : std::uint8_t { k64, k65 };

// The communication number an instance addresses, or nothing when the instance does not exist.
std::optional<std::uint16_t> ParameterNumber(ParameterClass parameter_class, std::uint32_t instance);
// The instance of a communication number (the inverse), or nothing when the class cannot reach it.
std::optional<std::uint32_t> ParameterInstance(ParameterClass parameter_class, std::uint16_t number);

class ParameterObject final : public RegisterAttributeHandler {
 public:
  ParameterObject(ParameterClass parameter_class, DriveAccessJournal& journal);

  CipObject& object() { return object_; }

  std::uint32_t MaxInstance() const override;
  std::uint32_t InstanceCount() const override;
  bool HasInstanceNumber(std::uint32_t instance) const override;
  std::span<const AttributeSpec> InstanceAttributes(std::uint32_t instance) const override;
  void GetInstanceAttribute(std::uint32_t instance, std::uint16_t id, base::ByteWriter& out) override;
  ServiceStatus SetInstanceAttribute(std::uint32_t instance, std::uint16_t id, base::ByteReader& value) override;

 private:
  ParameterClass class_;
  RegisterAttributeObject object_;
};

}  // namespace cip::drive
