#include "address_plan.h"

#include <array>
#include <cctype>
#include <charconv>
#include <cstdio>

#include "drive_link/drive_registers.h"

namespace sim {
namespace {

// c504 (the mode) and the twelve octets after it.
constexpr unsigned kFirstParameter = 504;
constexpr std::size_t kParameters = 13;

}  // namespace

bool ParseIpv4(std::string_view text, std::uint32_t& out) {
  std::uint32_t address = 0;
  for (int octet = 0; octet < 4; ++octet) {
    if (octet > 0) {
      if (text.empty() || text.front() != '.') return false;
      text.remove_prefix(1);
    }
    std::size_t digits = 0;
    while (digits < text.size() && std::isdigit(static_cast<unsigned char>(text[digits])) != 0) ++digits;
    unsigned value = 0;
    if (digits == 0 || digits > 3) return false;
    std::from_chars(text.data(), text.data() + digits, value);
    if (value > 255) return false;
    address = (address << 8) | value;
    text.remove_prefix(digits);
  }
  if (!text.empty()) return false;
  out = address;
  return true;
}

std::string FormatIpv4(std::uint32_t v) {
  char text[16];
  std::snprintf(text, sizeof text, "%u.%u.%u.%u", (v >> 24) & 0xFFu, (v >> 16) & 0xFFu, (v >> 8) & 0xFFu,
                v & 0xFFu);
  return text;
}

bool ParseCidr(std::string_view text, std::uint32_t& ip, std::uint32_t& netmask) {
  const std::size_t slash = text.find('/');
  if (slash == std::string_view::npos) return false;
  const std::string_view prefix_text = text.substr(slash + 1);
  if (prefix_text.empty() || prefix_text.size() > 2) return false;
  for (char c : prefix_text) {
    if (std::isdigit(static_cast<unsigned char>(c)) == 0) return false;
  }
  unsigned prefix = 0;
  std::from_chars(prefix_text.data(), prefix_text.data() + prefix_text.size(), prefix);
  if (prefix < 1 || prefix > 30) return false;
  std::uint32_t address = 0;
  if (!ParseIpv4(text.substr(0, slash), address)) return false;
  ip = address;
  netmask = ~std::uint32_t{0} << (32 - prefix);
  return true;
}

bool ParseAddressPlan(std::string_view text, AddressPlan& plan) {
  const std::size_t comma = text.find(',');
  AddressPlan parsed;
  if (!ParseCidr(text.substr(0, comma), parsed.ip, parsed.netmask)) return false;
  if (comma != std::string_view::npos && !ParseIpv4(text.substr(comma + 1), parsed.gateway)) return false;
  plan = parsed;
  return true;
}

bool KeyManualAddress(SimulatedInverter& inverter, const AddressPlan& plan, std::string& error) {
  std::array<std::uint16_t, kParameters> values{0};  // values[0]: c504 = 0, manual
  for (unsigned i = 0; i < 4; ++i) {
    const unsigned shift = 24 - 8 * i;
    values[1 + i] = static_cast<std::uint16_t>((plan.ip >> shift) & 0xFF);
    values[5 + i] = static_cast<std::uint16_t>((plan.netmask >> shift) & 0xFF);
    values[9 + i] = static_cast<std::uint16_t>((plan.gateway >> shift) & 0xFF);
  }
  for (unsigned i = 0; i < values.size(); ++i) {
    const unsigned parameter = kFirstParameter + i;
    const WriteResult result =
        inverter.model().Write(drive_link::reg::CParameter(parameter), values[i], WriteTarget::kRamAndEeprom);
    if (!result.ok()) {
      error = "--ip: the inverter refused c" + std::to_string(parameter) + " (" + WriteOutcomeName(result.outcome) +
              ")";
      return false;
    }
  }
  inverter.SaveIfChanged();
  return true;
}

}  // namespace sim
