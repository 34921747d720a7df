#include "drive_link/parameter_table.h"

#include <algorithm>

// generated::kParameters, from drive_link/registers/registers.csv (tools/gen_parameter_table.py).
#include "parameter_table.inc"

namespace drive_link {
namespace {

using generated::kParameters;

constexpr bool SortedByNumber() {
  for (std::size_t i = 1; i < std::size(kParameters); ++i) {
    if (kParameters[i - 1].number >= kParameters[i].number) return false;
  }
  return true;
}
static_assert(SortedByNumber(), "the generator sorts the rows by communication number");
// CIP Parameter instances and EDS ParamN are 16-bit.
static_assert(std::size(kParameters) < 0xFFFF);

}  // namespace

std::span<const ParameterInfo> CardParameters() { return kParameters; }

std::optional<std::size_t> FindParameterByNumber(std::uint16_t number) {
  const auto* end = std::end(kParameters);
  const auto* found = std::lower_bound(std::begin(kParameters), end, number,
                                       [](const ParameterInfo& row, std::uint16_t n) { return row.number < n; });
  if (found == end || found->number != number) return std::nullopt;
  return static_cast<std::size_t>(found - std::begin(kParameters));
}

std::optional<std::size_t> FindParameterByTitle(std::string_view title) {
  for (std::size_t i = 0; i < std::size(kParameters); ++i) {
    if (title == kParameters[i].title) return i;
  }
  return std::nullopt;
}

}  // namespace drive_link
