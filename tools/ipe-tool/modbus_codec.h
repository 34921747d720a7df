// Modbus TCP requests tools/ipe sends and the answers it reads, with the project's Modbus core
// (modbus/mbap.h framing, modbus/pdu.h function and exception codes, base/byte_reader.h). Pure functions.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace ipe {

// Whole ADUs (MBAP header + PDU).
std::vector<std::uint8_t> EncodeReadHoldingRegisters(std::uint16_t transaction, std::uint8_t unit,
                                                     std::uint16_t address, std::uint16_t count);
std::vector<std::uint8_t> EncodeWriteSingleRegister(std::uint16_t transaction, std::uint8_t unit,
                                                    std::uint16_t address, std::uint16_t value);

// FC 43 / MEI 14 Read Device Identification, regular (code 02) from object 0.
std::vector<std::uint8_t> EncodeReadDeviceId(std::uint16_t transaction, std::uint8_t unit);
// The objects of its answer: id -> text (object 04 is the drive's product name, "VF-MB1"). Empty when
// the answer does not decode or is an exception.
struct DeviceIdObject {
  std::uint8_t id = 0;
  std::string text;
};
std::vector<DeviceIdObject> DecodeDeviceIdAnswer(std::span<const std::uint8_t> adu, std::uint16_t transaction);

struct ModbusAnswer {
  bool valid = false;          // framed, the right transaction and function
  std::uint8_t exception = 0;  // the exception code of an exception answer, else 0
  std::vector<std::uint16_t> values;  // FC 03: the registers; FC 06: the echoed value
};

// Decodes a whole ADU answering `function` of `transaction`.
ModbusAnswer DecodeAnswer(std::span<const std::uint8_t> adu, std::uint16_t transaction, std::uint8_t function);

// "Modbus exception 02 (illegal data address)".
std::string FormatModbusException(std::uint8_t code);

}  // namespace ipe
