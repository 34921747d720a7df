// Parameter values as a user types and reads them: "5.0", "5", "5s", "5.0 s" for acc (0.1 s steps),
// "60Hz" or "60" for fh, "0x0404" for a bit field. Pure functions, no I/O.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "parameter_table.h"

namespace ipe {

struct ParsedValue {
  bool ok = false;
  std::int32_t raw = 0;  // in register units (acc 5.0 s -> 50)
  std::string error;     // when !ok: why, naming the parameter
};

// Parses `text` for `info`: a decimal number with at most info.decimals digits after the point (or a
// 0x hex integer), then optionally the parameter's unit (case-insensitive, a space allowed before it).
// The limits are not checked here (CheckRange).
ParsedValue ParseValue(std::string_view text, const ParameterInfo& info);

// An empty string when raw is inside the parameter's limits for the model, else the message
// ("acc = 6000.1 s is outside 0.1 .. 6000.0 s on VF-MB1").
std::string CheckRange(std::int32_t raw, const ParameterInfo& info, Model model);

// "5.0" (decimals as the register's step), "0x0404" for bit fields; no unit.
std::string FormatValue(std::int32_t raw, const ParameterInfo& info);
// FormatValue and the unit: "5.0 s", "60.00 Hz", "4".
std::string FormatWithUnit(std::int32_t raw, const ParameterInfo& info);

// Durations on the command line: "10ms", "10" (ms), "1s", "1.5s". False for anything else or 0.
bool ParseMillis(std::string_view text, std::uint32_t& millis);

}  // namespace ipe
