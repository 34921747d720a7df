// The card's parameter table (docs/eds.md "Parameters"): the registers a commissioning engineer reads
// and sets, generated at build time from drive_link/registers/registers.csv (tools/gen_parameter_table.py), so the
// CIP Parameter object 0x0F, the EDS and the host tool show one table. Flash only: a constexpr array.
//
// Rows: every host-writable register (access rw) and every read-only monitor (FB-FE, storage monitor),
// in communication-number order; the row index + 1 is the Parameter object instance and the EDS ParamN.
// Values are raw 16-bit register patterns: a signed parameter (fd18, fd20, fe18, fe36) holds two's
// complement, to be read as INT; the others as UINT. decimals is the register's step (0.1 s -> 1).
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>

namespace drive_link {

enum class InverterModel : std::uint8_t { kVfMb1, kVfS15 };

// Which inverters have the register (registers.csv column models).
enum ModelMask : std::uint8_t { kVfMb1Only = 1, kVfS15Only = 2, kBothModels = 3 };

struct ParameterLimits {
  std::uint16_t min = 0;
  std::uint16_t max = 0;
  std::uint16_t default_value = 0;
};

struct ParameterInfo {
  std::uint16_t number = 0;        // communication number, e.g. 0x0009 (acc)
  ParameterLimits vf_mb1;
  ParameterLimits vf_s15;
  std::uint8_t decimals = 0;       // 0-3: the value is raw / 10^decimals in `unit`
  bool is_signed = false;          // INT rather than UINT
  bool read_only = false;          // a monitor: nobody writes it
  ModelMask models = kBothModels;
  const char* title = "";          // the panel title, e.g. "acc"
  const char* unit = "";           // "Hz", "s", "%", ... or "" for codes, bit fields and characters
  const char* help = "";           // the function text, at most 255 characters

  const ParameterLimits& Limits(InverterModel model) const {
    return model == InverterModel::kVfS15 ? vf_s15 : vf_mb1;
  }
  // A raw pattern as the number it stands for (sign-extended for signed parameters).
  std::int32_t Value(std::uint16_t raw) const {
    return is_signed ? static_cast<std::int16_t>(raw) : static_cast<std::int32_t>(raw);
  }
  // Whether a raw value lies within the model's limits (compared as INT or UINT).
  bool InRange(InverterModel model, std::uint16_t raw) const {
    const ParameterLimits& limits = Limits(model);
    return Value(raw) >= Value(limits.min) && Value(raw) <= Value(limits.max);
  }
};

// The whole table, in communication-number order.
std::span<const ParameterInfo> CardParameters();
// The row of a communication number or a title (exact, lower case), or nothing.
std::optional<std::size_t> FindParameterByNumber(std::uint16_t number);
std::optional<std::size_t> FindParameterByTitle(std::string_view title);

}  // namespace drive_link
