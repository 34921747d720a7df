// The CIP Parameter object, class 0x0F (CIP Vol. 1 §5A; docs/eds.md "Parameter object 0x0F"): one
// instance per row of the card's parameter table (drive_link/parameter_table.h), instance n = row n - 1,
// the same numbering as the EDS's ParamN. Attribute 1 is the register's value, read and written over the
// drive link through the DriveAccessJournal as attribute 3 of 0x64/0x65 is (deferred replies); the
// others describe it from the table, with min/max/default of the model the card has detected (VF-MB1
// until FB05 says VF-S15; cip::DeviceInfoProvider::Model).
//
//   class      1 revision 1 (UINT), 2 max instance N, 3 instances N, 8 parameter class descriptor
//              0x000B (instances, full attributes, stored in non-volatile memory), 9 configuration
//              assembly 0, 10 native language 0 (English); service Get_Attribute_Single 0x0E
//   instance   services Get_Attribute_Single 0x0E, Set_Attribute_Single 0x10 (attribute 1 only)
//     1  value             UINT/INT   the register                                  Get/Set (monitors Get)
//     2  link path size    USINT      8
//     3  link path         EPATH      20 65 25 00 nn nn 30 03 (au1: 20 64 25 00 00 40 30 03)
//     4  descriptor        WORD       bit 2 scaling (decimals > 0), bits 4+5 read-only monitor
//     5  data type         USINT      0xC7 UINT, 0xC3 INT
//     6  data size         USINT      2
//     7  name              SHORT_STRING  the title (acc)
//     8  units             SHORT_STRING  Hz, s, %, ... or empty
//     9  help              SHORT_STRING  the function text
//     10 min, 11 max, 12 default  as attribute 5, of the detected model
//     13 multiplier 1, 14 divisor 10^decimals, 15 base 1 (UINT), 16 offset 0 (INT)
//     21 decimal precision USINT      decimals
//
// A Set of attribute 1 is a user's explicit parameter write (RAM and EEPROM, kParameterWriteMode), as
// through 0x64/0x65: the value is checked against min/max first (0x09, nothing sent), then the access
// errors map as AccessErrorStatus says, a register the inverter lacks as 0x14 (the instance is a table
// row and exists). Sets of control registers are subject to the exclusive-owner lock (control_lock.h).
#pragma once

#include <array>
#include <cstdint>
#include <span>

#include "cip/drive/drive_access_journal.h"
#include "cip/drive/register_attribute_object.h"
#include "cip/object_model.h"
#include "cip/providers.h"
#include "drive_link/parameter_table.h"

namespace cip::drive {

inline constexpr std::uint16_t kClassParameter = 0x0F;
inline constexpr std::uint16_t kParameterValue = 1;

inline constexpr std::uint8_t kDataTypeInt = 0xC3;
inline constexpr std::uint8_t kDataTypeUint = 0xC7;
// Parameter descriptor bits (§5A attribute 4).
inline constexpr std::uint16_t kDescriptorScaling = 1U << 2;
inline constexpr std::uint16_t kDescriptorReadOnly = 1U << 4;
inline constexpr std::uint16_t kDescriptorMonitor = 1U << 5;
// Class attribute 8: bit 0 parameter instances, bit 1 full attributes, bit 3 stored in non-volatile memory.
inline constexpr std::uint16_t kParameterClassDescriptor = 0x000B;
inline constexpr std::size_t kParameterLinkPathSize = 8;

// What the Parameter object and the EDS say about a row.
std::uint16_t ParameterDescriptor(const drive_link::ParameterInfo& row);
std::uint8_t ParameterDataType(const drive_link::ParameterInfo& row);
std::uint16_t ScalingDivisor(const drive_link::ParameterInfo& row);  // 10^decimals
// The path of the value (attribute 3): attribute 3 of the 0x65 instance of the number (0x64 for au1).
std::array<std::uint8_t, kParameterLinkPathSize> ParameterLinkPath(std::uint16_t number);
drive_link::InverterModel InverterModelOf(DriveModel model);

class CipParameterObject final : public RegisterAttributeHandler {
 public:
  CipParameterObject(DriveAccessJournal& journal, const DeviceInfoProvider& device);

  CipObject& object() { return object_; }

  std::uint32_t MaxInstance() const override;
  std::span<const AttributeSpec> InstanceAttributes(std::uint32_t instance) const override;
  void GetInstanceAttribute(std::uint32_t instance, std::uint16_t id, base::ByteWriter& out) override;
  ServiceStatus SetInstanceAttribute(std::uint32_t instance, std::uint16_t id, base::ByteReader& value) override;
  void GetClassAttribute(std::uint16_t id, base::ByteWriter& out) override;

 private:
  const DeviceInfoProvider& device_;
  RegisterAttributeObject object_;
};

}  // namespace cip::drive
