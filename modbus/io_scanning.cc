#include "modbus/io_scanning.h"

namespace modbus {
namespace {

// c600-c603 = 0.0.0.0: no master configured, any client may scan.
constexpr base::Ipv4Address kAnyMaster{0, 0, 0, 0};

bool InRange(std::uint16_t address, std::uint16_t count) {
  return static_cast<std::uint32_t>(address) + count <= kIoScanWordCount;
}

// Words 1-6 of the periodic area are scanner words 1-6; word 0 and 7-31 are reserved.
bool IsScannerWord(std::uint32_t word) { return word >= 1 && word <= drive_link::kScannerWordCount; }

void WriteOutputWords(drive_link::ScannerImage& scanner, std::uint16_t address,
                      std::span<const std::uint16_t> values) {
  drive_link::ScannerWords words = scanner.CommandWords();
  bool touched = false;
  for (std::size_t i = 0; i < values.size(); ++i) {
    const std::uint32_t word = address + static_cast<std::uint32_t>(i);
    if (!IsScannerWord(word)) continue;  // reserved: accepted, ignored
    words[word - 1] = values[i];
    touched = true;
  }
  if (touched) scanner.SetCommandWords(words);
}

void ReadInputWords(const drive_link::ScannerImage& scanner, std::uint16_t address, std::uint16_t count,
                    base::ByteWriter& writer, std::uint8_t function) {
  const drive_link::ScannerWords monitors = scanner.MonitorWords();
  writer.U8(function);
  writer.U8(static_cast<std::uint8_t>(2 * count));
  for (std::uint16_t i = 0; i < count; ++i) {
    const std::uint32_t word = static_cast<std::uint32_t>(address) + i;
    writer.U16Be(IsScannerWord(word) ? monitors[word - 1] : std::uint16_t{0});
  }
}

}  // namespace

ExceptionCode IoScanningAccess(const config::CardConfig& config, const base::Ipv4Address& peer) {
  if (!config.io_scanning) return ExceptionCode::kIllegalFunction;
  if (config.modbus_master != kAnyMaster && config.modbus_master != peer) {
    return ExceptionCode::kIllegalFunction;
  }
  return ExceptionCode::kNone;
}

bool ControlLockedFor(const config::CardConfig& config, const base::Ipv4Address& peer) {
  return config.io_scanning && config.modbus_master != kAnyMaster && config.modbus_master != peer;
}

bool IsIoScanningWrite(const Request& request) { return IsWriteFunction(request.function); }

void ServeIoScanner(const Request& request, drive_link::ScannerImage& scanner, base::ByteWriter& writer) {
  switch (request.function) {
    case fc::kReadHoldingRegisters:
      if (!InRange(request.read_address, request.read_count)) break;
      ReadInputWords(scanner, request.read_address, request.read_count, writer, request.function);
      return;
    case fc::kWriteSingleRegister:
      if (!InRange(request.write_address, 1)) break;
      WriteOutputWords(scanner, request.write_address, request.values());
      WriteSingleRegisterAnswer(writer, request.write_address, request.write_values[0]);
      return;
    case fc::kWriteMultipleRegisters:
      if (!InRange(request.write_address, request.write_count)) break;
      WriteOutputWords(scanner, request.write_address, request.values());
      WriteMultipleRegistersAnswer(writer, request.write_address, request.write_count);
      return;
    case fc::kReadWriteMultipleRegisters:
      // Both ranges are checked before anything is written.
      if (!InRange(request.read_address, request.read_count) ||
          !InRange(request.write_address, request.write_count)) {
        break;
      }
      WriteOutputWords(scanner, request.write_address, request.values());
      ReadInputWords(scanner, request.read_address, request.read_count, writer, request.function);
      return;
    default:
      WriteException(writer, request.function, ExceptionCode::kIllegalFunction);
      return;
  }
  WriteException(writer, request.function, ExceptionCode::kIllegalDataAddress);
}

}  // namespace modbus
