#include "values.h"

#include <cctype>
#include <cstdio>
#include <cstdlib>

#include "text.h"

namespace ipe {
namespace {

std::int64_t Power10(int n) {
  std::int64_t p = 1;
  for (int i = 0; i < n; ++i) p *= 10;
  return p;
}

ParsedValue Fail(const ParameterInfo& info, std::string_view text, const std::string& why) {
  ParsedValue v;
  v.error = info.title + ": '" + std::string(text) + "' " + why;
  return v;
}

std::string UnitDescription(const ParameterInfo& info) {
  std::string step = "1";
  if (info.decimals > 0) step = "0." + std::string(static_cast<std::size_t>(info.decimals - 1), '0') + "1";
  return info.unit.empty() ? "steps of " + step : "steps of " + step + " " + info.unit;
}

}  // namespace

ParsedValue ParseValue(std::string_view text, const ParameterInfo& info) {
  const std::string_view all = Trim(text);
  std::string_view number = all;
  // Split off a trailing unit: everything after the last digit.
  std::size_t end = number.size();
  while (end > 0 && !std::isdigit(static_cast<unsigned char>(number[end - 1]))) --end;
  std::string_view unit = Trim(number.substr(end));
  number = number.substr(0, end);
  const bool hex = number.size() > 2 && number[0] == '0' && (number[1] == 'x' || number[1] == 'X');
  if (hex) {
    // Hex digits a-f were taken for a unit above; take the whole text as the number.
    number = all;
    unit = {};
    if (number.size() > 6) return Fail(info, text, "is not a 16-bit value");
    std::int64_t value = 0;
    for (std::size_t i = 2; i < number.size(); ++i) {
      const char c = static_cast<char>(std::tolower(static_cast<unsigned char>(number[i])));
      if (!std::isxdigit(static_cast<unsigned char>(c))) return Fail(info, text, "is not a number");
      value = value * 16 + (c <= '9' ? c - '0' : c - 'a' + 10);
    }
    ParsedValue v;
    v.ok = true;
    v.raw = static_cast<std::int32_t>(value);
    return v;
  }
  if (number.empty()) return Fail(info, text, "is not a number");
  if (!unit.empty() && !EqualsIgnoringCase(unit, info.unit)) {
    return Fail(info, text,
                info.unit.empty() ? "has a unit, but " + info.title + " is a plain number"
                                  : "has the wrong unit (" + info.title + " is in " + info.unit + ")");
  }
  bool negative = false;
  if (!number.empty() && (number[0] == '-' || number[0] == '+')) {
    negative = number[0] == '-';
    number.remove_prefix(1);
  }
  std::int64_t whole = 0;
  std::int64_t fraction = 0;
  int fraction_digits = 0;
  bool seen_point = false;
  bool seen_digit = false;
  for (char c : number) {
    if (c == '.' && !seen_point) {
      seen_point = true;
      continue;
    }
    if (!std::isdigit(static_cast<unsigned char>(c))) return Fail(info, text, "is not a number");
    seen_digit = true;
    if (seen_point) {
      if (++fraction_digits > info.decimals) {
        return Fail(info, text, "has more decimals than " + info.title + " takes (" + UnitDescription(info) + ")");
      }
      fraction = fraction * 10 + (c - '0');
    } else {
      whole = whole * 10 + (c - '0');
      if (whole > 1'000'000'000) return Fail(info, text, "is too large");
    }
  }
  if (!seen_digit) return Fail(info, text, "is not a number");
  std::int64_t raw = whole * Power10(info.decimals) + fraction * Power10(info.decimals - fraction_digits);
  if (negative) raw = -raw;
  if (raw > 0x7FFFFFFF || raw < -0x7FFFFFFF) return Fail(info, text, "is too large");
  ParsedValue v;
  v.ok = true;
  v.raw = static_cast<std::int32_t>(raw);
  return v;
}

std::string CheckRange(std::int32_t raw, const ParameterInfo& info, Model model) {
  if (raw >= info.min && raw <= info.max) return "";
  return info.title + " = " + FormatWithUnit(raw, info) + " is outside " + FormatValue(info.min, info) + " .. " +
         FormatWithUnit(info.max, info) + " on " + ModelName(model);
}

std::string FormatValue(std::int32_t raw, const ParameterInfo& info) {
  char buffer[32];
  if (info.bits) {
    std::snprintf(buffer, sizeof buffer, "0x%04X", static_cast<unsigned>(raw) & 0xFFFFu);
    return buffer;
  }
  if (info.decimals == 0) return std::to_string(raw);
  const std::int64_t scale = Power10(info.decimals);
  const std::int64_t magnitude = raw < 0 ? -static_cast<std::int64_t>(raw) : raw;
  std::snprintf(buffer, sizeof buffer, "%s%lld.%0*lld", raw < 0 ? "-" : "", static_cast<long long>(magnitude / scale),
                info.decimals, static_cast<long long>(magnitude % scale));
  return buffer;
}

std::string FormatWithUnit(std::int32_t raw, const ParameterInfo& info) {
  std::string text = FormatValue(raw, info);
  if (!info.unit.empty()) text += " " + info.unit;
  return text;
}

bool ParseMillis(std::string_view text, std::uint32_t& millis) {
  text = Trim(text);
  std::int64_t scale = 1;  // the number's unit in ms / 1000
  std::string_view number = text;
  if (number.size() > 2 && number.substr(number.size() - 2) == "ms") {
    number.remove_suffix(2);
    scale = 1;
  } else if (number.size() > 1 && number.back() == 's') {
    number.remove_suffix(1);
    scale = 1000;
  }
  std::int64_t whole = 0, fraction = 0, fraction_scale = 1;
  bool point = false, digit = false;
  for (char c : number) {
    if (c == '.' && !point) {
      point = true;
      continue;
    }
    if (!std::isdigit(static_cast<unsigned char>(c))) return false;
    digit = true;
    if (point) {
      if (fraction_scale >= 1000) return false;
      fraction = fraction * 10 + (c - '0');
      fraction_scale *= 10;
    } else {
      whole = whole * 10 + (c - '0');
      if (whole > 100'000'000) return false;
    }
  }
  if (!digit) return false;
  const std::int64_t total = whole * scale + fraction * scale / fraction_scale;
  if (total <= 0 || total > 0xFFFFFFFF || (fraction * scale) % fraction_scale != 0) return false;
  millis = static_cast<std::uint32_t>(total);
  return true;
}

}  // namespace ipe
