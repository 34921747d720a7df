// Power loss while the simulated inverter stores its EEPROM image (docs/robustness.md "Power loss"): for
// every number of bytes of the new file that may have reached the disk (0 .. all of them, not yet
// renamed) and for a cut just after the rename, a new inverter created on the same state dir, as the
// next start creates it, holds exactly the old image or exactly the new one. And a live file that is
// only part of an image (what a file system that broke its promises would leave) is never loaded.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "host_sim_fixture.h"
#include "sim/register_numbers.h"

namespace host::test {
namespace {

namespace reg = sim::reg;
using hal::host::PowerCut;

class EepromPowerCut : public SimInverterFixture {
 protected:
  // What the next start sees: the inverter created on the state dir, before any time passes.
  struct Restart {
    bool started_new = false;
    std::string image;  // its EEPROM image as loaded
    std::uint16_t acc = 0;
  };
  Restart RestartOnTheStateDir() {
    std::string error;
    std::unique_ptr<SimulatedInverter> next = SimulatedInverter::Create(config_, *line_, clock_, log_, error);
    EXPECT_NE(next, nullptr) << error;
    if (next == nullptr) return {};
    return Restart{next->started_new(), next->model().SerializeEeprom(), *next->model().Read(reg::kAcc)};
  }
};

TEST_F(EepromPowerCut, EveryByteOfAnImageWrite_OldOrNewImage) {
  ASSERT_TRUE(Start());  // a new inverter: its image is stored
  ASSERT_TRUE(inverter_->SaveIfChanged());
  const std::string old_image = inverter_->model().SerializeEeprom();
  ASSERT_EQ(ReadText(FilePath()), EepromFileContents(old_image));
  ASSERT_TRUE(inverter_->model().Write(reg::kAcc, 50, sim::WriteTarget::kRamAndEeprom).ok());
  const std::string new_image = inverter_->model().SerializeEeprom();  // the clock stands still
  const std::size_t file_size = EepromFileContents(new_image).size();
  ASSERT_GT(file_size, 1000u);

  // A cut before the rename leaves the live file alone, so the same inverter tries again at each cut;
  // its image stays the new one (the fake clock does not move).
  for (std::size_t cut = 0; cut <= file_size; ++cut) {
    inverter_->CutPowerDuringNextSaveForTest(PowerCut{PowerCut::Stage::kWritingTempFile, cut});
    ASSERT_FALSE(inverter_->SaveIfChanged()) << cut;
    ASSERT_EQ(std::filesystem::file_size(FilePath() + ".tmp"), cut);
    const Restart restart = RestartOnTheStateDir();
    ASSERT_FALSE(restart.started_new) << "cut after " << cut << " of " << file_size << " bytes";
    ASSERT_EQ(restart.image, old_image) << "cut after " << cut << " of " << file_size << " bytes";
    ASSERT_EQ(restart.acc, 100);
    ASSERT_FALSE(std::filesystem::exists(FilePath() + ".tmp")) << cut;  // the start removed it
  }
  inverter_->CutPowerDuringNextSaveForTest(PowerCut{PowerCut::Stage::kAfterRename, 0});
  ASSERT_FALSE(inverter_->SaveIfChanged());
  const Restart restart = RestartOnTheStateDir();
  EXPECT_FALSE(restart.started_new);
  EXPECT_EQ(restart.image, new_image);
  EXPECT_EQ(restart.acc, 50);
  EXPECT_FALSE(std::filesystem::exists(FilePath() + ".bad"));
  EXPECT_EQ(Log(), "ipe002z-host: warning: cannot store the inverter's EEPROM (power cut (test)); retrying\n");
}

TEST_F(EepromPowerCut, LiveFileCutShortAtEveryByte_NeverLoaded) {
  ASSERT_TRUE(Start());
  ASSERT_TRUE(inverter_->model().Write(reg::kAcc, 50, sim::WriteTarget::kRamAndEeprom).ok());
  ASSERT_TRUE(inverter_->SaveIfChanged());
  const std::string whole = ReadText(FilePath());
  inverter_.reset();
  // Every proper prefix: a file system that made the rename durable before the data (no fsync) could
  // leave any of them. None may be taken for an image: the inverter starts from its factory defaults.
  for (std::size_t size = 0; size < whole.size(); ++size) {
    std::filesystem::remove(FilePath() + ".bad");
    WriteText(FilePath(), whole.substr(0, size));
    const Restart restart = RestartOnTheStateDir();
    ASSERT_TRUE(restart.started_new) << "cut short to " << size << " of " << whole.size() << " bytes";
    ASSERT_EQ(restart.acc, 100) << size;
    ASSERT_EQ(ReadText(FilePath() + ".bad"), whole.substr(0, size)) << size;
  }
  // The whole file is the image.
  WriteText(FilePath(), whole);
  EXPECT_EQ(RestartOnTheStateDir().acc, 50);
}

}  // namespace
}  // namespace host::test
