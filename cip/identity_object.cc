#include "cip/identity_object.h"

#include <array>
#include <string_view>

namespace cip {
namespace {

constexpr std::array<std::uint16_t, 6> kClassAttributes = {1, 2, 3, 4, 6, 7};
constexpr std::array<std::uint8_t, 2> kClassServices = {kServiceGetAttributesAll, kServiceGetAttributeSingle};
constexpr std::array<std::uint8_t, 3> kInstanceServices = {kServiceGetAttributesAll, kServiceReset,
                                                           kServiceGetAttributeSingle};
constexpr ClassSpec kIdentityClass = {
    kClassIdentity, kIdentityClassRevision, kClassAttributes, {}, {}, 7, 7, kClassServices, kInstanceServices,
};
constexpr std::array<AttributeSpec, 7> kAttributes = GettableAttributes<7>();

constexpr std::uint8_t kResetRestart = 0;
constexpr std::uint8_t kResetFactoryDefaults = 1;

std::span<const std::uint8_t> Bytes(std::string_view text) {
  return std::span<const std::uint8_t>(reinterpret_cast<const std::uint8_t*>(text.data()), text.size());
}

}  // namespace

std::uint16_t ProductCodeOf(DriveModel model) {
  return model == DriveModel::kVfS15 ? kProductCodeVfS15 : kProductCodeVfMb1;
}

std::string_view ProductNameOf(DriveModel model) { return model == DriveModel::kVfS15 ? "VF-S15" : "VF-MB1"; }

// The MAC's last four octets, read as one big-endian number.
std::uint32_t SerialNumberFromMac(const base::MacAddress& mac) {
  base::ByteReader low(std::span(mac.octets()).subspan(2));
  return low.U32Be();
}

std::uint16_t EncodeStatusWord(const DeviceStatus& status) {
  // Bit 0 (owned) is not supported (§4.1); bits 1, 3 and 12-15 are reserved.
  std::uint16_t word = 0;
  if (status.configured) word |= 1U << 2;
  word = static_cast<std::uint16_t>(word | static_cast<std::uint16_t>(status.extended) << 4);
  if (status.minor_recoverable_fault) word |= 1U << 8;
  if (status.minor_unrecoverable_fault) word |= 1U << 9;
  if (status.major_recoverable_fault) word |= 1U << 10;
  if (status.major_unrecoverable_fault) word |= 1U << 11;
  return word;
}

IdentityObject::IdentityObject(const DeviceInfoProvider& device, hal::ResetControl& reset)
    : device_(device), reset_(reset), object_(kIdentityClass, *this) {}

std::uint16_t IdentityObject::ProductCode() const { return ProductCodeOf(device_.Model()); }

std::string_view IdentityObject::ProductName() const { return ProductNameOf(device_.Model()); }

IdentityItem IdentityObject::ListIdentityItem(const SocketAddress& socket_address) const {
  IdentityItem item;
  item.socket_address = socket_address;
  item.vendor_id = kVendorIdToshiba;
  item.device_type = kDeviceTypeAcDrive;
  item.product_code = ProductCode();
  item.major_revision = kMajorRevision;
  item.minor_revision = kMinorRevision;
  item.status = EncodeStatusWord(device_.Status());
  item.serial_number = SerialNumberFromMac(device_.Mac());
  (void)item.product_name.Assign(ProductName());  // 6 characters always fit
  item.state = kIdentityStateUnknown;
  return item;
}

std::span<const AttributeSpec> IdentityObject::InstanceAttributes(std::uint32_t) const { return kAttributes; }

void IdentityObject::GetInstanceAttribute(std::uint32_t, std::uint16_t id, base::ByteWriter& out) {
  switch (id) {
    case 1:
      out.U16Le(kVendorIdToshiba);
      break;
    case 2:
      out.U16Le(kDeviceTypeAcDrive);
      break;
    case 3:
      out.U16Le(ProductCode());
      break;
    case 4:
      out.U8(kMajorRevision);
      out.U8(kMinorRevision);
      break;
    case 5:
      out.U16Le(EncodeStatusWord(device_.Status()));
      break;
    case 6:
      out.U32Le(SerialNumberFromMac(device_.Mac()));
      break;
    case 7:
      PutShortString(Bytes(ProductName()), out);
      break;
    default:
      break;
  }
}

ServiceStatus IdentityObject::ExecuteOther(const ServiceRequest& request, base::ByteWriter&) {
  if (request.service != kServiceReset) return Error(GeneralStatus::kServiceNotSupported);
  // The reset type is optional and defaults to 0. Type 2 (keep communication settings) and the
  // vendor-specific range are not offered.
  base::ByteReader in(request.data);
  if (in.remaining() > 1) return Error(GeneralStatus::kTooMuchData);
  const std::uint8_t type = in.empty() ? kResetRestart : in.U8();
  if (type == kResetRestart) {
    reset_.RequestReset(hal::ResetKind::kRestart);
  } else if (type == kResetFactoryDefaults) {
    reset_.RequestReset(hal::ResetKind::kFactoryDefaults);
  } else {
    return Error(GeneralStatus::kInvalidParameter);
  }
  return Success();  // the reply goes out before the reset (hal::ResetControl's contract)
}

}  // namespace cip
