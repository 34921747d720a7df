#include "cip/drive/motor_data_object.h"

#include <array>

#include "cip/drive/parameter_channel.h"

namespace cip::drive {
namespace {

constexpr std::array<std::uint16_t, 5> kClassAttributes = {1, 2, 3, 6, 7};
constexpr std::array<std::uint8_t, 1> kClassServices = {kServiceGetAttributeSingle};
constexpr std::array<std::uint8_t, 2> kInstanceServices = {kServiceGetAttributeSingle, kServiceSetAttributeSingle};
constexpr ClassSpec kMotorDataClass = {
    kClassMotorData, 1, kClassAttributes, {}, {}, 7, 15, kClassServices, kInstanceServices,
};

// §4.5's attribute list, which attributes 1 and 2 report. No Get_Attributes_All (§4.5 lists none).
constexpr std::array<AttributeSpec, 9> kAttributes = {{
    {1, Access::kGet, false},
    {2, Access::kGet, false},
    {3, Access::kGet, false},
    {6, Access::kGetSet, false},
    {7, Access::kGetSet, false},
    {8, Access::kGetSet, false},
    {9, Access::kGetSet, false},
    {12, Access::kGet, false},
    {15, Access::kGetSet, false},
}};

}  // namespace

MotorDataObject::MotorDataObject(DriveAccessJournal& journal)
    : RegisterAttributeHandler(journal, MissingRegister::kNoSuchAttribute), object_(kMotorDataClass, *this) {}

std::span<const AttributeSpec> MotorDataObject::InstanceAttributes(std::uint32_t) const { return kAttributes; }

void MotorDataObject::GetInstanceAttribute(std::uint32_t, std::uint16_t id, base::ByteWriter& out) {
  switch (id) {
    case 1:
      out.U16Le(static_cast<std::uint16_t>(kAttributes.size()));
      return;
    case 2:
      for (const AttributeSpec& attribute : kAttributes) out.U8(static_cast<std::uint8_t>(attribute.id));
      return;
    case 3:
      out.U8(kMotorTypeSquirrelCage);
      return;
    default:
      break;
  }
  // The register-backed ones: nothing is written unless the value is there.
  switch (id) {
    case 6:
      if (const auto f415 = ReadRegister(kMotorRatedCurrentParameter)) out.U16Le(*f415);
      return;
    case 7:
      if (const auto vlv = ReadRegister(kMotorRatedVoltageParameter)) out.U16Le(VoltsFromVlv(*vlv));
      return;
    case 8:
      if (const auto f405 = ReadRegister(kMotorRatedPowerParameter)) out.U32Le(WattsFromF405(*f405));
      return;
    case 9:
      if (const auto vl = ReadRegister(kMotorBaseFrequencyParameter)) out.U16Le(HertzFromVl(*vl));
      return;
    case 12:
      if (const auto f856 = ReadRegister(kMotorPolePairsParameter)) out.U16Le(PoleCountFromF856(*f856));
      return;
    case 15:
      if (const auto f417 = ReadRegister(kMotorBaseSpeedParameter)) out.U16Le(*f417);
      return;
    default:
      return;
  }
}

ServiceStatus MotorDataObject::SetInstanceAttribute(std::uint32_t, std::uint16_t id, base::ByteReader& value) {
  std::uint16_t number = 0;
  std::optional<std::uint16_t> register_value;
  ServiceStatus size;
  if (id == 8) {
    std::uint32_t watts = 0;
    size = ReadExactU32(value, watts);
    number = kMotorRatedPowerParameter;
    register_value = F405FromWatts(watts);
  } else {
    std::uint16_t data = 0;
    size = ReadExactU16(value, data);
    switch (id) {
      case 6:
        number = kMotorRatedCurrentParameter;
        register_value = data;
        break;
      case 7:
        number = kMotorRatedVoltageParameter;
        register_value = VlvFromVolts(data);
        break;
      case 9:
        number = kMotorBaseFrequencyParameter;
        register_value = VlFromHertz(data);
        break;
      case 15:
        number = kMotorBaseSpeedParameter;
        register_value = data;
        break;
      default:
        return Error(GeneralStatus::kAttributeNotSettable);  // the table lets only the above through
    }
  }
  if (!size.ok()) return size;
  if (!register_value) return Error(GeneralStatus::kInvalidAttributeValue);
  return WriteRegister(number, *register_value, kParameterWriteMode);
}

}  // namespace cip::drive
