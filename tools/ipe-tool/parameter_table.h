// The drive parameters tools/ipe knows by name: title, unit, decimal step and limits per model.
//
// This is the tool's ONE adapter onto a parameter table. Today it reads the project's register table
// (drive_link/registers/registers.csv through sim::RegisterInfo); the day the card serves its own parameter table (CIP
// Parameter object 0x0F), only parameter_table.cc changes. Nothing else in tools/ipe includes sim/.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace ipe {

enum class Model : std::uint8_t { kVfMb1, kVfS15 };

// "VF-MB1" / "VF-S15" (the Identity product names), and back (case-insensitive).
const char* ModelName(Model model);
std::optional<Model> ModelFromName(std::string_view name);

struct ParameterInfo {
  std::uint16_t number = 0;  // communication number (acc 0x0009, c500 0xC500, fd00 0xFD00)
  std::string title;         // panel title, lower case
  std::string function;      // short description
  std::string unit;          // "s", "Hz", "%", ... ; "" for plain numbers and codes
  bool bits = false;         // a bit field: shown in hex
  int decimals = 0;          // physical value = raw / 10^decimals
  std::int32_t min = 0;      // raw, for the model asked about
  std::int32_t max = 0;
  std::int32_t default_value = 0;
  bool host_writable = false;        // a host (Modbus, CIP) may write it
  bool setting = false;              // a parameter kept in the drive's EEPROM (what backup saves)
  bool monitor = false;              // computed by the drive, read-only
  bool write_during_run = false;     // false: the drive refuses a write while the motor runs
  bool effective_after_reset = false;  // acts only after f899 = 1 or a power cycle
  bool is_signed = false;            // the 16-bit word is two's complement

  std::uint16_t ToWord(std::int32_t raw) const { return static_cast<std::uint16_t>(raw & 0xFFFF); }
  std::int32_t FromWord(std::uint16_t word) const {
    return is_signed ? static_cast<std::int16_t>(word) : static_cast<std::int32_t>(word);
  }
};

// The parameter with this panel title (case-insensitive) on `model`; nothing when unknown or not on it.
std::optional<ParameterInfo> FindParameter(std::string_view title, Model model);

// What a backup saves for `model`: every host-writable EEPROM setting the model has, by number. Command
// registers (FA..), f899, typ and option-written values are not settings and are left out.
std::vector<ParameterInfo> BackupParameters(Model model);

}  // namespace ipe
