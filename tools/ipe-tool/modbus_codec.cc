#include "modbus_codec.h"

#include <cstdio>

#include "base/byte_reader.h"
#include "base/byte_writer.h"
#include "modbus/mbap.h"
#include "modbus/pdu.h"

namespace ipe {
namespace {

// The MBAP header of a request whose PDU is `pdu_length` bytes (the core writes it as for an answer).
void WriteRequestHeader(base::ByteWriter& out, std::uint16_t transaction, std::uint8_t unit, std::size_t pdu_length) {
  modbus::MbapHeader header;
  header.transaction_id = transaction;
  header.unit_id = unit;
  modbus::WriteMbapHeader(out, header, pdu_length);
}

std::vector<std::uint8_t> Adu(std::uint16_t transaction, std::uint8_t unit, std::uint8_t function,
                              std::uint16_t first, std::uint16_t second) {
  std::vector<std::uint8_t> buffer(modbus::kMbapHeaderBytes + 5);
  base::ByteWriter out(buffer);
  WriteRequestHeader(out, transaction, unit, 5);
  out.U8(function);
  out.U16Be(first);
  out.U16Be(second);
  return std::vector<std::uint8_t>(out.written().begin(), out.written().end());
}

}  // namespace

std::vector<std::uint8_t> EncodeReadHoldingRegisters(std::uint16_t transaction, std::uint8_t unit,
                                                     std::uint16_t address, std::uint16_t count) {
  return Adu(transaction, unit, modbus::fc::kReadHoldingRegisters, address, count);
}

std::vector<std::uint8_t> EncodeWriteSingleRegister(std::uint16_t transaction, std::uint8_t unit,
                                                    std::uint16_t address, std::uint16_t value) {
  return Adu(transaction, unit, modbus::fc::kWriteSingleRegister, address, value);
}

std::vector<std::uint8_t> EncodeReadDeviceId(std::uint16_t transaction, std::uint8_t unit) {
  std::vector<std::uint8_t> buffer(modbus::kMbapHeaderBytes + 4);
  base::ByteWriter out(buffer);
  WriteRequestHeader(out, transaction, unit, 4);
  out.U8(modbus::fc::kEncapsulatedInterface);
  out.U8(modbus::fc::kMeiReadDeviceId);
  out.U8(modbus::kDeviceIdRegular);
  out.U8(0);  // from object 0
  return std::vector<std::uint8_t>(out.written().begin(), out.written().end());
}

std::vector<DeviceIdObject> DecodeDeviceIdAnswer(std::span<const std::uint8_t> adu, std::uint16_t transaction) {
  const modbus::FrameResult frame = modbus::FindFrame(adu);
  if (frame.check != modbus::FrameCheck::kComplete || frame.adu_length != adu.size() ||
      frame.header.transaction_id != transaction) {
    return {};
  }
  base::ByteReader in(modbus::PduOf(adu));
  if (in.U8() != modbus::fc::kEncapsulatedInterface || in.U8() != modbus::fc::kMeiReadDeviceId) return {};
  (void)in.U8();  // code
  (void)in.U8();  // conformity level
  (void)in.U8();  // more follows
  (void)in.U8();  // next object id
  const std::uint8_t count = in.U8();
  std::vector<DeviceIdObject> objects;
  for (std::uint8_t i = 0; i < count && in.ok(); ++i) {
    DeviceIdObject object;
    object.id = in.U8();
    const std::uint8_t length = in.U8();
    for (std::uint8_t k = 0; k < length; ++k) object.text.push_back(static_cast<char>(in.U8()));
    objects.push_back(std::move(object));
  }
  if (!in.ok() || in.remaining() != 0) return {};
  return objects;
}

ModbusAnswer DecodeAnswer(std::span<const std::uint8_t> adu, std::uint16_t transaction, std::uint8_t function) {
  ModbusAnswer answer;
  const modbus::FrameResult frame = modbus::FindFrame(adu);
  if (frame.check != modbus::FrameCheck::kComplete || frame.adu_length != adu.size() ||
      frame.header.transaction_id != transaction) {
    return answer;
  }
  base::ByteReader in(modbus::PduOf(adu));
  const std::uint8_t answered = in.U8();
  if (answered == (function | modbus::fc::kExceptionBit)) {
    answer.exception = in.U8();
    answer.valid = in.ok() && in.remaining() == 0;
    return answer;
  }
  if (answered != function) return answer;
  if (function == modbus::fc::kReadHoldingRegisters) {
    const std::uint8_t count = in.U8();
    if (count % 2 != 0 || in.remaining() != count) return answer;
    for (std::uint8_t i = 0; i < count / 2; ++i) answer.values.push_back(in.U16Be());
  } else {
    (void)in.U16Be();  // the address echoed
    answer.values.push_back(in.U16Be());
    if (in.remaining() != 0) return answer;
  }
  answer.valid = in.ok();
  return answer;
}

std::string FormatModbusException(std::uint8_t code) {
  const char* name = "exception";
  switch (static_cast<modbus::ExceptionCode>(code)) {
    case modbus::ExceptionCode::kIllegalFunction: name = "illegal function"; break;
    case modbus::ExceptionCode::kIllegalDataAddress: name = "illegal data address"; break;
    case modbus::ExceptionCode::kIllegalDataValue: name = "illegal data value"; break;
    case modbus::ExceptionCode::kServerDeviceFailure: name = "server device failure"; break;
    case modbus::ExceptionCode::kGatewayPathUnavailable: name = "gateway path unavailable"; break;
    case modbus::ExceptionCode::kNone: break;
  }
  char text[64];
  std::snprintf(text, sizeof text, "Modbus exception %02X (%s)", code, name);
  return text;
}

}  // namespace ipe
