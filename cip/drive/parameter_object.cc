#include "cip/drive/parameter_object.h"

#include <array>

#include "cip/drive/parameter_channel.h"
#include "drive_link/drive_registers.h"

namespace cip::drive {
namespace {

constexpr std::array<std::uint16_t, 5> kClassAttributes = {1, 2, 3, 6, 7};
constexpr std::array<std::uint8_t, 1> kClassServices = {kServiceGetAttributeSingle};
constexpr std::array<std::uint8_t, 2> kInstanceServices = {kServiceGetAttributeSingle, kServiceSetAttributeSingle};

constexpr ClassSpec kParameter64Class = {
    kClassParameter64, 1, kClassAttributes, {}, {}, 7, kParameterValueAttribute, kClassServices, kInstanceServices,
};
constexpr ClassSpec kParameter65Class = {
    kClassParameter65, 1, kClassAttributes, {}, {}, 7, kParameterValueAttribute, kClassServices, kInstanceServices,
};

// Neither class lists Get_Attributes_All, so in_get_all does not matter.
constexpr std::array<AttributeSpec, 1> kSettableValue = {{{kParameterValueAttribute, Access::kGetSet, false}}};
constexpr std::array<AttributeSpec, 1> kMonitorValue = {{{kParameterValueAttribute, Access::kGet, false}}};

// §4.8's and §4.9's class attributes 2 and 3, as printed. 0x64's 8190 is not the 8192 instances of its
// two windows (nor the 5120 that exist once A-F endings are left out); an originator reading it is
// comparing with the manual, so the manual's figure is what it gets.
constexpr std::uint32_t kParameter64MaxInstance = 32767;
constexpr std::uint32_t kParameter64InstanceCount = 8190;
constexpr std::uint32_t kParameter65MaxInstance = 65535;
constexpr std::uint32_t kParameter65InstanceCount = 65535;

}  // namespace

std::optional<std::uint16_t> ParameterNumber(ParameterClass parameter_class, std::uint32_t instance) {
  std::uint32_t number = 0;
  if (parameter_class == ParameterClass::k65) {
    if (instance == 0 || instance > 0xFFFF) return std::nullopt;
    number = instance;
  } else if (instance >= kParameter64BasicFirst && instance <= kParameter64BasicLast) {
    number = instance - kParameter64BasicFirst;
  } else if (instance >= kParameter64MonitorFirst && instance <= kParameter64MonitorLast) {
    number = instance + 0x8000;  // bit 15 set again (§4.8: "- 0x8000, same as bit15 set to 0")
  } else {
    return std::nullopt;
  }
  const auto result = static_cast<std::uint16_t>(number);
  if (!drive_link::reg::HasDecimalLastDigit(result)) return std::nullopt;
  return result;
}

std::optional<std::uint32_t> ParameterInstance(ParameterClass parameter_class, std::uint16_t number) {
  if (!drive_link::reg::HasDecimalLastDigit(number)) return std::nullopt;
  if (parameter_class == ParameterClass::k65) {
    if (number == 0) return std::nullopt;
    return number;
  }
  if (number <= 0x0FFF) return kParameter64BasicFirst + number;
  if (number >= 0xF000) return static_cast<std::uint32_t>(number) - 0x8000;
  return std::nullopt;
}

ParameterObject::ParameterObject(ParameterClass parameter_class, DriveAccessJournal& journal)
    : RegisterAttributeHandler(journal, MissingRegister::kNoSuchInstance),
      class_(parameter_class),
      object_(parameter_class == ParameterClass::k64 ? kParameter64Class : kParameter65Class, *this) {}

std::uint32_t ParameterObject::MaxInstance() const {
  return class_ == ParameterClass::k64 ? kParameter64MaxInstance : kParameter65MaxInstance;
}

std::uint32_t ParameterObject::InstanceCount() const {
  return class_ == ParameterClass::k64 ? kParameter64InstanceCount : kParameter65InstanceCount;
}

bool ParameterObject::HasInstanceNumber(std::uint32_t instance) const {
  return ParameterNumber(class_, instance).has_value();
}

std::span<const AttributeSpec> ParameterObject::InstanceAttributes(std::uint32_t instance) const {
  const std::optional<std::uint16_t> number = ParameterNumber(class_, instance);
  // §4.8: "Monitor parameter can access Get only".
  if (number && drive_link::reg::IsMonitorNumber(*number)) return kMonitorValue;
  return kSettableValue;
}

void ParameterObject::GetInstanceAttribute(std::uint32_t instance, std::uint16_t id, base::ByteWriter& out) {
  const std::optional<std::uint16_t> number = ParameterNumber(class_, instance);
  if (id != kParameterValueAttribute || !number) return;  // the router let only existing ones through
  if (const std::optional<std::uint16_t> value = ReadRegister(*number)) out.U16Le(*value);
}

ServiceStatus ParameterObject::SetInstanceAttribute(std::uint32_t instance, std::uint16_t id, base::ByteReader& value) {
  const std::optional<std::uint16_t> number = ParameterNumber(class_, instance);
  if (id != kParameterValueAttribute || !number) return Error(GeneralStatus::kAttributeNotSupported);
  std::uint16_t data = 0;
  const ServiceStatus size = ReadExactU16(value, data);
  if (!size.ok()) return size;
  return WriteRegister(*number, data, kParameterWriteMode);
}

}  // namespace cip::drive
