// The card's parameter table (drive_link/parameters/include/drive_link/parameter_table.h), generated
// from drive_link/registers/registers.csv: exact rows as the CSV has them, the selection (rw and ro monitors), order,
// lookups and the range check for signed and unsigned parameters.
#include "drive_link/parameter_table.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <string_view>

namespace drive_link {
namespace {

const ParameterInfo& Row(std::string_view title) {
  const std::optional<std::size_t> index = FindParameterByTitle(title);
  EXPECT_TRUE(index.has_value()) << title;
  return CardParameters()[index.value_or(0)];
}

TEST(DriveParameterTable, AccAsInTheCsv) {
  // 0009,acc,...,rw,1,60000,100,,,,0.1 s
  const ParameterInfo& acc = Row("acc");
  EXPECT_EQ(acc.number, 0x0009);
  EXPECT_EQ(acc.vf_mb1.min, 1);
  EXPECT_EQ(acc.vf_mb1.max, 60000);
  EXPECT_EQ(acc.vf_mb1.default_value, 100);
  EXPECT_EQ(acc.vf_s15.max, 60000);
  EXPECT_EQ(acc.decimals, 1);
  EXPECT_EQ(std::string_view(acc.unit), "s");
  EXPECT_EQ(std::string_view(acc.help), "Acceleration time 1 (unit per f519)");
  EXPECT_FALSE(acc.is_signed);
  EXPECT_FALSE(acc.read_only);
  EXPECT_EQ(acc.models, kBothModels);
}

// Number, VF-MB1 limits, decimals and unit of a row, as the CSV has them.
void ExpectRow(std::string_view title, std::uint16_t number, ParameterLimits limits, std::uint8_t decimals,
               std::string_view unit) {
  SCOPED_TRACE(title);
  const ParameterInfo& row = Row(title);
  EXPECT_EQ(row.number, number);
  EXPECT_EQ(row.vf_mb1.min, limits.min);
  EXPECT_EQ(row.vf_mb1.max, limits.max);
  EXPECT_EQ(row.vf_mb1.default_value, limits.default_value);
  EXPECT_EQ(row.decimals, decimals);
  EXPECT_EQ(std::string_view(row.unit), unit);
}

TEST(DriveParameterTable, DecFhC101AsInTheCsv) {
  ExpectRow("dec", 0x0010, {1, 60000, 100}, 1, "s");     // 0010, 1-60000, 100, 0.1 s
  ExpectRow("fh", 0x0011, {3000, 50000, 8000}, 2, "Hz");  // 0011, 3000-50000, 8000, 0.01 Hz
  ExpectRow("c101", 0xC101, {0, 5, 4}, 0, "");            // C101, 0-5, 4, "-"
}

TEST(DriveParameterTable, ModelLimitsDiffer) {
  // 0004 fmod: 0-11 on VF-MB1, 0-14 on VF-S15; 0016 vb default 60 / 30.
  const ParameterInfo& fmod = Row("fmod");
  EXPECT_EQ(fmod.Limits(InverterModel::kVfMb1).max, 11);
  EXPECT_EQ(fmod.Limits(InverterModel::kVfS15).max, 14);
  EXPECT_FALSE(fmod.InRange(InverterModel::kVfMb1, 12));
  EXPECT_TRUE(fmod.InRange(InverterModel::kVfS15, 12));
  const ParameterInfo& vb = Row("vb");
  EXPECT_EQ(vb.Limits(InverterModel::kVfMb1).default_value, 60);
  EXPECT_EQ(vb.Limits(InverterModel::kVfS15).default_value, 30);
}

TEST(DriveParameterTable, MonitorsAreReadOnlyAndSignedOnesSignExtend) {
  const ParameterInfo& fd00 = Row("fd00");  // FD00 output frequency, 0-50000, 0.01 Hz
  EXPECT_EQ(fd00.number, 0xFD00);
  EXPECT_TRUE(fd00.read_only);
  EXPECT_FALSE(fd00.is_signed);
  const ParameterInfo& fe36 = Row("fe36");  // FE36, -10000..10000, 0.01 %
  EXPECT_TRUE(fe36.is_signed);
  EXPECT_EQ(fe36.vf_mb1.min, 0xD8F0);
  EXPECT_EQ(fe36.vf_mb1.max, 0x2710);
  EXPECT_EQ(fe36.Value(0xD8F0), -10000);
  EXPECT_TRUE(fe36.InRange(InverterModel::kVfMb1, 0xFFFF));   // -1
  EXPECT_FALSE(fe36.InRange(InverterModel::kVfMb1, 0xD8EF));  // -10001
  EXPECT_FALSE(fe36.InRange(InverterModel::kVfMb1, 0x2711));  // 10001
}

TEST(DriveParameterTable, SelectionAndOrder) {
  // 149 rw registers and 37 monitors; option registers (c502, fa30 ...) and trip history are left out.
  EXPECT_EQ(CardParameters().size(), 186u);
  EXPECT_FALSE(FindParameterByTitle("c502").has_value());
  EXPECT_FALSE(FindParameterByTitle("fe10").has_value());  // trip-hold
  EXPECT_EQ(CardParameters().front().number, 0x0000);      // au1
  EXPECT_EQ(FindParameterByNumber(0x0009), FindParameterByTitle("acc"));
  EXPECT_EQ(FindParameterByNumber(0x0009), std::optional<std::size_t>(5));
  EXPECT_FALSE(FindParameterByNumber(0x0008).has_value());
  EXPECT_FALSE(FindParameterByTitle("ACC").has_value());
}

}  // namespace
}  // namespace drive_link
