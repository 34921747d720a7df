// The simulated VF-MB1 / VF-S15 inverter's register table: what exists, its limits and how it is stored.
//
// Data only. The one source is drive_link/registers/registers.csv (the inverter's registers, which the
// card and the simulator share); tools/gen_register_table.py checks it
// and turns it into the constexpr array that register_table.cc serves (sorted by number). The CSV's
// `source` column says where every row comes from and which values are assumed; docs/simulator.md
// lists the assumptions. Behaviour (what a write to FA06 does, how FD01 is computed) belongs to the
// simulator, which looks registers up here.
//
// Vocabulary:
// - A register is named by its 16-bit communication number: 0xyz = parameters (fNNN = 0x0NNN, plus
//   named ones: acc = 0x0009), 0xCNNN = the option's c-parameters (c500 = 0xC500), 0xFAxx = command
//   registers, 0xFBxx/FCxx/FDxx/FExx = monitors. Numbers whose last hex digit is A-F never exist
//   (seed 000 section 8.9 note (5)); neither does any number missing from the table.
// - Values are integers in the register's unit step (`Scale`): acc = 100 means 10.0 s. A register whose
//   minimum is negative is signed: its 16-bit word is the two's complement (FE36 -100.00 % = 0xD8F0).
// - Limits are static. Run-time limits that depend on other registers (FA07 and sr1 up to fh, ll up to
//   ul) are the simulator's business; the static maximum here is the widest legal value.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string_view>

namespace sim {

// How a register keeps its value.
enum class StorageClass : std::uint8_t {
  kEeprom,    // parameter kept across power cycles (written to RAM, then EEPROM)
  kRamOnly,   // lost at power-off, and returns to its default on reset (FA commands, f899, typ, displays)
  kMonitor,   // computed by the drive, read-only
  kTripHold,  // read-only; follows the live value until a trip, then holds it until the trip is reset
};

// Who may write it.
enum class Access : std::uint8_t {
  kReadWrite,  // any host (Modbus, CIP, panel) within the limits
  kReadOnly,   // nobody; the drive produces the value
  kOption,     // the option card writes it through the drive link (actual IP, c555...); hosts only read
};

enum class Model : std::uint8_t { kVfMb1, kVfS15 };

// Which models have a register (bit per Model).
enum class ModelMask : std::uint8_t { kVfMb1 = 1, kVfS15 = 2, kBoth = 3 };

enum class Unit : std::uint8_t {
  kNone,  // a plain number or a code from a list
  kBits,  // a bit field
  kAscii, // one ASCII character (device name c081-c096)
  kHertz,
  kSecond,
  kPercent,
  kVolt,
  kAmpere,
  kKilowatt,
  kKilowattHour,
  kHour,
  kDegreeCelsius,
  kPulsesPerSecond,
  kRpm,
};

// Physical value = raw / 10^decimals in `unit`: {kHertz, 2} is 0.01 Hz, {kSecond, 1} is 0.1 s.
struct Scale {
  Unit unit;
  std::uint8_t decimals;
};

struct Limits {
  std::int32_t min;
  std::int32_t max;
  std::int32_t default_value;  // factory default; for monitors, the value before the drive computes one
};

struct RegisterInfo {
  std::uint16_t number;   // communication number
  const char* title;      // panel title, lower case ("acc", "c500", "fa06")
  const char* function;   // short description
  StorageClass storage;
  Access access;
  Limits mb1;             // VF-MB1
  Limits s15;             // VF-S15 (equal to mb1 unless the model differs)
  Scale scale;
  bool write_during_run;       // false: a write while the motor runs is refused
  bool effective_after_reset;  // the manual's (*3): the new value acts only after power-on or f899 = 1
  ModelMask models;

  constexpr const Limits& limits(Model model) const { return model == Model::kVfS15 ? s15 : mb1; }
  constexpr std::int32_t min(Model model) const { return limits(model).min; }
  constexpr std::int32_t max(Model model) const { return limits(model).max; }
  constexpr std::int32_t default_value(Model model) const { return limits(model).default_value; }

  constexpr bool AppliesTo(Model model) const {
    const ModelMask bit = model == Model::kVfS15 ? ModelMask::kVfS15 : ModelMask::kVfMb1;
    return (static_cast<std::uint8_t>(models) & static_cast<std::uint8_t>(bit)) != 0;
  }
  constexpr bool is_signed() const { return mb1.min < 0 || s15.min < 0; }
  // Hosts (Modbus clients, CIP, the panel) may write it; monitors and option-written values they may not.
  constexpr bool HostWritable() const { return access == Access::kReadWrite; }
  constexpr bool InRange(Model model, std::int32_t value) const {
    return value >= min(model) && value <= max(model);
  }
  // The 16-bit word on the wire for `value` (two's complement when signed), and back.
  constexpr std::uint16_t ToWord(std::int32_t value) const {
    return static_cast<std::uint16_t>(value & 0xFFFF);
  }
  constexpr std::int32_t FromWord(std::uint16_t word) const {
    if (is_signed()) return static_cast<std::int16_t>(word);
    return word;
  }
};

// False for numbers whose last hex digit is A-F: they do not exist on VF-MB1/S15 and multi-register
// transfers skip them (a 2-word read at acc 0x0009 returns acc and dec 0x0010).
constexpr bool CommunicationNumberMayExist(std::uint16_t number) { return (number & 0x000Fu) <= 9u; }

// Every register, sorted by ascending number.
std::span<const RegisterInfo> AllRegisters();

// The register with this number, or nullptr when it does not exist (binary search).
const RegisterInfo* FindRegister(std::uint16_t number);
// As above, and nullptr too when `model` does not have it.
const RegisterInfo* FindRegister(std::uint16_t number, Model model);

// By panel title, ignoring case: "acc", "ACC", "FA06", "c500". nullptr when unknown.
const RegisterInfo* FindRegisterByTitle(std::string_view title);

// "eeprom", "ram", "monitor", "trip-hold" (the CSV's words).
const char* StorageClassName(StorageClass storage);
// "vf-mb1", "vf-s15" (the --model values), and back; nullopt for anything else.
const char* ModelName(Model model);
std::optional<Model> ModelFromName(std::string_view name);

}  // namespace sim
