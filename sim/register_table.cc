#include "sim/register_table.h"

#include <algorithm>
#include <array>
#include <cstddef>
#include <initializer_list>
#include <iterator>

// Written by tools/gen_register_table.py from registers.csv into the build directory.
#include "register_table.inc"

namespace sim {
namespace {

constexpr std::span<const RegisterInfo> kTable(generated::kRegisters);

// The generator validates the CSV; these repeat the properties the lookups rely on, so that a table
// edited by any other route still cannot build.
constexpr bool SortedAndUnique() {
  for (std::size_t i = 1; i < kTable.size(); ++i) {
    if (kTable[i - 1].number >= kTable[i].number) return false;
  }
  return true;
}
constexpr bool NoNumberEndsInAToF() {
  return std::all_of(kTable.begin(), kTable.end(),
                     [](const RegisterInfo& r) { return CommunicationNumberMayExist(r.number); });
}
constexpr bool LimitsHold(const Limits& l) { return l.min <= l.default_value && l.default_value <= l.max; }
constexpr bool FitsInAWord(const RegisterInfo& r) {
  for (const Limits* l : {&r.mb1, &r.s15}) {
    if (r.is_signed() ? (l->min < -32768 || l->max > 32767) : (l->min < 0 || l->max > 0xFFFF)) return false;
  }
  return true;
}
constexpr bool AllLimitsHold() {
  return std::all_of(kTable.begin(), kTable.end(), [](const RegisterInfo& r) {
    return LimitsHold(r.mb1) && LimitsHold(r.s15) && FitsInAWord(r);
  });
}
constexpr bool MonitorsAreReadOnly() {
  return std::all_of(kTable.begin(), kTable.end(), [](const RegisterInfo& r) {
    const bool monitor = r.storage == StorageClass::kMonitor || r.storage == StorageClass::kTripHold;
    return !monitor || (r.access != Access::kReadWrite && !r.write_during_run && !r.effective_after_reset);
  });
}

static_assert(!kTable.empty());
static_assert(SortedAndUnique(), "registers must be sorted by number without duplicates");
static_assert(NoNumberEndsInAToF(), "communication numbers ending in A-F do not exist on VF-MB1/S15");
static_assert(AllLimitsHold(), "every register needs min <= default <= max within one 16-bit word");
static_assert(MonitorsAreReadOnly(), "monitors and trip-hold registers are never host-writable");

// Every 16-bit number to its row (kNoRow: none): one load per lookup. The simulator looks registers up
// on every request and every model step, so a search per lookup was most of its work. 128 KiB of
// constants in a host process; the card never links the simulator.
constexpr std::uint16_t kNoRow = 0xFFFF;
static_assert(kTable.size() < kNoRow);
struct RowIndex {
  std::array<std::uint16_t, 0x10000> row{};
};
constexpr RowIndex BuildRowIndex() {
  RowIndex index;
  for (std::uint16_t& row : index.row) row = kNoRow;
  for (std::size_t i = 0; i < kTable.size(); ++i) index.row[kTable[i].number] = static_cast<std::uint16_t>(i);
  return index;
}
constexpr RowIndex kRowIndex = BuildRowIndex();

char Lower(char c) { return (c >= 'A' && c <= 'Z') ? static_cast<char>(c - 'A' + 'a') : c; }

bool EqualsIgnoringCase(std::string_view a, std::string_view b) {
  return a.size() == b.size() &&
         std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) { return Lower(x) == Lower(y); });
}

}  // namespace

std::span<const RegisterInfo> AllRegisters() { return kTable; }

const RegisterInfo* FindRegister(std::uint16_t number) {
  const std::uint16_t row = kRowIndex.row[number];
  return row == kNoRow ? nullptr : &kTable[row];
}

const RegisterInfo* FindRegister(std::uint16_t number, Model model) {
  const RegisterInfo* info = FindRegister(number);
  return (info != nullptr && info->AppliesTo(model)) ? info : nullptr;
}

const RegisterInfo* FindRegisterByTitle(std::string_view title) {
  // A few hundred short titles, looked up when parsing names (command line, control socket): a scan is
  // plenty.
  const auto it = std::find_if(kTable.begin(), kTable.end(),
                               [title](const RegisterInfo& r) { return EqualsIgnoringCase(r.title, title); });
  return it == kTable.end() ? nullptr : &*it;
}

const char* StorageClassName(StorageClass storage) {
  switch (storage) {
    case StorageClass::kEeprom:
      return "eeprom";
    case StorageClass::kRamOnly:
      return "ram";
    case StorageClass::kMonitor:
      return "monitor";
    case StorageClass::kTripHold:
      return "trip-hold";
  }
  return "?";
}

const char* ModelName(Model model) { return model == Model::kVfS15 ? "vf-s15" : "vf-mb1"; }

std::optional<Model> ModelFromName(std::string_view name) {
  if (name == "vf-mb1") return Model::kVfMb1;
  if (name == "vf-s15") return Model::kVfS15;
  return std::nullopt;
}

}  // namespace sim
