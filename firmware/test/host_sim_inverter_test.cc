// The host card's simulated inverter: its EEPROM file in the state dir (new, loaded, unusable, one per
// model), the --param presets, when the image is stored, power cycles, and the server settings.
#include <gtest/gtest.h>

#include <filesystem>

#include "host_options.h"
#include "host_sim_fixture.h"
#include "sim/register_numbers.h"

namespace host::test {
namespace {

namespace reg = sim::reg;
using sim::ServerConfigFromOptions;

ParamPreset Preset(const char* text, std::uint16_t number, std::int32_t value) { return {text, number, value}; }

using SimInverter = SimInverterFixture;

TEST_F(SimInverter, NewStateDir_DefaultsPlusPresetsStoredAtOnce) {
  config_.presets = {Preset("acc=50", reg::kAcc, 50), Preset("0010=40", reg::kDec, 40)};
  ASSERT_TRUE(Start()) << error_;
  EXPECT_TRUE(inverter_->started_new());
  EXPECT_EQ(inverter_->file_path(), dir_ + "/inverter/vf-mb1.eeprom");
  EXPECT_EQ(Read(reg::kAcc), 50);
  EXPECT_EQ(Read(reg::kDec), 40);
  EXPECT_EQ(inverter_->saves(), 1u);
  const std::string image = ReadText(FilePath());
  EXPECT_NE(image.find("\nmodel vf-mb1\n"), std::string::npos);
  EXPECT_NE(image.find("\nreg 0009 50 1\n"), std::string::npos);  // a preset is a W: one EEPROM write
  EXPECT_NE(image.find("\nreg 0010 40 1\n"), std::string::npos);
  EXPECT_EQ(Log(), "");
}

TEST_F(SimInverter, ExistingFile_LoadedAndPresetsIgnored) {
  config_.presets = {Preset("acc=50", reg::kAcc, 50)};
  ASSERT_TRUE(Start());
  inverter_.reset();
  config_.presets = {Preset("acc=70", reg::kAcc, 70)};
  ASSERT_TRUE(Start());
  EXPECT_FALSE(inverter_->started_new());
  EXPECT_EQ(Read(reg::kAcc), 50);
  EXPECT_EQ(inverter_->model().EepromWriteCount(reg::kAcc), 1u);
  EXPECT_EQ(inverter_->saves(), 0u);  // loading stores nothing
}

TEST_F(SimInverter, CorruptFile_MovedAsideAndTheInverterStartsNew) {
  WriteText(FilePath(), EepromFileContents("format 1\nmodel vf-mb1\nreg 0009 fifty 1\n"));
  config_.presets = {Preset("acc=50", reg::kAcc, 50)};
  ASSERT_TRUE(Start()) << error_;
  EXPECT_TRUE(inverter_->started_new());
  EXPECT_EQ(Read(reg::kAcc), 50);  // a new inverter takes the presets
  EXPECT_EQ(Read(reg::kDec), 100);
  EXPECT_EQ(Log(), "ipe002z-host: warning: " + FilePath() +
                       " is not usable (it is not a valid EEPROM image); moved to " + FilePath() +
                       ".bad; the inverter starts from its factory defaults\n");
  EXPECT_EQ(ReadText(FilePath() + ".bad"), EepromFileContents("format 1\nmodel vf-mb1\nreg 0009 fifty 1\n"));
  sim::InverterModel check(sim::Model::kVfMb1);
  const std::string stored = ReadText(FilePath());
  ASSERT_TRUE(EepromImageOf(stored).has_value());
  EXPECT_TRUE(check.LoadEeprom(*EepromImageOf(stored)));
}

TEST_F(SimInverter, FileWithoutItsCheckLine_MovedAsideAndTheInverterStartsNew) {
  // A whole image, but no check line: it cannot prove it is whole (an older version wrote it, or it
  // was cut short after its last complete line), so none of it is used.
  sim::InverterModel old(sim::Model::kVfMb1);
  ASSERT_TRUE(old.Write(reg::kAcc, 50, sim::WriteTarget::kRamAndEeprom).ok());
  WriteText(FilePath(), old.SerializeEeprom());
  ASSERT_TRUE(Start());
  EXPECT_TRUE(inverter_->started_new());
  EXPECT_EQ(Read(reg::kAcc), 100);
  EXPECT_EQ(Log(), "ipe002z-host: warning: " + FilePath() +
                       " is not usable (its check line is missing or does not match (cut short, damaged, or from"
                       " an older version)); moved to " + FilePath() +
                       ".bad; the inverter starts from its factory defaults\n");
}

TEST(SimInverterEepromFile, CheckLineIsTheCrcOfEverythingBeforeIt) {
  // CRC-32 of "123456789" is 0xcbf43926 (the standard check value).
  EXPECT_EQ(EepromFileContents("123456789"), "123456789check cbf43926\n");
  EXPECT_EQ(EepromFileContents("a\n"), "a\ncheck ddeaa107\n");
  EXPECT_EQ(EepromImageOf("a\ncheck ddeaa107\n"), std::optional<std::string_view>("a\n"));
  EXPECT_EQ(EepromImageOf("check 00000000\n"), std::optional<std::string_view>(""));
  EXPECT_EQ(EepromImageOf("b\ncheck ddeaa107\n"), std::nullopt);   // another image
  EXPECT_EQ(EepromImageOf("a\ncheck DDEAA107\n"), std::nullopt);   // only lowercase
  EXPECT_EQ(EepromImageOf("a\ncheck ddeaa107"), std::nullopt);      // no line end
  EXPECT_EQ(EepromImageOf("a\ncheck ddeaa107\n\n"), std::nullopt);  // anything after it
  EXPECT_EQ(EepromImageOf("a\n"), std::nullopt);
  EXPECT_EQ(EepromImageOf(""), std::nullopt);
}

TEST_F(SimInverter, AnotherModelsImage_MovedAsideWithTheReason) {
  sim::InverterModel s15(sim::Model::kVfS15);
  WriteText(FilePath(), EepromFileContents(s15.SerializeEeprom()));
  ASSERT_TRUE(Start());
  EXPECT_TRUE(inverter_->started_new());
  EXPECT_EQ(Log(), "ipe002z-host: warning: " + FilePath() +
                       " is not usable (it holds a vf-s15 image, not vf-mb1); moved to " + FilePath() +
                       ".bad; the inverter starts from its factory defaults\n");
}

TEST_F(SimInverter, OneFilePerModel) {
  config_.presets = {Preset("acc=50", reg::kAcc, 50)};
  ASSERT_TRUE(Start());
  inverter_.reset();
  config_.model = sim::Model::kVfS15;
  config_.presets = {Preset("acc=70", reg::kAcc, 70)};
  ASSERT_TRUE(Start());
  EXPECT_TRUE(inverter_->started_new());
  EXPECT_EQ(inverter_->file_path(), dir_ + "/inverter/vf-s15.eeprom");
  EXPECT_EQ(Read(reg::kAcc), 70);
  EXPECT_EQ(Read(0xFB05), 9);  // the VF-S15's capacity code
  EXPECT_NE(ReadText(dir_ + "/inverter/vf-mb1.eeprom").find("\nreg 0009 50 1\n"), std::string::npos);
}

TEST_F(SimInverter, PresetRefusedByARunTimeLimit_FailsAndStoresNothing) {
  config_.presets = {Preset("ul=9000", reg::kUl, 9000)};  // ul <= fh (80.00 Hz)
  EXPECT_FALSE(Start());
  EXPECT_EQ(error_, "--param ul=9000: refused by the inverter (out of range)");
  EXPECT_FALSE(std::filesystem::exists(FilePath()));
}

TEST_F(SimInverter, ASettingIsStoredAtTheNextCheck) {
  ASSERT_TRUE(Start());  // created at t0; Start moved the clock to t0 + 2 s
  const hal::Micros t0 = clock_.NowMicros() - 2 * kSecond;
  EXPECT_EQ(inverter_->NextDeadline(), t0 + kSecond);
  inverter_->Poll(clock_.NowMicros());  // nothing changed but the hours: not stored
  EXPECT_EQ(inverter_->saves(), 1u);
  EXPECT_EQ(inverter_->NextDeadline(), t0 + 3 * kSecond);  // base time kept

  EXPECT_TRUE(inverter_->model().Write(reg::kAcc, 50, sim::WriteTarget::kRamAndEeprom).ok());
  inverter_->Poll(t0 + 2 * kSecond + 500 * hal::kMicrosPerMilli);  // before the check: nothing
  EXPECT_EQ(inverter_->saves(), 1u);
  clock_.Set(t0 + 3 * kSecond);
  inverter_->Poll(clock_.NowMicros());
  EXPECT_EQ(inverter_->saves(), 2u);
  EXPECT_NE(ReadText(FilePath()).find("\nreg 0009 50 1\n"), std::string::npos);
}

TEST_F(SimInverter, RamOnlyWritesAreNotStored) {
  ASSERT_TRUE(Start());
  EXPECT_TRUE(inverter_->model().Write(reg::kAcc, 50, sim::WriteTarget::kRamOnly).ok());  // P
  EXPECT_TRUE(inverter_->model().Write(reg::kFa06, 0x8000, sim::WriteTarget::kRamAndEeprom).ok());
  clock_.Advance(kSecond);
  inverter_->Poll(clock_.NowMicros());
  EXPECT_EQ(inverter_->saves(), 1u);
}

TEST_F(SimInverter, CountersAloneAreStoredOncePerMinute) {
  ASSERT_TRUE(Start());
  const hal::Micros t0 = clock_.NowMicros() - 2 * kSecond;
  for (int s = 3; s < 60; ++s) {
    clock_.Set(t0 + s * kSecond);
    inverter_->Poll(clock_.NowMicros());
  }
  EXPECT_EQ(inverter_->saves(), 1u);
  clock_.Set(t0 + 60 * kSecond);
  inverter_->Poll(clock_.NowMicros());
  EXPECT_EQ(inverter_->saves(), 2u);
  EXPECT_NE(ReadText(FilePath()).find("\npower-on-us 60000000\n"), std::string::npos);
}

TEST_F(SimInverter, SaveIfChanged_WritesOnlyADifferentImage) {
  ASSERT_TRUE(Start());
  EXPECT_TRUE(inverter_->SaveIfChanged());  // the hours moved since the start
  EXPECT_EQ(inverter_->saves(), 2u);
  EXPECT_TRUE(inverter_->SaveIfChanged());
  EXPECT_EQ(inverter_->saves(), 2u);
  EXPECT_FALSE(std::filesystem::exists(FilePath() + ".tmp"));
}

TEST_F(SimInverter, PowerCycle_RamOnlyRegistersBackToDefaultsAndImageStored) {
  ASSERT_TRUE(Start());
  EXPECT_TRUE(inverter_->model().Write(reg::kAcc, 50, sim::WriteTarget::kRamAndEeprom).ok());
  EXPECT_TRUE(inverter_->model().Write(reg::kDec, 50, sim::WriteTarget::kRamOnly).ok());
  EXPECT_TRUE(inverter_->model().Write(reg::kFa06, 0x8000, sim::WriteTarget::kRamOnly).ok());
  inverter_->model().Trip(sim::trip_code::kOptionCommunication);
  inverter_->PowerCycle();
  EXPECT_EQ(Read(reg::kFa06), 0);
  EXPECT_EQ(Read(reg::kAcc), 50);
  EXPECT_EQ(Read(reg::kDec), 100);  // the P write is lost, the EEPROM value returns
  EXPECT_FALSE(inverter_->model().tripped());
  EXPECT_TRUE(inverter_->model().in_reset(clock_.NowMicros()));  // the power-on second again
  EXPECT_EQ(inverter_->saves(), 2u);
  const std::string image = ReadText(FilePath());
  EXPECT_NE(image.find("\nreg 0009 50 1\n"), std::string::npos);
  EXPECT_NE(image.find("\ntrip-history 27 0 0 0\n"), std::string::npos);
}

TEST_F(SimInverter, StateDirNotWritable_WarnsOnceAndRuns) {
  WriteText(dir_ + "/blocked", "a file where the directory should be\n");
  config_.directory = dir_ + "/blocked/inverter";
  config_.presets = {Preset("acc=50", reg::kAcc, 50)};
  ASSERT_TRUE(Start());
  EXPECT_EQ(Read(reg::kAcc), 50);
  EXPECT_EQ(inverter_->saves(), 0u);
  const std::string warning = Log();
  EXPECT_EQ(warning.rfind("ipe002z-host: warning: cannot store the inverter's EEPROM (" + dir_ +
                              "/blocked/inverter: Not a directory); retrying\n",
                          0),
            0u)
      << warning;
  EXPECT_FALSE(inverter_->SaveIfChanged());
  EXPECT_EQ(Log(), warning);  // not repeated
}

TEST(SimInverterServerConfig, FromOptions) {
  HostOptions options;
  EXPECT_EQ(ServerConfigFromOptions(options).processing_delay, 2 * hal::kMicrosPerMilli);
  options.rs485_profile = true;
  const sim::ServerConfig rs485 = ServerConfigFromOptions(options);
  EXPECT_EQ(rs485.processing_delay, 20 * hal::kMicrosPerMilli);
  EXPECT_EQ(rs485.baud, 19200u);
  EXPECT_EQ(rs485.bits_per_character, 11);
  options.sim_processing_ms = 0;
  EXPECT_EQ(ServerConfigFromOptions(options).processing_delay, 0);
  options.rs485_profile = false;
  options.sim_processing_ms = 7;
  EXPECT_EQ(ServerConfigFromOptions(options).processing_delay, 7 * hal::kMicrosPerMilli);
}

}  // namespace
}  // namespace host::test
