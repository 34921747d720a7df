// tools/ipe: value parsing and formatting in the parameter's unit, range checks, durations.
#include <gtest/gtest.h>

#include "parameter_table.h"
#include "values.h"

namespace ipe {
namespace {

ParameterInfo Info(const char* title, Model model = Model::kVfMb1) {
  const std::optional<ParameterInfo> info = FindParameter(title, model);
  EXPECT_TRUE(info.has_value()) << title;
  return info.value_or(ParameterInfo{});
}

TEST(IpeParameterTable, TitlesUnitsAndLimitsComeFromTheRegisterTable) {
  const ParameterInfo acc = Info("ACC");
  EXPECT_EQ(acc.number, 0x0009);
  EXPECT_EQ(acc.title, "acc");
  EXPECT_EQ(acc.unit, "s");
  EXPECT_EQ(acc.decimals, 1);
  EXPECT_EQ(acc.min, 1);
  EXPECT_EQ(acc.max, 60000);
  EXPECT_TRUE(acc.setting);
  const ParameterInfo fmod_mb1 = Info("fmod", Model::kVfMb1);
  const ParameterInfo fmod_s15 = Info("fmod", Model::kVfS15);
  EXPECT_EQ(fmod_mb1.max, 11);  // 12-14 are VF-S15 only
  EXPECT_EQ(fmod_s15.max, 14);
  EXPECT_TRUE(Info("fd00").monitor);
  EXPECT_FALSE(Info("fd00").host_writable);
  EXPECT_FALSE(Info("fa06").setting);  // a command, not a setting: never backed up
  EXPECT_FALSE(Info("f899").setting);
  EXPECT_TRUE(Info("c500").effective_after_reset);
  EXPECT_FALSE(FindParameter("nosuch", Model::kVfMb1).has_value());
}

TEST(IpeParameterTable, BackupHoldsEveryWritableEepromSettingAndNothingElse) {
  const std::vector<ParameterInfo> list = BackupParameters(Model::kVfMb1);
  ASSERT_EQ(list.size(), 140u);  // registers.csv: 140 rows eeprom + rw, all on both models
  EXPECT_EQ(list.front().title, "au1");
  EXPECT_EQ(list.back().title, "c604");
  for (const ParameterInfo& info : list) EXPECT_TRUE(info.setting && info.host_writable) << info.title;
}

TEST(IpeValues, ParsesInTheParametersOwnUnitAndStep) {
  const ParameterInfo acc = Info("acc");
  EXPECT_EQ(ParseValue("5.0", acc).raw, 50);
  EXPECT_EQ(ParseValue("5", acc).raw, 50);
  EXPECT_EQ(ParseValue("5s", acc).raw, 50);
  EXPECT_EQ(ParseValue(" 5.0 S ", acc).raw, 50);
  EXPECT_EQ(ParseValue("0.1", acc).raw, 1);
  const ParameterInfo fh = Info("fh");
  EXPECT_EQ(ParseValue("60Hz", fh).raw, 6000);
  EXPECT_EQ(ParseValue("60", fh).raw, 6000);
  EXPECT_EQ(ParseValue("59.99 hz", fh).raw, 5999);
  EXPECT_EQ(ParseValue("4", Info("c101")).raw, 4);
  EXPECT_EQ(ParseValue("0x0404", Info("fa06")).raw, 0x0404);
}

TEST(IpeValues, RefusesWhatDoesNotFitWithAMessageNamingTheParameter) {
  const ParameterInfo acc = Info("acc");
  EXPECT_EQ(ParseValue("0.05", acc).error, "acc: '0.05' has more decimals than acc takes (steps of 0.1 s)");
  EXPECT_EQ(ParseValue("5Hz", acc).error, "acc: '5Hz' has the wrong unit (acc is in s)");
  EXPECT_EQ(ParseValue("five", acc).error, "acc: 'five' is not a number");
  EXPECT_EQ(ParseValue("", acc).error, "acc: '' is not a number");
  EXPECT_EQ(ParseValue("1.2.3", acc).error, "acc: '1.2.3' is not a number");
  EXPECT_EQ(ParseValue("4s", Info("c101")).error, "c101: '4s' has a unit, but c101 is a plain number");
  EXPECT_EQ(ParseValue("0x12345", Info("fa06")).error, "fa06: '0x12345' is not a 16-bit value");
  EXPECT_FALSE(ParseValue("99999999999", acc).ok);
}

TEST(IpeValues, RangeIsTheModelsLimits) {
  const ParameterInfo acc = Info("acc");
  EXPECT_EQ(CheckRange(1, acc, Model::kVfMb1), "");
  EXPECT_EQ(CheckRange(60000, acc, Model::kVfMb1), "");
  EXPECT_EQ(CheckRange(60001, acc, Model::kVfMb1), "acc = 6000.1 s is outside 0.1 .. 6000.0 s on VF-MB1");
  EXPECT_EQ(CheckRange(0, acc, Model::kVfMb1), "acc = 0.0 s is outside 0.1 .. 6000.0 s on VF-MB1");
  EXPECT_EQ(CheckRange(12, Info("fmod", Model::kVfMb1), Model::kVfMb1), "fmod = 12 is outside 0 .. 11 on VF-MB1");
  EXPECT_EQ(CheckRange(12, Info("fmod", Model::kVfS15), Model::kVfS15), "");
}

TEST(IpeValues, FormatsWithTheRegistersDecimalsAndUnit) {
  EXPECT_EQ(FormatWithUnit(50, Info("acc")), "5.0 s");
  EXPECT_EQ(FormatWithUnit(6000, Info("fh")), "60.00 Hz");
  EXPECT_EQ(FormatWithUnit(5, Info("fh")), "0.05 Hz");
  EXPECT_EQ(FormatWithUnit(4, Info("c101")), "4");
  EXPECT_EQ(FormatWithUnit(0x4800, Info("fd01")), "0x4800");
  const ParameterInfo fe36 = Info("fe36");  // signed: -100.00 % is the word 0xD8F0
  EXPECT_EQ(fe36.FromWord(0xD8F0), -10000);
  EXPECT_EQ(FormatWithUnit(fe36.FromWord(0xD8F0), fe36), "-100.00 %");
  EXPECT_EQ(fe36.ToWord(-10000), 0xD8F0);
}

TEST(IpeValues, Durations) {
  std::uint32_t ms = 0;
  EXPECT_TRUE(ParseMillis("10ms", ms));
  EXPECT_EQ(ms, 10u);
  EXPECT_TRUE(ParseMillis("250", ms));
  EXPECT_EQ(ms, 250u);
  EXPECT_TRUE(ParseMillis("1.5s", ms));
  EXPECT_EQ(ms, 1500u);
  EXPECT_TRUE(ParseMillis("2s", ms));
  EXPECT_EQ(ms, 2000u);
  EXPECT_FALSE(ParseMillis("0", ms));
  EXPECT_FALSE(ParseMillis("10us", ms));
  EXPECT_FALSE(ParseMillis("0.5ms", ms));
  EXPECT_FALSE(ParseMillis("", ms));
}

}  // namespace
}  // namespace ipe
