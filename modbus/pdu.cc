#include "modbus/pdu.h"

namespace modbus {
namespace {

// Each decoder gets the PDU after its function byte and checks the exact length of its layout: a PDU
// longer or shorter than its function's layout is "illegal data value" (decided, docs/modbus.md).
ExceptionCode DecodeReadHolding(base::ByteReader& reader, Request& request) {
  request.read_address = reader.U16Be();
  request.read_count = reader.U16Be();
  if (!reader.ok() || reader.remaining() != 0) return ExceptionCode::kIllegalDataValue;
  if (request.read_count < 1 || request.read_count > kMaxReadRegisters) return ExceptionCode::kIllegalDataValue;
  return ExceptionCode::kNone;
}

ExceptionCode DecodeWriteSingle(base::ByteReader& reader, Request& request) {
  request.write_address = reader.U16Be();
  request.write_values[0] = reader.U16Be();
  request.write_count = 1;
  if (!reader.ok() || reader.remaining() != 0) return ExceptionCode::kIllegalDataValue;
  return ExceptionCode::kNone;
}

// Count, byte count and values of a write (FC 16 and the write half of FC 23).
ExceptionCode DecodeWriteValues(base::ByteReader& reader, Request& request, std::uint16_t max_count) {
  request.write_count = reader.U16Be();
  const std::uint8_t byte_count = reader.U8();
  if (!reader.ok()) return ExceptionCode::kIllegalDataValue;
  if (request.write_count < 1 || request.write_count > max_count) return ExceptionCode::kIllegalDataValue;
  if (byte_count != 2 * request.write_count || reader.remaining() != byte_count) {
    return ExceptionCode::kIllegalDataValue;
  }
  for (std::uint16_t i = 0; i < request.write_count; ++i) request.write_values[i] = reader.U16Be();
  return reader.ok() ? ExceptionCode::kNone : ExceptionCode::kIllegalDataValue;
}

ExceptionCode DecodeWriteMultiple(base::ByteReader& reader, Request& request) {
  request.write_address = reader.U16Be();
  return DecodeWriteValues(reader, request, kMaxWriteRegisters);
}

// The Modbus layout: read address, read count, write address, write count, byte count, values (the
// seed's §8.7 tables repeat FC 16's and are not followed).
ExceptionCode DecodeReadWrite(base::ByteReader& reader, Request& request) {
  request.read_address = reader.U16Be();
  request.read_count = reader.U16Be();
  request.write_address = reader.U16Be();
  if (!reader.ok()) return ExceptionCode::kIllegalDataValue;
  if (request.read_count < 1 || request.read_count > kMaxIoScanReadWords) return ExceptionCode::kIllegalDataValue;
  return DecodeWriteValues(reader, request, kMaxIoScanWriteWords);
}

ExceptionCode DecodeEncapsulated(base::ByteReader& reader, Request& request) {
  const std::uint8_t mei_type = reader.U8();
  if (!reader.ok()) return ExceptionCode::kIllegalDataValue;
  // Another MEI type (0x0D CANopen) is a function the card does not serve.
  if (mei_type != fc::kMeiReadDeviceId) return ExceptionCode::kIllegalFunction;
  request.device_id_code = reader.U8();
  request.object_id = reader.U8();
  if (!reader.ok() || reader.remaining() != 0) return ExceptionCode::kIllegalDataValue;
  if (request.device_id_code < kDeviceIdBasic || request.device_id_code > kDeviceIdExtended) {
    return ExceptionCode::kIllegalDataValue;
  }
  return ExceptionCode::kNone;
}

}  // namespace

UnitKind ClassifyUnit(std::uint8_t unit_id) {
  if (unit_id <= 248) return UnitKind::kDrive;
  if (unit_id == 251) return UnitKind::kOptionBoard;
  if (unit_id == 255) return UnitKind::kIoScanner;
  return UnitKind::kNone;
}

DecodedRequest DecodeRequest(std::span<const std::uint8_t> pdu) {
  DecodedRequest decoded;
  base::ByteReader reader(pdu);
  decoded.request.function = reader.U8();
  if (!reader.ok()) {
    decoded.exception = ExceptionCode::kIllegalFunction;
    return decoded;
  }
  Request& request = decoded.request;
  switch (request.function) {
    case fc::kReadHoldingRegisters:
      decoded.exception = DecodeReadHolding(reader, request);
      break;
    case fc::kWriteSingleRegister:
      decoded.exception = DecodeWriteSingle(reader, request);
      break;
    case fc::kWriteMultipleRegisters:
      decoded.exception = DecodeWriteMultiple(reader, request);
      break;
    case fc::kReadWriteMultipleRegisters:
      decoded.exception = DecodeReadWrite(reader, request);
      break;
    case fc::kEncapsulatedInterface:
      decoded.exception = DecodeEncapsulated(reader, request);
      break;
    default:
      decoded.exception = ExceptionCode::kIllegalFunction;
      break;
  }
  return decoded;
}

bool IsWriteFunction(std::uint8_t function) {
  return function == fc::kWriteSingleRegister || function == fc::kWriteMultipleRegisters ||
         function == fc::kReadWriteMultipleRegisters;
}

void WriteException(base::ByteWriter& writer, std::uint8_t function, ExceptionCode code) {
  writer.U8(static_cast<std::uint8_t>(function | fc::kExceptionBit));
  writer.U8(static_cast<std::uint8_t>(code));
}

void WriteRegisterValues(base::ByteWriter& writer, std::uint8_t function, std::span<const std::uint16_t> values) {
  writer.U8(function);
  writer.U8(static_cast<std::uint8_t>(2 * values.size()));
  for (std::uint16_t value : values) writer.U16Be(value);
}

void WriteSingleRegisterAnswer(base::ByteWriter& writer, std::uint16_t address, std::uint16_t value) {
  writer.U8(fc::kWriteSingleRegister);
  writer.U16Be(address);
  writer.U16Be(value);
}

void WriteMultipleRegistersAnswer(base::ByteWriter& writer, std::uint16_t address, std::uint16_t count) {
  writer.U8(fc::kWriteMultipleRegisters);
  writer.U16Be(address);
  writer.U16Be(count);
}

}  // namespace modbus
