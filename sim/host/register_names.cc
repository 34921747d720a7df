#include "register_names.h"

#include <cctype>
#include <charconv>
#include <cstdio>
#include <system_error>

namespace sim {
namespace {

bool IsHexNumber(std::string_view text, std::uint16_t& number) {
  if (text.size() != 4) return false;
  const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), number, 16);
  return ec == std::errc() && ptr == text.data() + text.size();
}

std::string Hex4(std::uint16_t number) {
  char text[8];
  std::snprintf(text, sizeof text, "%04X", static_cast<unsigned>(number));
  return text;
}

}  // namespace

const RegisterInfo* ResolveRegister(std::string_view name, Model model, std::string& error) {
  const RegisterInfo* info = FindRegisterByTitle(name);
  std::uint16_t number = 0;
  if (info == nullptr && IsHexNumber(name, number)) {
    if (!CommunicationNumberMayExist(number)) {
      error = "no communication number " + Hex4(number) + " (numbers ending in A-F do not exist)";
      return nullptr;
    }
    info = FindRegister(number);
    if (info == nullptr) {
      error = "no communication number " + Hex4(number);
      return nullptr;
    }
  }
  if (info == nullptr) {
    error = "unknown register '" + std::string(name) + "'";
    return nullptr;
  }
  if (!info->AppliesTo(model)) {
    error = std::string(info->title) + " does not exist on " + ModelName(model);
    return nullptr;
  }
  return info;
}

bool ParseRegisterValue(std::string_view text, std::int32_t& value) {
  bool negative = false;
  if (!text.empty() && (text.front() == '-' || text.front() == '+')) {
    negative = text.front() == '-';
    text.remove_prefix(1);
  }
  int base = 10;
  if (text.size() > 2 && text[0] == '0' && (text[1] == 'x' || text[1] == 'X')) {
    base = 16;
    text.remove_prefix(2);
  }
  // from_chars would accept a second sign; only digits may follow.
  if (text.empty() || std::isxdigit(static_cast<unsigned char>(text.front())) == 0) return false;
  std::int64_t magnitude = 0;
  const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), magnitude, base);
  if (ec != std::errc() || ptr != text.data() + text.size() || magnitude > 0x7FFFFFFF) return false;
  value = static_cast<std::int32_t>(negative ? -magnitude : magnitude);
  return true;
}

std::string FormatRegisterValue(const RegisterInfo& info, std::uint16_t word) {
  char hex[8];
  std::snprintf(hex, sizeof hex, "0x%04X", static_cast<unsigned>(word));
  return std::string(info.title) + " = " + std::to_string(info.FromWord(word)) + " (" + hex + ")";
}

std::string StaticRangeError(const RegisterInfo& info, Model model, std::int32_t value) {
  if (info.InRange(model, value)) return {};
  return "out of range " + std::to_string(info.min(model)) + ".." + std::to_string(info.max(model));
}

}  // namespace sim
