#include "modbus/device_identification.h"

#include <array>
#include <cstddef>
#include <string_view>

#include "modbus/pdu.h"

namespace modbus {
namespace {

struct Object {
  std::uint8_t id = 0;
  std::string_view value;
};

// At most the six objects of the drive's regular category.
struct ObjectList {
  std::array<Object, 6> objects{};
  std::size_t count = 0;
  void Add(std::uint8_t id, std::string_view value) { objects[count++] = Object{id, value}; }
};

ObjectList ObjectsFor(IdentitySubject subject, const OptionBoardData& data, const IdentityText& firmware,
                      std::uint8_t device_id_code) {
  ObjectList list;
  if (subject == IdentitySubject::kOptionBoard) {
    list.Add(0, kVendorName);
    list.Add(1, kOptionBoardProductCode);
    list.Add(2, firmware.view());
    return list;
  }
  list.Add(0, kVendorName);
  list.Add(1, data.drive_product_code.view());
  list.Add(2, data.drive_version.view());
  if (device_id_code == kDeviceIdBasic) return list;
  list.Add(4, data.drive_product_name.view());
  list.Add(5, data.model_name.view());
  list.Add(6, data.user_application_name.view());
  return list;
}

}  // namespace

void WriteDeviceIdentification(base::ByteWriter& writer, IdentitySubject subject, const OptionBoardData& data,
                               std::uint8_t device_id_code, std::uint8_t object_id) {
  const IdentityText firmware = FirmwareVersionText(data.firmware_version);
  const ObjectList list = ObjectsFor(subject, data, firmware, device_id_code);
  std::size_t first = 0;
  for (std::size_t i = 0; i < list.count; ++i) {
    if (list.objects[i].id == object_id) first = i;
  }
  writer.U8(fc::kEncapsulatedInterface);
  writer.U8(fc::kMeiReadDeviceId);
  writer.U8(device_id_code);
  writer.U8(kConformityLevel);
  writer.U8(0x00);  // More Follows: everything fits in one answer
  writer.U8(0x00);  // Next Object Id
  writer.U8(static_cast<std::uint8_t>(list.count - first));
  for (std::size_t i = first; i < list.count; ++i) {
    const Object& object = list.objects[i];
    writer.U8(object.id);
    writer.U8(static_cast<std::uint8_t>(object.value.size()));
    for (char c : object.value) writer.U8(static_cast<std::uint8_t>(c));
  }
}

}  // namespace modbus
