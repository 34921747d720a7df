// The simulated inverter's EEPROM image: per-register values and write counters, plus what a drive keeps
// across power cycles (cumulative hours, watt-hours, trip history). Part of InverterModel.
//
// Text format, one item per line, '#' comments:
//   format 1
//   model vf-mb1
//   operation-us <u64>      (FE14 source)
//   power-on-us <u64>       (FE80 source)
//   input-mwh <u64>         (FE76 source, milliwatt-hours)
//   output-mwh <u64>        (FE77 source)
//   trip-history <FE10> <FE11> <FE12> <FE13>
//   reg <number hex> <value decimal> <writes decimal>     (every EEPROM register)
// Registers the table does not have (any more) or values outside its limits are skipped: the register
// keeps its default.
#include <charconv>
#include <cmath>
#include <cstdio>
#include <optional>
#include <system_error>

#include "sim/inverter_model.h"

namespace sim {
namespace {

constexpr std::string_view kFormatLine = "format 1";

// Splits `line` into at most `N` space-separated words; nullopt when there are more.
template <std::size_t N>
std::optional<std::array<std::string_view, N>> Words(std::string_view line, std::size_t& count) {
  std::array<std::string_view, N> words{};
  count = 0;
  while (!line.empty()) {
    const std::size_t start = line.find_first_not_of(' ');
    if (start == std::string_view::npos) break;
    line.remove_prefix(start);
    const std::size_t end = std::min(line.find(' '), line.size());
    if (count == N) return std::nullopt;
    words[count++] = line.substr(0, end);
    line.remove_prefix(end);
  }
  return words;
}

template <typename T>
bool Parse(std::string_view text, T& out, int base = 10) {
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, out, base);
  return ec == std::errc() && ptr == end;
}

std::uint64_t ToMilliWattHours(double kwh) { return static_cast<std::uint64_t>(std::llround(kwh * 1e6)); }

}  // namespace

std::uint32_t InverterModel::EepromWriteCount(std::uint16_t number) const {
  const RegisterInfo* info = FindRegister(number, model_);
  return info != nullptr ? eeprom_writes_[Index(*info)] : 0;
}

std::int32_t InverterModel::EepromValue(std::uint16_t number) const {
  const RegisterInfo* info = FindRegister(number, model_);
  return (info != nullptr && info->storage == StorageClass::kEeprom) ? eeprom_[Index(*info)] : 0;
}

std::int32_t InverterModel::ActiveValue(std::uint16_t number) const {
  const RegisterInfo* info = FindRegister(number, model_);
  if (info == nullptr) return 0;
  return info->effective_after_reset ? active_[Index(*info)] : ram_[Index(*info)];
}

std::string InverterModel::SerializeEeprom() const {
  std::string out = "# simulated VF-MB1/S15 inverter EEPROM (sim/inverter_eeprom.cc)\n";
  out += kFormatLine;
  out += "\nmodel ";
  out += ModelName(model_);
  out += "\noperation-us " + std::to_string(operation_us_);
  out += "\npower-on-us " + std::to_string(power_on_us_);
  out += "\ninput-mwh " + std::to_string(ToMilliWattHours(input_kwh_));
  out += "\noutput-mwh " + std::to_string(ToMilliWattHours(output_kwh_));
  out += "\ntrip-history";
  for (std::uint8_t code : trip_history_) out += " " + std::to_string(code);
  out += "\n";
  for (std::size_t i = 0; i < table_.size(); ++i) {
    if (table_[i].storage != StorageClass::kEeprom || !table_[i].AppliesTo(model_)) continue;
    char number[8];
    std::snprintf(number, sizeof number, "%04X", static_cast<unsigned>(table_[i].number));
    out += "reg ";
    out += number;
    out += " " + std::to_string(eeprom_[i]) + " " + std::to_string(eeprom_writes_[i]) + "\n";
  }
  return out;
}

bool InverterModel::LoadEeprom(std::string_view text) {
  std::vector<std::int32_t> values(table_.size());
  std::vector<std::uint32_t> writes(table_.size(), 0);
  for (std::size_t i = 0; i < table_.size(); ++i) values[i] = table_[i].default_value(model_);
  std::uint64_t operation_us = 0;
  std::uint64_t power_on_us = 0;
  std::uint64_t input_mwh = 0;
  std::uint64_t output_mwh = 0;
  std::array<std::uint8_t, 4> history{};
  bool format_seen = false;
  bool model_seen = false;

  while (!text.empty()) {
    const std::size_t eol = std::min(text.find('\n'), text.size());
    std::string_view line = text.substr(0, eol);
    text.remove_prefix(std::min(eol + 1, text.size()));
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    if (line.empty() || line.front() == '#') continue;
    std::size_t n = 0;
    const auto words = Words<5>(line, n);
    if (!words || n == 0) return false;
    const auto& w = *words;
    if (n == 2 && line == kFormatLine) {
      format_seen = true;
    } else if (w[0] == "model" && n == 2) {
      if (ModelFromName(w[1]) != model_) return false;
      model_seen = true;
    } else if (w[0] == "operation-us" && n == 2) {
      if (!Parse(w[1], operation_us)) return false;
    } else if (w[0] == "power-on-us" && n == 2) {
      if (!Parse(w[1], power_on_us)) return false;
    } else if (w[0] == "input-mwh" && n == 2) {
      if (!Parse(w[1], input_mwh)) return false;
    } else if (w[0] == "output-mwh" && n == 2) {
      if (!Parse(w[1], output_mwh)) return false;
    } else if (w[0] == "trip-history" && n == 5) {
      for (std::size_t i = 0; i < history.size(); ++i) {
        if (!Parse(w[i + 1], history[i])) return false;
      }
    } else if (w[0] == "reg" && n == 4) {
      std::uint16_t number = 0;
      std::int32_t value = 0;
      std::uint32_t count = 0;
      if (w[1].size() != 4 || !Parse(w[1], number, 16) || !Parse(w[2], value) || !Parse(w[3], count)) {
        return false;
      }
      const RegisterInfo* info = FindRegister(number, model_);
      if (info == nullptr || info->storage != StorageClass::kEeprom || !info->InRange(model_, value)) continue;
      values[Index(*info)] = value;
      writes[Index(*info)] = count;
    } else {
      return false;
    }
  }
  if (!format_seen || !model_seen) return false;

  for (std::size_t i = 0; i < table_.size(); ++i) {
    if (table_[i].storage != StorageClass::kEeprom) continue;
    eeprom_[i] = values[i];
    eeprom_writes_[i] = writes[i];
    ram_[i] = values[i];
    active_[i] = values[i];
  }
  operation_us_ = operation_us;
  power_on_us_ = power_on_us;
  input_kwh_ = static_cast<double>(input_mwh) / 1e6;
  output_kwh_ = static_cast<double>(output_mwh) / 1e6;
  trip_history_ = history;
  ++eeprom_generation_;
  return true;
}

}  // namespace sim
