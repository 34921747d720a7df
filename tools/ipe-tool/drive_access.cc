#include "drive_access.h"

#include "base/byte_reader.h"
#include "base/byte_writer.h"
#include "cip/cip_status.h"
#include "cip/drive/parameter_object.h"
#include "failure.h"
#include "modbus/mbap.h"
#include "modbus/pdu.h"
#include "modbus_codec.h"

namespace ipe {

AccessResult EipDriveAccess::Read(std::uint16_t number) {
  const ParameterAddress address = ParameterAddressOf(number);
  const CipReply reply = session_.Request(cip::kServiceGetAttributeSingle,
                                          {address.class_id, address.instance, cip::drive::kParameterValueAttribute});
  AccessResult result;
  if (!reply.ok()) {
    result.refusal = FormatCipStatus(reply);
    return result;
  }
  if (reply.data.size() != 2) Fail(kExitUnreachable, "the card answered a parameter read with " +
                                                         std::to_string(reply.data.size()) + " bytes, not a UINT");
  result.ok = true;
  result.word = static_cast<std::uint16_t>(reply.data[0] | reply.data[1] << 8);
  return result;
}

AccessResult EipDriveAccess::Write(std::uint16_t number, std::uint16_t word) {
  const ParameterAddress address = ParameterAddressOf(number);
  const std::uint8_t value[2] = {static_cast<std::uint8_t>(word), static_cast<std::uint8_t>(word >> 8)};
  const CipReply reply = session_.Request(
      cip::kServiceSetAttributeSingle, {address.class_id, address.instance, cip::drive::kParameterValueAttribute},
      value);
  AccessResult result;
  result.ok = reply.ok();
  result.word = word;
  if (!reply.ok()) result.refusal = FormatCipStatus(reply);
  return result;
}

ModbusDriveAccess::ModbusDriveAccess(const std::string& host, std::uint16_t port, std::uint8_t unit, int timeout_ms)
    : tcp_(host, port, timeout_ms), unit_(unit) {}

std::vector<std::uint8_t> ModbusDriveAccess::Exchange(const std::vector<std::uint8_t>& request) {
  tcp_.Send(request);
  std::vector<std::uint8_t> stream;
  for (;;) {
    const modbus::FrameResult frame = modbus::FindFrame(stream);
    if (frame.check == modbus::FrameCheck::kComplete) {
      stream.resize(frame.adu_length);
      return stream;
    }
    if (frame.check == modbus::FrameCheck::kBadHeader) Fail(kExitUnreachable, tcp_.name() + ": a bad Modbus answer");
    const std::vector<std::uint8_t> more = tcp_.ReceiveSome();
    stream.insert(stream.end(), more.begin(), more.end());
  }
}

AccessResult ModbusDriveAccess::Read(std::uint16_t number) {
  const std::uint16_t transaction = ++transaction_;
  const ModbusAnswer answer = DecodeAnswer(Exchange(EncodeReadHoldingRegisters(transaction, unit_, number, 1)),
                                           transaction, modbus::fc::kReadHoldingRegisters);
  if (!answer.valid || (answer.exception == 0 && answer.values.size() != 1)) {
    Fail(kExitUnreachable, tcp_.name() + ": the Modbus answer does not decode");
  }
  AccessResult result;
  result.ok = answer.exception == 0;
  if (result.ok) result.word = answer.values[0];
  else result.refusal = FormatModbusException(answer.exception);
  return result;
}

AccessResult ModbusDriveAccess::Write(std::uint16_t number, std::uint16_t word) {
  const std::uint16_t transaction = ++transaction_;
  const ModbusAnswer answer = DecodeAnswer(Exchange(EncodeWriteSingleRegister(transaction, unit_, number, word)),
                                           transaction, modbus::fc::kWriteSingleRegister);
  if (!answer.valid) Fail(kExitUnreachable, tcp_.name() + ": the Modbus answer does not decode");
  AccessResult result;
  result.ok = answer.exception == 0;
  result.word = word;
  if (!result.ok) result.refusal = FormatModbusException(answer.exception);
  return result;
}

}  // namespace ipe

namespace ipe {

std::string ModbusDriveAccess::ProductName() {
  const std::uint16_t transaction = ++transaction_;
  for (const DeviceIdObject& object : DecodeDeviceIdAnswer(Exchange(EncodeReadDeviceId(transaction, unit_)), transaction)) {
    if (object.id == 0x04) return object.text;
  }
  return "";
}

}  // namespace ipe
