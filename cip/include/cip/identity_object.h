// Identity object 0x01 (manual §4.1): one instance.
//
//   class attributes  1 revision 1, 2 max instance 1, 3 instances 1, 4 optional attributes (none),
//                     6 max class attribute 7, 7 max instance attribute 7
//   class services    Get_Attributes_All 0x01, Get_Attribute_Single 0x0E
//   instance          1 vendor 377, 2 device type 2 (AC drive), 3 product code 32000 VF-MB1 /
//                     32001 VF-S15, 4 revision 1.8, 5 status WORD, 6 serial number (last 4 MAC bytes),
//                     7 product name "VF-MB1" / "VF-S15"
//   instance services Get_Attributes_All 0x01, Reset 0x05 (type 0 restart, 1 factory defaults),
//                     Get_Attribute_Single 0x0E
//
// Serial number: the MAC's last four bytes read as one big-endian number, so that the serial shown
// by a tool in hex spells the MAC's tail: MAC 00-80-F4-7D-02-C0 gives 0xF47D02C0, sent as C0 02 7D F4.
#pragma once

#include <cstdint>
#include <span>
#include <string_view>

#include "cip/encapsulation.h"
#include "cip/object_model.h"
#include "cip/providers.h"
#include "hal/reset.h"

namespace cip {

// Class attribute 1 (also the EDS's [Identity Class] Revision).
inline constexpr std::uint16_t kIdentityClassRevision = 1;
inline constexpr std::uint16_t kVendorIdToshiba = 377;
inline constexpr std::uint16_t kDeviceTypeAcDrive = 2;
inline constexpr std::uint16_t kProductCodeVfMb1 = 32000;
inline constexpr std::uint16_t kProductCodeVfS15 = 32001;
inline constexpr std::uint8_t kMajorRevision = 1;
inline constexpr std::uint8_t kMinorRevision = 8;
// ListIdentity's state byte: the card has no Identity attribute 8, so it reports "not implemented".
inline constexpr std::uint8_t kIdentityStateUnknown = 0xFF;

// Product code and name of the card on an inverter model (attributes 3 and 7; the EDS of that model).
std::uint16_t ProductCodeOf(DriveModel model);
std::string_view ProductNameOf(DriveModel model);

std::uint32_t SerialNumberFromMac(const base::MacAddress& mac);
std::uint16_t EncodeStatusWord(const DeviceStatus& status);

class IdentityObject final : public AttributeHandler {
 public:
  IdentityObject(const DeviceInfoProvider& device, hal::ResetControl& reset);

  CipObject& object() { return object_; }
  // The ListIdentity item, with the card's socket address filled in by the caller.
  IdentityItem ListIdentityItem(const SocketAddress& socket_address) const;

  std::uint32_t MaxInstance() const override { return 1; }
  std::span<const AttributeSpec> InstanceAttributes(std::uint32_t instance) const override;
  void GetInstanceAttribute(std::uint32_t instance, std::uint16_t id, base::ByteWriter& out) override;
  ServiceStatus ExecuteOther(const ServiceRequest& request, base::ByteWriter& reply) override;

 private:
  std::uint16_t ProductCode() const;
  std::string_view ProductName() const;

  const DeviceInfoProvider& device_;
  hal::ResetControl& reset_;
  AttributeObject object_;
};

}  // namespace cip
