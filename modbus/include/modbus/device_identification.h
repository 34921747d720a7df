// Function 43 / MEI 14, Read Device Identification (seed 000 §8.8).
//
// Two identities: the drive's (unit 248, and decided: units 0-247, which reach the same drive) and
// the option board's (unit 251, and decided: unit 255, the id a Modbus TCP client uses for "the device
// itself"). Conformity level 2 (regular identification, stream access only), everything in one answer
// (More Follows 0, Next Object Id 0). The seed lists only objects 0-2 for unit 251; the regular objects
// are optional in the Modbus specification, so its regular and extended answers hold the same three.
#pragma once

#include <cstdint>
#include <string_view>

#include "base/byte_reader.h"
#include "base/byte_writer.h"
#include "modbus/option_board.h"

namespace modbus {

enum class IdentitySubject : std::uint8_t { kDrive, kOptionBoard };

inline constexpr std::uint8_t kConformityLevel = 0x02;
inline constexpr std::string_view kVendorName = "TOSHIBA";
inline constexpr std::string_view kOptionBoardProductCode = "IPE002Z";

// Writes the answer PDU for a request already decoded (code 01-03). The stream starts at `object_id`
// when that object belongs to the requested category, otherwise at object 0 (Modbus Application
// Protocol 1.1b3 §6.21: an unknown object id restarts the stream).
void WriteDeviceIdentification(base::ByteWriter& writer, IdentitySubject subject, const OptionBoardData& data,
                               std::uint8_t device_id_code, std::uint8_t object_id);

}  // namespace modbus
