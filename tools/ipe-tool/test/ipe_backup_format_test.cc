// tools/ipe: the backup file (print, parse, refusals) and the restore diff.
#include <gtest/gtest.h>

#include "backup_format.h"

namespace ipe {
namespace {

BackupValue Value(const char* title, std::int32_t raw) { return {FindParameter(title, Model::kVfMb1).value(), raw}; }

constexpr const char* kFile =
    "# ipe backup of a VF-MB1/S15 drive (restore with: tools/ipe restore HOST FILE)\n"
    "# model: VF-MB1\n"
    "# product: VF-MB1\n"
    "# card: 127.0.0.2\n"
    "# date: 2026-11-27T22:00:00Z\n"
    "acc = 5.0 s  # 0009 Acceleration time 1 (unit per f519)\n"
    "fh = 60.00 Hz  # 0011 Maximum frequency\n"
    "c101 = 1  # C101 Inverter operation at communication loss (0 stop + cmod/fmod, 1 continue, 2 decelerate, 3 "
    "coast, 4 err8 trip, 5 preset speed c102)\n";

TEST(IpeBackupFormat, PrintsHeaderAndOneLinePerParameter) {
  const BackupHeader header{"VF-MB1", "VF-MB1", "127.0.0.2", "2026-11-27T22:00:00Z"};
  EXPECT_EQ(PrintBackup(header, {Value("acc", 50), Value("fh", 6000), Value("c101", 1)}), kFile);
}

TEST(IpeBackupFormat, ParsesWhatItPrints) {
  const ParsedBackup parsed = ParseBackup(kFile);
  ASSERT_TRUE(parsed.ok) << parsed.error;
  EXPECT_EQ(parsed.model, Model::kVfMb1);
  EXPECT_EQ(parsed.header.product, "VF-MB1");
  EXPECT_EQ(parsed.header.card, "127.0.0.2");
  EXPECT_EQ(parsed.header.date, "2026-11-27T22:00:00Z");
  ASSERT_EQ(parsed.values.size(), 3u);
  EXPECT_EQ(parsed.values[0].info.title, "acc");
  EXPECT_EQ(parsed.values[0].raw, 50);
  EXPECT_EQ(parsed.values[1].raw, 6000);
  EXPECT_EQ(parsed.values[2].info.number, 0xC101);
  EXPECT_EQ(parsed.values[2].raw, 1);
}

TEST(IpeBackupFormat, AcceptsHandEditsWithoutUnitsOrComments) {
  const ParsedBackup parsed = ParseBackup("# model: vf-s15\n\nACC=7\n  dec = 2.5s\n");
  ASSERT_TRUE(parsed.ok) << parsed.error;
  EXPECT_EQ(parsed.model, Model::kVfS15);
  EXPECT_EQ(parsed.values[0].raw, 70);
  EXPECT_EQ(parsed.values[1].raw, 25);
}

TEST(IpeBackupFormat, RefusalsNameTheLine) {
  EXPECT_EQ(ParseBackup("acc = 5\n").error, "line 1: no '# model:' line: not an ipe backup");
  EXPECT_EQ(ParseBackup("# model: VF-AS3\n").error, "line 1: unknown model 'VF-AS3' (VF-MB1 or VF-S15)");
  EXPECT_EQ(ParseBackup("# model: VF-MB1\nacc 5\n").error, "line 2: expected 'name = value', got 'acc 5'");
  EXPECT_EQ(ParseBackup("# model: VF-MB1\nnosuch = 5\n").error, "line 2: no parameter 'nosuch' on VF-MB1");
  EXPECT_EQ(ParseBackup("# model: VF-MB1\nfd00 = 5\n").error, "line 2: fd00 is not a setting a backup holds");
  EXPECT_EQ(ParseBackup("# model: VF-MB1\nfa06 = 0\n").error, "line 2: fa06 is not a setting a backup holds");
  EXPECT_EQ(ParseBackup("# model: VF-MB1\nacc = 1\nacc = 2\n").error, "line 3: acc appears twice");
  EXPECT_EQ(ParseBackup("# model: VF-MB1\nacc = 0.05\n").error,
            "line 2: acc: '0.05' has more decimals than acc takes (steps of 0.1 s)");
  EXPECT_EQ(ParseBackup("# model: VF-MB1\nfmod = 12\n").error, "line 2: fmod = 12 is outside 0 .. 11 on VF-MB1");
  EXPECT_TRUE(ParseBackup("# model: VF-S15\nfmod = 12\n").ok);
}

TEST(IpeBackupFormat, DiffListsOnlyWhatDiffers) {
  const std::vector<BackupValue> file{Value("acc", 50), Value("fh", 6000), Value("c101", 1)};
  const std::vector<BackupValue> card{Value("c101", 4), Value("fh", 6000), Value("acc", 100)};
  const std::vector<DiffLine> diff = Diff(file, card);
  ASSERT_EQ(diff.size(), 2u);
  EXPECT_EQ(FormatDiffLine(diff[0]), "acc: 10.0 s -> 5.0 s");
  EXPECT_EQ(FormatDiffLine(diff[1]), "c101: 4 -> 1");
  EXPECT_TRUE(Diff(file, file).empty());
}

}  // namespace
}  // namespace ipe
