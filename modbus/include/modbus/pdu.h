// Modbus PDUs: the functions the card serves (seed 000 §8.3), request decoding with the limits and
// exception codes of §8.4-§8.8, and the answers. The rules for cases the seed leaves open are in
// docs/modbus.md "Exceptions"; each is named where it is decided below.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "base/byte_reader.h"
#include "base/byte_writer.h"

namespace modbus {

namespace fc {
inline constexpr std::uint8_t kReadHoldingRegisters = 0x03;
inline constexpr std::uint8_t kWriteSingleRegister = 0x06;
inline constexpr std::uint8_t kWriteMultipleRegisters = 0x10;
inline constexpr std::uint8_t kReadWriteMultipleRegisters = 0x17;
inline constexpr std::uint8_t kEncapsulatedInterface = 0x2B;
// The MEI type of Read Device Identification inside function 43.
inline constexpr std::uint8_t kMeiReadDeviceId = 0x0E;
// Set in the function code of an exception answer.
inline constexpr std::uint8_t kExceptionBit = 0x80;
}  // namespace fc

enum class ExceptionCode : std::uint8_t {
  kNone = 0x00,
  kIllegalFunction = 0x01,
  kIllegalDataAddress = 0x02,
  kIllegalDataValue = 0x03,
  kServerDeviceFailure = 0x04,
  // A unit id with no server behind it (249, 250, 252-254). Decided: the card routes unit ids to its
  // servers like a gateway, and 0A is the Modbus answer of a gateway with no path for the unit.
  kGatewayPathUnavailable = 0x0A,
};

// Size limits of §8.3 (MB-2). FC 03 and FC 16 carry at most 63 words (the seed's request tables say
// 125/100; the function table and MB-2 say 63, which is what the card enforces). FC 23 carries at most
// 20 words each way (§8.3; §10.4's PL7 example configures 32, see docs/modbus.md).
inline constexpr std::uint16_t kMaxReadRegisters = 63;
inline constexpr std::uint16_t kMaxWriteRegisters = 63;
inline constexpr std::uint16_t kMaxIoScanReadWords = 20;
inline constexpr std::uint16_t kMaxIoScanWriteWords = 20;

// Read Device ID codes (§8.8). 04 (individual access) is not served: conformity level 2 is "regular
// identification, stream access only".
inline constexpr std::uint8_t kDeviceIdBasic = 0x01;
inline constexpr std::uint8_t kDeviceIdRegular = 0x02;
inline constexpr std::uint8_t kDeviceIdExtended = 0x03;

// Which server a unit id reaches (§8.2).
enum class UnitKind : std::uint8_t {
  kDrive,        // 0-248: the inverter's registers, address = communication number
  kOptionBoard,  // 251: the card's own registers
  kIoScanner,    // 255: the IO scanning words (§9.2)
  kNone,         // 249, 250, 252-254
};
UnitKind ClassifyUnit(std::uint8_t unit_id);

struct Request {
  std::uint8_t function = 0;
  // FC 03 and the read half of FC 23.
  std::uint16_t read_address = 0;
  std::uint16_t read_count = 0;
  // FC 06 (count 1), FC 16 and the write half of FC 23.
  std::uint16_t write_address = 0;
  std::uint16_t write_count = 0;
  std::array<std::uint16_t, kMaxWriteRegisters> write_values{};
  // FC 43 / MEI 14.
  std::uint8_t device_id_code = 0;
  std::uint8_t object_id = 0;

  std::span<const std::uint16_t> values() const {
    return std::span<const std::uint16_t>(write_values).first(write_count);
  }
};

struct DecodedRequest {
  Request request;
  // kNone: well formed. kIllegalFunction: a function (or MEI type) the card does not serve.
  // kIllegalDataValue: wrong PDU length, a count outside its limits, a byte count that does not
  // match the count, a Read Device ID code other than 01-03.
  ExceptionCode exception = ExceptionCode::kNone;
  bool ok() const { return exception == ExceptionCode::kNone; }
};

// Decodes a PDU (function code first). Reads nothing past the span's end.
DecodedRequest DecodeRequest(std::span<const std::uint8_t> pdu);

// Whether a function writes registers (FC 06, 16, 23).
bool IsWriteFunction(std::uint8_t function);

// Communication numbers whose last hex digit is A-F do not exist and are skipped in multi-register
// transfers (§8.9 (5)): register k of a transfer is the k-th existing number after the start, so two
// words from 0009 are 0009 (acc) and 0010 (dec). The start itself is used as given (a read of a start
// ending A-F yields 0x8000, a write is refused with 02).
constexpr std::uint32_t NextCommunicationNumber(std::uint32_t number) {
  std::uint32_t next = number + 1;
  if ((next & 0x000F) > 9) next = (next | 0x000F) + 1;
  return next;
}
// The number register `count - 1` of a transfer from `first` lands on; above 0xFFFF when the transfer
// runs past FFF9 (refused with 02 before anything is accessed).
constexpr std::uint32_t LastCommunicationNumber(std::uint16_t first, std::uint16_t count) {
  std::uint32_t number = first;
  for (std::uint16_t i = 1; i < count; ++i) number = NextCommunicationNumber(number);
  return number;
}

// The value a read of a communication number that does not exist returns (§8.4 note).
inline constexpr std::uint16_t kNoSuchRegisterValue = 0x8000;

// --- Answers (PDU only; the connection adds the MBAP header) ---
void WriteException(base::ByteWriter& writer, std::uint8_t function, ExceptionCode code);
// FC 03 and FC 23: function, byte count, the words.
void WriteRegisterValues(base::ByteWriter& writer, std::uint8_t function, std::span<const std::uint16_t> values);
// FC 06: the echo of the request.
void WriteSingleRegisterAnswer(base::ByteWriter& writer, std::uint16_t address, std::uint16_t value);
// FC 16: function, start address, count.
void WriteMultipleRegistersAnswer(base::ByteWriter& writer, std::uint16_t address, std::uint16_t count);

}  // namespace modbus
