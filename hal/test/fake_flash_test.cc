// The fake flash keeps the rules of hal/flash.h, and its power cuts leave exactly the mixes it promises
// (the store's power-cut tests are only as good as this).
#include "fake_flash.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

namespace hal::test {
namespace {

using Bytes = std::vector<std::uint8_t>;

Bytes ReadBytes(FakeFlash& flash, std::size_t offset, std::size_t size) {
  Bytes out(size);
  EXPECT_EQ(flash.Read(offset, out), base::OkStatus());
  return out;
}

TEST(FakeFlash, StartsErasedAndProgramOnlyClearsBits) {
  FakeFlash flash(64, 2, 4);
  EXPECT_EQ(flash.Size(), 128u);
  EXPECT_EQ(ReadBytes(flash, 0, 128), Bytes(128, 0xFF));
  ASSERT_EQ(flash.Program(4, Bytes{0x0F, 0xF0, 0x00, 0xFF}), base::OkStatus());
  EXPECT_EQ(ReadBytes(flash, 0, 12), (Bytes{0xFF, 0xFF, 0xFF, 0xFF, 0x0F, 0xF0, 0x00, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF}));
  EXPECT_EQ(flash.steps(), 4u);
  EXPECT_EQ(flash.violations(), 0);
}

TEST(FakeFlash, AUnitIsProgrammedOnceBetweenErases) {
  FakeFlash flash(64, 2, 4);
  ASSERT_EQ(flash.Program(0, Bytes{0xFE, 0xFF, 0xFF, 0xFF}), base::OkStatus());
  // Even a program that would only clear more bits is refused, and nothing of it is written.
  EXPECT_EQ(flash.Program(0, Bytes{0xFC, 0xFF, 0xFF, 0xFF, 0x00, 0x00, 0x00, 0x00}), base::FailedPrecondition());
  EXPECT_EQ(ReadBytes(flash, 0, 8), (Bytes{0xFE, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF}));
  EXPECT_EQ(flash.violations(), 1);
  ASSERT_EQ(flash.Erase(0), base::OkStatus());
  EXPECT_EQ(flash.erase_count(0), 1);
  EXPECT_EQ(flash.erase_count(1), 0);
  EXPECT_EQ(ReadBytes(flash, 0, 4), Bytes(4, 0xFF));
  EXPECT_EQ(flash.Program(0, Bytes{0x00, 0x11, 0x22, 0x33}), base::OkStatus());
  EXPECT_EQ(flash.steps(), 4u + 1u + 4u);
}

TEST(FakeFlash, MisalignedAndOutOfRangeCallsAreRefusedAndCounted) {
  FakeFlash flash(64, 2, 4);
  EXPECT_EQ(flash.Program(2, Bytes(4, 0)), base::InvalidArgument());
  EXPECT_EQ(flash.Program(0, Bytes(3, 0)), base::InvalidArgument());
  EXPECT_EQ(flash.Program(124, Bytes(8, 0)), base::OutOfRange());
  EXPECT_EQ(flash.Erase(2), base::OutOfRange());
  Bytes out(2);
  EXPECT_EQ(flash.Read(127, out), base::OutOfRange());
  EXPECT_EQ(flash.Read(1000, out), base::OutOfRange());
  EXPECT_EQ(flash.violations(), 6);
  EXPECT_EQ(ReadBytes(flash, 0, 128), Bytes(128, 0xFF));
  Bytes last(1);
  EXPECT_EQ(flash.Read(127, last), base::OkStatus());  // reads need no alignment
}

// Program 8 bytes in two units of 4; power fails at step 5 (byte 1 of the second unit).
Bytes CutSecondUnit(CutMix mix, std::uint32_t seed, FakeFlash& flash) {
  flash.CutPowerAtStep(5, mix, seed);
  EXPECT_EQ(flash.Program(0, Bytes{0x00, 0x00, 0x00, 0x00, 0x11, 0x22, 0x33, 0x44, 0x00, 0x00, 0x00, 0x00}),
            base::Unavailable());
  EXPECT_FALSE(flash.powered());
  flash.PowerOn();
  return ReadBytes(flash, 0, 12);
}

TEST(FakeFlash, ACutTearsOnlyTheUnitBeingProgrammed) {
  const Bytes first_done = {0x00, 0x00, 0x00, 0x00};
  const Bytes third_untouched = {0xFF, 0xFF, 0xFF, 0xFF};
  const auto expect = [&](CutMix mix, const Bytes& torn) {
    FakeFlash flash(64, 2, 4);
    Bytes expected = first_done;
    expected.insert(expected.end(), torn.begin(), torn.end());
    expected.insert(expected.end(), third_untouched.begin(), third_untouched.end());
    EXPECT_EQ(CutSecondUnit(mix, 1, flash), expected) << static_cast<int>(mix);
    EXPECT_EQ(flash.steps(), 4u);  // the torn unit's bytes are not counted as done
  };
  expect(CutMix::kOld, {0xFF, 0xFF, 0xFF, 0xFF});
  expect(CutMix::kPartlyNew, {0x11, 0xF2, 0xFF, 0xFF});  // byte 0 new, byte 1 half (0x22 | 0xF0)
  expect(CutMix::kNew, {0x11, 0x22, 0x33, 0x44});
}

TEST(FakeFlash, ARandomMixHasEveryNewBitOrItsOldOneAndDependsOnTheSeedOnly) {
  const Bytes data = {0x11, 0x22, 0x33, 0x44};
  Bytes previous;
  int differing = 0;
  for (std::uint32_t seed = 1; seed <= 8; ++seed) {
    FakeFlash flash(64, 2, 4);
    const Bytes after = CutSecondUnit(CutMix::kRandom, seed, flash);
    for (std::size_t i = 0; i < 4; ++i) {
      EXPECT_EQ(after[4 + i] & data[i], data[i]) << "a bit the program did not clear was cleared";
    }
    FakeFlash again(64, 2, 4);
    EXPECT_EQ(CutSecondUnit(CutMix::kRandom, seed, again), after);  // deterministic
    if (!previous.empty() && previous != after) ++differing;
    previous = after;
  }
  EXPECT_GT(differing, 0);
}

TEST(FakeFlash, NoPowerMeansNothingAnswersUntilPowerReturns) {
  FakeFlash flash(64, 2, 4);
  flash.CutPowerAtStep(0, CutMix::kOld);
  EXPECT_EQ(flash.Erase(1), base::Unavailable());
  Bytes out(4);
  EXPECT_EQ(flash.Read(0, out), base::Unavailable());
  EXPECT_EQ(flash.Program(0, Bytes(4, 0)), base::Unavailable());
  EXPECT_EQ(flash.Erase(0), base::Unavailable());
  flash.PowerOn();
  EXPECT_EQ(flash.Program(0, Bytes(4, 0)), base::OkStatus());  // sector 0 was not touched
}

TEST(FakeFlash, ATornUnitCountsAsProgrammedEvenWhenItReadsErased) {
  FakeFlash flash(64, 2, 4);
  EXPECT_EQ(CutSecondUnit(CutMix::kOld, 1, flash)[4], 0xFF);
  EXPECT_EQ(flash.Program(4, Bytes(4, 0)), base::FailedPrecondition());
  EXPECT_EQ(flash.Program(8, Bytes(4, 0)), base::OkStatus());  // the units after it are free
  EXPECT_EQ(flash.violations(), 1);
}

TEST(FakeFlash, UnreadableTornUnitsAnswerDataLoss) {
  FakeFlash flash(64, 2, 4);
  flash.CutPowerAtStep(5, CutMix::kPartlyNew);
  EXPECT_EQ(flash.Program(0, Bytes(8, 0)), base::Unavailable());
  flash.PowerOn();
  flash.set_torn_units_unreadable(true);
  Bytes out(4);
  EXPECT_EQ(flash.Read(0, out), base::OkStatus());
  EXPECT_EQ(flash.Read(4, out), base::DataLoss());
  EXPECT_EQ(flash.Read(2, out), base::DataLoss());
  EXPECT_EQ(flash.Read(8, out), base::OkStatus());
  ASSERT_EQ(flash.Erase(0), base::OkStatus());
  EXPECT_EQ(flash.Read(4, out), base::OkStatus());
}

TEST(FakeFlash, ACutEraseLeavesOldBitsAndOnesAndTheSectorUnprogrammable) {
  for (const CutMix mix : {CutMix::kOld, CutMix::kPartlyNew, CutMix::kRandom, CutMix::kNew}) {
    FakeFlash flash(64, 2, 4);
    Bytes old(64);
    for (std::size_t i = 0; i < old.size(); ++i) old[i] = static_cast<std::uint8_t>(i * 37);
    ASSERT_EQ(flash.Program(64, old), base::OkStatus());
    flash.CutPowerAtStep(flash.steps(), mix, 3);
    EXPECT_EQ(flash.Erase(1), base::Unavailable());
    flash.PowerOn();
    const Bytes after = ReadBytes(flash, 64, 64);
    for (std::size_t i = 0; i < 64; ++i) EXPECT_EQ(after[i] & old[i], old[i]) << "byte " << i;
    if (mix == CutMix::kOld) {
      EXPECT_EQ(after, old);
    }
    if (mix == CutMix::kNew) {
      EXPECT_EQ(after, Bytes(64, 0xFF));
    }
    if (mix == CutMix::kPartlyNew || mix == CutMix::kRandom) {
      EXPECT_NE(after, old);
      EXPECT_NE(after, Bytes(64, 0xFF));
    }
    EXPECT_EQ(flash.erase_count(1), 0);
    EXPECT_EQ(flash.Program(64 + 60, Bytes(4, 0)), base::FailedPrecondition()) << "not erased";
    ASSERT_EQ(flash.Erase(1), base::OkStatus());
    EXPECT_EQ(flash.Program(64 + 60, Bytes(4, 0)), base::OkStatus());
  }
}

TEST(FakeFlash, ContentsSetByATestCountAsProgrammedWhereNotErased) {
  FakeFlash flash(16, 2, 4);
  Bytes contents(32, 0xFF);
  contents[5] = 0x7F;
  flash.SetContents(contents);
  EXPECT_EQ(ReadBytes(flash, 0, 32), contents);
  EXPECT_EQ(flash.Program(4, Bytes(4, 0)), base::FailedPrecondition());
  EXPECT_EQ(flash.Program(0, Bytes(4, 0)), base::OkStatus());
  flash.FlipBits(0, 0x81);
  EXPECT_EQ(ReadBytes(flash, 0, 1), Bytes{0x81});
}

}  // namespace
}  // namespace hal::test
