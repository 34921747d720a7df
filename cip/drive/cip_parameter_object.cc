#include "cip/drive/cip_parameter_object.h"

#include <string_view>

#include "cip/drive/parameter_channel.h"
#include "cip/drive/parameter_object.h"

namespace cip::drive {
namespace {

using drive_link::CardParameters;
using drive_link::ParameterInfo;

constexpr std::array<std::uint16_t, 6> kClassAttributes = {1, 2, 3, 8, 9, 10};
constexpr std::array<std::uint8_t, 1> kClassServices = {kServiceGetAttributeSingle};
constexpr std::array<std::uint8_t, 2> kInstanceServices = {kServiceGetAttributeSingle, kServiceSetAttributeSingle};
constexpr ClassSpec kParameterClass = {
    kClassParameter, 1, kClassAttributes, {}, {}, 10, 21, kClassServices, kInstanceServices,
};

// Attribute 1 settable or not; every other attribute is read-only. No Get_Attributes_All (0x08), so
// in_get_all does not matter.
template <Access value_access>
constexpr std::array<AttributeSpec, 17> kAttributes = {{
    {kParameterValue, value_access, false},
    {2, Access::kGet, false},  {3, Access::kGet, false},  {4, Access::kGet, false},  {5, Access::kGet, false},
    {6, Access::kGet, false},  {7, Access::kGet, false},  {8, Access::kGet, false},  {9, Access::kGet, false},
    {10, Access::kGet, false}, {11, Access::kGet, false}, {12, Access::kGet, false}, {13, Access::kGet, false},
    {14, Access::kGet, false}, {15, Access::kGet, false}, {16, Access::kGet, false}, {21, Access::kGet, false},
}};

constexpr std::uint8_t kNativeLanguageEnglish = 0;
constexpr std::uint16_t kNoConfigurationAssembly = 0;

const ParameterInfo* RowOf(std::uint32_t instance) {
  const std::span<const ParameterInfo> rows = CardParameters();
  if (instance == 0 || instance > rows.size()) return nullptr;
  return &rows[instance - 1];
}

void PutText(const char* text, base::ByteWriter& out) {
  const std::string_view view(text);
  PutShortString(std::span<const std::uint8_t>(reinterpret_cast<const std::uint8_t*>(view.data()), view.size()), out);
}

}  // namespace

std::uint16_t ParameterDescriptor(const ParameterInfo& row) {
  std::uint16_t descriptor = 0;
  if (row.decimals > 0) descriptor |= kDescriptorScaling;
  if (row.read_only) descriptor |= kDescriptorReadOnly | kDescriptorMonitor;
  return descriptor;
}

std::uint8_t ParameterDataType(const ParameterInfo& row) { return row.is_signed ? kDataTypeInt : kDataTypeUint; }

std::uint16_t ScalingDivisor(const ParameterInfo& row) {
  std::uint16_t divisor = 1;
  for (std::uint8_t i = 0; i < row.decimals; ++i) divisor = static_cast<std::uint16_t>(divisor * 10);
  return divisor;
}

std::array<std::uint8_t, kParameterLinkPathSize> ParameterLinkPath(std::uint16_t number) {
  // au1 (0000) has no 0x65 instance (instance 0 is the class): 0x64 reaches it as 4000.
  const ParameterClass parameter_class = number == 0 ? ParameterClass::k64 : ParameterClass::k65;
  const auto instance = static_cast<std::uint16_t>(ParameterInstance(parameter_class, number).value_or(0));
  return {0x20,
          static_cast<std::uint8_t>(number == 0 ? kClassParameter64 : kClassParameter65),
          0x25,
          0x00,
          static_cast<std::uint8_t>(instance & 0xFF),
          static_cast<std::uint8_t>(instance >> 8),
          0x30,
          static_cast<std::uint8_t>(kParameterValueAttribute)};
}

drive_link::InverterModel InverterModelOf(DriveModel model) {
  return model == DriveModel::kVfS15 ? drive_link::InverterModel::kVfS15 : drive_link::InverterModel::kVfMb1;
}

CipParameterObject::CipParameterObject(DriveAccessJournal& journal, const DeviceInfoProvider& device)
    // The instance is a row of the table and exists; a register the inverter lacks is its value's
    // absence: 0x14, as for Motor Data.
    : RegisterAttributeHandler(journal, MissingRegister::kNoSuchAttribute),
      device_(device),
      object_(kParameterClass, *this) {}

std::uint32_t CipParameterObject::MaxInstance() const { return static_cast<std::uint32_t>(CardParameters().size()); }

std::span<const AttributeSpec> CipParameterObject::InstanceAttributes(std::uint32_t instance) const {
  const ParameterInfo* row = RowOf(instance);
  if (row != nullptr && row->read_only) return kAttributes<Access::kGet>;
  return kAttributes<Access::kGetSet>;
}

void CipParameterObject::GetInstanceAttribute(std::uint32_t instance, std::uint16_t id, base::ByteWriter& out) {
  const ParameterInfo* row = RowOf(instance);
  if (row == nullptr) return;  // the router let only existing instances through
  const drive_link::ParameterLimits& limits = row->Limits(InverterModelOf(device_.Model()));
  switch (id) {
    case kParameterValue:
      if (const std::optional<std::uint16_t> value = ReadRegister(row->number)) out.U16Le(*value);
      return;
    case 2:
      out.U8(static_cast<std::uint8_t>(kParameterLinkPathSize));
      return;
    case 3:
      out.Bytes(ParameterLinkPath(row->number));
      return;
    case 4:
      out.U16Le(ParameterDescriptor(*row));
      return;
    case 5:
      out.U8(ParameterDataType(*row));
      return;
    case 6:
      out.U8(2);
      return;
    case 7:
      PutText(row->title, out);
      return;
    case 8:
      PutText(row->unit, out);
      return;
    case 9:
      PutText(row->help, out);
      return;
    case 10:
      out.U16Le(limits.min);
      return;
    case 11:
      out.U16Le(limits.max);
      return;
    case 12:
      out.U16Le(limits.default_value);
      return;
    case 13:
    case 15:
      out.U16Le(1);
      return;
    case 14:
      out.U16Le(ScalingDivisor(*row));
      return;
    case 16:
      out.U16Le(0);
      return;
    case 21:
      out.U8(row->decimals);
      return;
    default:
      return;
  }
}

ServiceStatus CipParameterObject::SetInstanceAttribute(std::uint32_t instance, std::uint16_t id, base::ByteReader& value) {
  const ParameterInfo* row = RowOf(instance);
  if (id != kParameterValue || row == nullptr) return Error(GeneralStatus::kAttributeNotSupported);
  std::uint16_t data = 0;
  const ServiceStatus size = ReadExactU16(value, data);
  if (!size.ok()) return size;
  // The table's limits are the inverter's: a value outside them is refused before anything is sent.
  if (!row->InRange(InverterModelOf(device_.Model()), data)) return Error(GeneralStatus::kInvalidAttributeValue);
  return WriteRegister(row->number, data, kParameterWriteMode);
}

void CipParameterObject::GetClassAttribute(std::uint16_t id, base::ByteWriter& out) {
  if (id == 8) out.U16Le(kParameterClassDescriptor);
  if (id == 9) out.U16Le(kNoConfigurationAssembly);
  if (id == 10) out.U8(kNativeLanguageEnglish);
}

}  // namespace cip::drive
