// hal::FlashNvStore on the fake flash: the documented layout byte for byte, the NvStore contract's
// status codes, compaction and its ring, damaged and foreign flash contents. Power cuts:
// flash_nv_store_power_cut_test.cc.
#include "hal/flash_nv_store.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "base/crc32.h"
#include "fake_flash.h"

namespace hal {
namespace {

using Bytes = std::vector<std::uint8_t>;
using test::FakeFlash;

Bytes BytesOf(const std::string& text) { return Bytes(text.begin(), text.end()); }

Bytes Pattern(std::size_t size, std::uint8_t seed) {
  Bytes bytes(size);
  for (std::size_t i = 0; i < size; ++i) bytes[i] = static_cast<std::uint8_t>(seed + i * 7);
  return bytes;
}

// The record `id` as `store` reads it, or its status.
base::Result<Bytes> ReadRecord(NvStore& store, NvRecordId id) {
  Bytes buffer(kMaxRecordBytes);
  const base::Result<std::size_t> n = store.Read(id, buffer);
  if (!n.ok()) return n.status();
  buffer.resize(*n);
  return buffer;
}

// The record as a store mounted afresh on `flash` reads it (what the card sees after a restart).
base::Result<Bytes> ReadAfterRestart(FakeFlash& flash, NvRecordId id) {
  FlashNvStore store(flash);
  EXPECT_EQ(store.Mount(), base::OkStatus());
  return ReadRecord(store, id);
}

Bytes FlashBytes(const FakeFlash& flash, std::size_t offset, std::size_t size) {
  return Bytes(flash.bytes().begin() + static_cast<std::ptrdiff_t>(offset),
               flash.bytes().begin() + static_cast<std::ptrdiff_t>(offset + size));
}

TEST(FlashNvStore, FootprintsFollowTheProgramUnit) {
  EXPECT_EQ(FlashNvStore::SectorOverhead(1), 20u);
  EXPECT_EQ(FlashNvStore::SectorOverhead(4), 20u);
  EXPECT_EQ(FlashNvStore::SectorOverhead(8), 24u);
  EXPECT_EQ(FlashNvStore::SectorOverhead(32), 64u);
  EXPECT_EQ(FlashNvStore::RecordFootprint(0, 1), 24u);
  EXPECT_EQ(FlashNvStore::RecordFootprint(9, 1), 33u);
  EXPECT_EQ(FlashNvStore::RecordFootprint(9, 4), 36u);
  EXPECT_EQ(FlashNvStore::RecordFootprint(6, 8), 24u + 8u + 8u);
  EXPECT_EQ(FlashNvStore::RecordFootprint(107, 16), 32u + 112u + 16u);
  EXPECT_EQ(FlashNvStore::RecordFootprint(1024, 32), 32u + 1024u + 32u);
}

TEST(FlashNvStore, WritesTheDocumentedLayout) {
  FakeFlash flash(512, 2, 4);
  FlashNvStore store(flash);
  ASSERT_EQ(store.Mount(), base::OkStatus());
  ASSERT_EQ(store.Write(7, BytesOf("123456789")), base::OkStatus());

  const Bytes expected = {
      // sector 0 header
      0x49, 0x50, 0x4E, 0x46,  // magic "IPNF"
      0x01, 0x00,              // format 1
      0x04, 0x00,              // program unit 4
      0xFE, 0xFF, 0xFF, 0xFF,  // generation 1, inverted
      0xBA, 0xDE, 0x66, 0xB2,  // CRC-32 of the 12 bytes before
      'L', 'I', 'V', 'E',      // sector commit at A(16) = 16
      // record at A(16) + A(4) = 20
      0x52, 0x44,              // tag "RD"
      0x07, 0x00,              // id 7
      0x09, 0x00, 0x00, 0x00,  // length 9
      0x01, 0x00, 0x00, 0x00,  // sequence 1
      0x26, 0x39, 0xF4, 0xCB,  // CRC-32("123456789") = 0xCBF43926
      0xFF, 0x39, 0x8E, 0x05,  // CRC-32 of the 16 header bytes before
      '1', '2', '3', '4', '5', '6', '7', '8', '9', 0xFF, 0xFF, 0xFF,  // payload at 20 + A(20), padded
      'C', 'M', 'I', 'T',      // record commit at 40 + A(9)
      0xFF, 0xFF, 0xFF, 0xFF};
  EXPECT_EQ(FlashBytes(flash, 0, expected.size()), expected);
  EXPECT_EQ(FlashBytes(flash, 512, 512), Bytes(512, 0xFF)) << "sector 1 untouched";
  EXPECT_EQ(flash.erase_count(0), 1) << "the first change formats sector 0";
  EXPECT_EQ(store.usage().append_offset, 56u);
  EXPECT_EQ(ReadRecord(store, 7).value(), BytesOf("123456789"));
}

TEST(FlashNvStore, LayoutOffsetsScaleWithALargerProgramUnit) {
  FakeFlash flash(1024, 2, 16);
  FlashNvStore store(flash);
  ASSERT_EQ(store.Mount(), base::OkStatus());
  ASSERT_EQ(store.Write(0x20, Bytes{0xAB}), base::OkStatus());
  EXPECT_EQ(FlashBytes(flash, 6, 2), (Bytes{0x10, 0x00}));           // program unit 16 in the header
  EXPECT_EQ(FlashBytes(flash, 16, 4), BytesOf("LIVE"));               // sector commit at A(16) = 16
  EXPECT_EQ(FlashBytes(flash, 32, 4), (Bytes{0x52, 0x44, 0x20, 0x00}));  // record at 16 + A(4) = 32
  EXPECT_EQ(FlashBytes(flash, 32 + 32, 2), (Bytes{0xAB, 0xFF}));      // payload at A(20) = 32
  EXPECT_EQ(FlashBytes(flash, 32 + 48, 16), (Bytes{'C', 'M', 'I', 'T', 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF,
                                                    0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF}));
  EXPECT_EQ(store.usage().append_offset, 32u + 64u);
}

TEST(FlashNvStore, MountRefusesAGeometryTheLayoutCannotUse) {
  const auto mount = [](std::size_t sector_size, std::size_t count, std::size_t unit) {
    FakeFlash flash(sector_size, count, unit);
    FlashNvStore store(flash);
    return store.Mount();
  };
  EXPECT_EQ(mount(4096, 1, 4), base::InvalidArgument()) << "one sector: no place to compact into";
  EXPECT_EQ(mount(4096, 2, 64), base::InvalidArgument()) << "unit above kMaxProgramUnit";
  EXPECT_EQ(mount(4080, 2, 48), base::InvalidArgument()) << "not a power of two";
  EXPECT_EQ(mount(36, 2, 4), base::InvalidArgument()) << "no room for an empty record";
  EXPECT_EQ(mount(44, 2, 4), base::OkStatus()) << "room for one empty record";
  EXPECT_EQ(mount(4096, 2, 32), base::OkStatus());
  EXPECT_EQ(mount(256, 16, 1), base::OkStatus());
}

TEST(FlashNvStore, EveryCallBeforeASuccessfulMountIsFailedPrecondition) {
  FakeFlash flash(4096, 1, 4);
  FlashNvStore store(flash);
  Bytes out(8);
  EXPECT_EQ(store.Read(1, out).status(), base::FailedPrecondition());
  EXPECT_EQ(store.Write(1, Bytes{1}), base::FailedPrecondition());
  EXPECT_EQ(store.Erase(1), base::FailedPrecondition());
  EXPECT_EQ(store.Mount(), base::InvalidArgument());
  EXPECT_EQ(store.Write(1, Bytes{1}), base::FailedPrecondition());
  EXPECT_EQ(flash.steps(), 0u);
}

TEST(FlashNvStore, ABlankFlashIsAnEmptyStoreAndMountingWritesNothing) {
  FakeFlash flash(4096, 2, 4);
  FlashNvStore store(flash);
  ASSERT_EQ(store.Mount(), base::OkStatus());
  EXPECT_EQ(ReadRecord(store, 1).status(), base::NotFound());
  EXPECT_EQ(store.Erase(1), base::OkStatus());
  EXPECT_FALSE(store.usage().has_active);
  EXPECT_EQ(flash.steps(), 0u) << "no erase, no program";
}

TEST(FlashNvStore, ReadsBackWhatWasWrittenAndNothingMore) {
  FakeFlash flash(4096, 2, 4);
  FlashNvStore store(flash);
  ASSERT_EQ(store.Mount(), base::OkStatus());
  const Bytes data = BytesOf("admin:secret");
  ASSERT_EQ(store.Write(3, data), base::OkStatus());
  Bytes out(64, 0xEE);
  ASSERT_EQ(store.Read(3, out).value(), data.size());
  EXPECT_EQ(Bytes(out.begin(), out.begin() + 12), data);
  EXPECT_EQ(out[12], 0xEE);
  EXPECT_EQ(ReadAfterRestart(flash, 3).value(), data);
}

TEST(FlashNvStore, BufferTooSmallIsOutOfRangeAndLeavesItUntouched) {
  FakeFlash flash(4096, 2, 4);
  FlashNvStore store(flash);
  ASSERT_EQ(store.Mount(), base::OkStatus());
  ASSERT_EQ(store.Write(4, BytesOf("0123456789")), base::OkStatus());
  Bytes small(9, 0xEE);
  EXPECT_EQ(store.Read(4, small).status(), base::OutOfRange());
  EXPECT_EQ(small, Bytes(9, 0xEE));
  Bytes exact(10);
  EXPECT_EQ(store.Read(4, exact).value(), 10u);
}

TEST(FlashNvStore, EmptyRecordsAndEveryIdWork) {
  FakeFlash flash(4096, 2, 1);
  FlashNvStore store(flash);
  ASSERT_EQ(store.Mount(), base::OkStatus());
  ASSERT_EQ(store.Write(0, Bytes{}), base::OkStatus());
  ASSERT_EQ(store.Write(0xFFFF, BytesOf("last id")), base::OkStatus());
  ASSERT_EQ(store.Write(0x00FF, BytesOf("low byte 0xFF")), base::OkStatus());  // an id byte of 0xFF
  EXPECT_EQ(ReadAfterRestart(flash, 0).value(), Bytes{});
  EXPECT_EQ(ReadAfterRestart(flash, 0xFFFF).value(), BytesOf("last id"));
  EXPECT_EQ(ReadAfterRestart(flash, 0x00FF).value(), BytesOf("low byte 0xFF"));
  EXPECT_EQ(ReadAfterRestart(flash, 0xFF00).status(), base::NotFound());
}

TEST(FlashNvStore, LargestRecordFitsAndOneMoreByteIsInvalidArgument) {
  FakeFlash flash(4096, 2, 8);
  FlashNvStore store(flash);
  ASSERT_EQ(store.Mount(), base::OkStatus());
  const Bytes largest = Pattern(kMaxRecordBytes, 3);
  ASSERT_EQ(store.Write(5, largest), base::OkStatus());
  EXPECT_EQ(ReadAfterRestart(flash, 5).value(), largest);
  const std::uint64_t steps = flash.steps();
  EXPECT_EQ(store.Write(6, Bytes(kMaxRecordBytes + 1)), base::InvalidArgument());
  EXPECT_EQ(flash.steps(), steps);
  EXPECT_EQ(ReadAfterRestart(flash, 6).status(), base::NotFound());
}

TEST(FlashNvStore, ARecordLargerThanASectorHoldsIsResourceExhausted) {
  FakeFlash flash(1024, 2, 4);  // 1024 - 20 bytes for records: at most 980 bytes of payload
  FlashNvStore store(flash);
  ASSERT_EQ(store.Mount(), base::OkStatus());
  EXPECT_EQ(store.Write(1, Bytes(kMaxRecordBytes)), base::ResourceExhausted());
  EXPECT_EQ(store.Write(1, Bytes(981)), base::ResourceExhausted());
  EXPECT_EQ(flash.steps(), 0u);
  ASSERT_EQ(store.Write(1, Pattern(980, 1)), base::OkStatus());
  EXPECT_EQ(ReadAfterRestart(flash, 1).value(), Pattern(980, 1));
}

TEST(FlashNvStore, OverwritesAppendAndTheNewestCopyWins) {
  FakeFlash flash(4096, 2, 4);
  FlashNvStore store(flash);
  ASSERT_EQ(store.Mount(), base::OkStatus());
  ASSERT_EQ(store.Write(8, BytesOf("a long first value")), base::OkStatus());
  ASSERT_EQ(store.Write(9, BytesOf("other")), base::OkStatus());
  ASSERT_EQ(store.Write(8, BytesOf("short")), base::OkStatus());
  EXPECT_EQ(ReadRecord(store, 8).value(), BytesOf("short"));
  EXPECT_EQ(ReadAfterRestart(flash, 8).value(), BytesOf("short"));
  EXPECT_EQ(ReadAfterRestart(flash, 9).value(), BytesOf("other"));
  EXPECT_EQ(flash.erase_count(0) + flash.erase_count(1), 1) << "appends need no erase";
}

TEST(FlashNvStore, EraseWritesATombstoneOnlyWhenThereIsSomethingToErase) {
  FakeFlash flash(4096, 2, 4);
  FlashNvStore store(flash);
  ASSERT_EQ(store.Mount(), base::OkStatus());
  ASSERT_EQ(store.Write(10, BytesOf("x")), base::OkStatus());
  ASSERT_EQ(store.Write(11, BytesOf("kept")), base::OkStatus());
  const std::size_t before = store.usage().append_offset;
  EXPECT_EQ(store.Erase(10), base::OkStatus());
  EXPECT_EQ(store.usage().append_offset, before + FlashNvStore::RecordFootprint(0, 4));
  EXPECT_EQ(FlashBytes(flash, before, 2), (Bytes{0x54, 0x42})) << "tag \"TB\"";
  EXPECT_EQ(ReadRecord(store, 10).status(), base::NotFound());
  EXPECT_EQ(ReadAfterRestart(flash, 10).status(), base::NotFound());
  EXPECT_EQ(ReadAfterRestart(flash, 11).value(), BytesOf("kept"));
  const std::uint64_t steps = flash.steps();
  EXPECT_EQ(store.Erase(10), base::OkStatus());  // idempotent, and costs nothing
  EXPECT_EQ(store.Erase(12), base::OkStatus());
  EXPECT_EQ(flash.steps(), steps);
  ASSERT_EQ(store.Write(10, BytesOf("back")), base::OkStatus());
  EXPECT_EQ(ReadAfterRestart(flash, 10).value(), BytesOf("back"));
}

TEST(FlashNvStore, AFullStoreRefusesWithResourceExhaustedAndKeepsEverything) {
  // 256 - 20 = 236 bytes for records; five of 16 bytes take 5 x (20 + 16 + 4) = 200, 36 are left.
  FakeFlash flash(256, 2, 4);
  FlashNvStore store(flash);
  ASSERT_EQ(store.Mount(), base::OkStatus());
  for (NvRecordId id = 1; id <= 5; ++id) {
    ASSERT_EQ(store.Write(id, Pattern(16, static_cast<std::uint8_t>(id))), base::OkStatus());
  }
  EXPECT_EQ(store.Write(6, Pattern(20, 6)), base::ResourceExhausted()) << "44 bytes, even after compacting";
  EXPECT_EQ(store.Write(6, Bytes{}), base::OkStatus()) << "an empty record takes 24";
  EXPECT_EQ(store.Write(7, Bytes{}), base::ResourceExhausted());
  // Replacing record 1: 236 - 4 x 40 - 24 = 52 bytes for it after a compaction.
  EXPECT_EQ(store.Write(1, Pattern(32, 9)), base::ResourceExhausted()) << "56 bytes";
  for (NvRecordId id = 1; id <= 5; ++id) {
    EXPECT_EQ(ReadAfterRestart(flash, id).value(), Pattern(16, static_cast<std::uint8_t>(id))) << id;
  }
  EXPECT_EQ(ReadAfterRestart(flash, 6).value(), Bytes{});
  ASSERT_EQ(store.Write(1, Pattern(28, 9)), base::OkStatus()) << "52 bytes: exactly full";
  EXPECT_EQ(ReadAfterRestart(flash, 1).value(), Pattern(28, 9));
  // The same size again fits, over and over: each compaction drops the copy it replaces.
  for (int round = 0; round < 10; ++round) {
    ASSERT_EQ(store.Write(3, Pattern(16, static_cast<std::uint8_t>(100 + round))), base::OkStatus()) << round;
  }
  EXPECT_EQ(ReadAfterRestart(flash, 3).value(), Pattern(16, 109));
  // An erase makes room, even when the store is too full for its tombstone.
  ASSERT_EQ(store.Erase(2), base::OkStatus());
  ASSERT_EQ(store.Write(7, Pattern(16, 7)), base::OkStatus());
  EXPECT_EQ(ReadAfterRestart(flash, 2).status(), base::NotFound());
  EXPECT_EQ(ReadAfterRestart(flash, 7).value(), Pattern(16, 7));
  EXPECT_EQ(ReadAfterRestart(flash, 1).value(), Pattern(28, 9));
  EXPECT_EQ(flash.violations(), 0);
}

TEST(FlashNvStore, CompactionsGoRoundTheRingAndSpreadTheWear) {
  FakeFlash flash(256, 3, 4);
  FlashNvStore store(flash);
  ASSERT_EQ(store.Mount(), base::OkStatus());
  ASSERT_EQ(store.Write(1, BytesOf("constant")), base::OkStatus());
  std::vector<std::size_t> actives;
  for (int i = 0; i < 60; ++i) {
    ASSERT_EQ(store.Write(2, Pattern(40, static_cast<std::uint8_t>(i))), base::OkStatus()) << i;
    if (actives.empty() || actives.back() != store.usage().active_sector) {
      actives.push_back(store.usage().active_sector);
    }
  }
  ASSERT_GE(actives.size(), 7u);
  for (std::size_t i = 0; i < actives.size(); ++i) EXPECT_EQ(actives[i], i % 3) << i;
  EXPECT_EQ(store.usage().generation, actives.size());
  // Each sector erased once per visit: the counts differ by at most one.
  const int e0 = flash.erase_count(0), e1 = flash.erase_count(1), e2 = flash.erase_count(2);
  EXPECT_LE(std::max({e0, e1, e2}) - std::min({e0, e1, e2}), 1);
  EXPECT_EQ(e0 + e1 + e2, static_cast<int>(actives.size()));
  EXPECT_EQ(ReadAfterRestart(flash, 1).value(), BytesOf("constant"));
  EXPECT_EQ(ReadAfterRestart(flash, 2).value(), Pattern(40, 59));
}

TEST(FlashNvStore, CompactionKeepsCurrentRecordsOnlyAndForgetsTombstones) {
  FakeFlash flash(512, 2, 4);
  FlashNvStore store(flash);
  ASSERT_EQ(store.Mount(), base::OkStatus());
  ASSERT_EQ(store.Write(1, BytesOf("one")), base::OkStatus());
  ASSERT_EQ(store.Write(2, BytesOf("two")), base::OkStatus());
  ASSERT_EQ(store.Write(3, BytesOf("three")), base::OkStatus());
  ASSERT_EQ(store.Erase(2), base::OkStatus());
  while (store.usage().generation == 1) ASSERT_EQ(store.Write(3, Pattern(100, 3)), base::OkStatus());
  // The new sector: header, then "one" (seq 1), then the new 3 (seq 2); no 2, no tombstone.
  const std::size_t records = 512 + FlashNvStore::SectorOverhead(4);
  EXPECT_EQ(FlashBytes(flash, records, 12),
            (Bytes{0x52, 0x44, 0x01, 0x00, 0x03, 0x00, 0x00, 0x00, 0x01, 0x00, 0x00, 0x00}));
  const std::size_t second = records + FlashNvStore::RecordFootprint(3, 4);
  EXPECT_EQ(FlashBytes(flash, second, 12),
            (Bytes{0x52, 0x44, 0x03, 0x00, 0x64, 0x00, 0x00, 0x00, 0x02, 0x00, 0x00, 0x00}));
  EXPECT_EQ(store.usage().append_offset, second - 512 + FlashNvStore::RecordFootprint(100, 4));
  EXPECT_EQ(ReadAfterRestart(flash, 1).value(), BytesOf("one"));
  EXPECT_EQ(ReadAfterRestart(flash, 2).status(), base::NotFound());
  EXPECT_EQ(ReadAfterRestart(flash, 3).value(), Pattern(100, 3));
}

TEST(FlashNvStore, TheFirstChangeAfterAStartCompactsAndTheNextOnesAppend) {
  FakeFlash flash(4096, 2, 8);
  {
    FlashNvStore store(flash);
    ASSERT_EQ(store.Mount(), base::OkStatus());
    ASSERT_EQ(store.Write(1, BytesOf("one")), base::OkStatus());
    ASSERT_EQ(store.Write(2, BytesOf("two")), base::OkStatus());
  }
  FlashNvStore store(flash);
  ASSERT_EQ(store.Mount(), base::OkStatus());
  EXPECT_EQ(store.usage().append_offset, 4096u) << "nothing goes after a log this session did not write";
  EXPECT_EQ(ReadRecord(store, 2).value(), BytesOf("two"));
  ASSERT_EQ(store.Write(3, BytesOf("three")), base::OkStatus());
  EXPECT_EQ(store.usage().active_sector, 1u);
  EXPECT_EQ(store.usage().generation, 2u);
  EXPECT_EQ(flash.erase_count(1), 1);
  const std::size_t records = FlashNvStore::SectorOverhead(8);
  const std::size_t three = FlashNvStore::RecordFootprint(3, 8) * 2 + FlashNvStore::RecordFootprint(5, 8);
  EXPECT_EQ(store.usage().append_offset, records + three);
  ASSERT_EQ(store.Write(1, BytesOf("ONE")), base::OkStatus());
  EXPECT_EQ(store.usage().generation, 2u) << "appended";
  EXPECT_EQ(FlashBytes(flash, 4096 + records + three, 4), (Bytes{0x52, 0x44, 0x01, 0x00}));
  EXPECT_EQ(ReadAfterRestart(flash, 1).value(), BytesOf("ONE"));
  EXPECT_EQ(ReadAfterRestart(flash, 2).value(), BytesOf("two"));
  EXPECT_EQ(ReadAfterRestart(flash, 3).value(), BytesOf("three"));
  EXPECT_EQ(flash.violations(), 0);
}

TEST(FlashNvStore, ADamagedNewestCopyGivesThePreviousOneAndALoneDamagedCopyIsDataLoss) {
  FakeFlash flash(4096, 2, 4);
  FlashNvStore store(flash);
  ASSERT_EQ(store.Mount(), base::OkStatus());
  ASSERT_EQ(store.Write(1, BytesOf("old")), base::OkStatus());
  const std::size_t newest = store.usage().append_offset;
  ASSERT_EQ(store.Write(1, BytesOf("new")), base::OkStatus());
  const std::size_t alone = store.usage().append_offset;
  ASSERT_EQ(store.Write(2, BytesOf("alone")), base::OkStatus());
  const std::size_t payload = 20;  // A(20) with a unit of 4
  flash.FlipBits(newest + payload, 0x01);
  EXPECT_EQ(ReadRecord(store, 1).value(), BytesOf("old"));
  EXPECT_EQ(ReadAfterRestart(flash, 1).value(), BytesOf("old"));
  flash.FlipBits(alone + payload + 4, 0x80);
  EXPECT_EQ(ReadRecord(store, 2).status(), base::DataLoss());
  EXPECT_EQ(ReadAfterRestart(flash, 2).status(), base::DataLoss());
  // A damaged record can be erased and written again.
  FlashNvStore again(flash);
  ASSERT_EQ(again.Mount(), base::OkStatus());
  EXPECT_EQ(again.Erase(2), base::OkStatus());
  EXPECT_EQ(ReadRecord(again, 2).status(), base::NotFound());
  ASSERT_EQ(again.Write(2, BytesOf("again")), base::OkStatus());
  EXPECT_EQ(ReadAfterRestart(flash, 2).value(), BytesOf("again"));
}

TEST(FlashNvStore, ADamagedHeaderEndsTheLogAndTheNextChangeCompacts) {
  FakeFlash flash(4096, 2, 4);
  FlashNvStore store(flash);
  ASSERT_EQ(store.Mount(), base::OkStatus());
  ASSERT_EQ(store.Write(1, BytesOf("one")), base::OkStatus());
  ASSERT_EQ(store.Write(2, BytesOf("two")), base::OkStatus());
  const std::size_t third = store.usage().append_offset;
  ASSERT_EQ(store.Write(2, BytesOf("two, later")), base::OkStatus());
  flash.FlipBits(third + 5, 0x01);  // its length: the header CRC fails, the record's end is unknown

  FlashNvStore mounted(flash);
  ASSERT_EQ(mounted.Mount(), base::OkStatus());
  EXPECT_EQ(ReadRecord(mounted, 1).value(), BytesOf("one"));
  EXPECT_EQ(ReadRecord(mounted, 2).value(), BytesOf("two"));
  ASSERT_EQ(mounted.Write(3, BytesOf("three")), base::OkStatus());
  EXPECT_EQ(mounted.usage().active_sector, 1u);
  EXPECT_EQ(mounted.usage().generation, 2u);
  EXPECT_EQ(ReadAfterRestart(flash, 1).value(), BytesOf("one"));
  EXPECT_EQ(ReadAfterRestart(flash, 2).value(), BytesOf("two"));
  EXPECT_EQ(ReadAfterRestart(flash, 3).value(), BytesOf("three"));
  EXPECT_EQ(flash.violations(), 0);
}

TEST(FlashNvStore, AnUncommittedRecordIsIgnored) {
  FakeFlash flash(4096, 2, 4);
  FlashNvStore store(flash);
  ASSERT_EQ(store.Mount(), base::OkStatus());
  ASSERT_EQ(store.Write(1, BytesOf("committed")), base::OkStatus());
  const std::size_t second = store.usage().append_offset;
  ASSERT_EQ(store.Write(1, BytesOf("then this")), base::OkStatus());
  flash.FlipBits(second + 20 + 12, 0x02);  // "CMIT" -> "AMIT"
  EXPECT_EQ(ReadAfterRestart(flash, 1).value(), BytesOf("committed"));
}

// A record programmed by hand after the log, valid in itself, with sequence number `sequence`.
void AppendRawRecord(FakeFlash& flash, std::size_t offset, NvRecordId id, const Bytes& payload,
                     std::uint32_t sequence) {
  Bytes record = {0x52, 0x44, static_cast<std::uint8_t>(id), static_cast<std::uint8_t>(id >> 8)};
  for (const std::uint32_t field : {static_cast<std::uint32_t>(payload.size()), sequence, base::Crc32(payload)}) {
    for (int i = 0; i < 4; ++i) record.push_back(static_cast<std::uint8_t>(field >> (8 * i)));
  }
  const std::uint32_t header_crc = base::Crc32(record);
  for (int i = 0; i < 4; ++i) record.push_back(static_cast<std::uint8_t>(header_crc >> (8 * i)));
  record.insert(record.end(), payload.begin(), payload.end());
  while (record.size() % 4 != 0) record.push_back(0xFF);
  record.insert(record.end(), {'C', 'M', 'I', 'T'});
  ASSERT_EQ(flash.Program(offset, record), base::OkStatus());
}

TEST(FlashNvStore, TheLogEndsWhereSequenceNumbersStopRising) {
  FakeFlash flash(4096, 2, 4);
  std::size_t end = 0;
  {
    FlashNvStore store(flash);
    ASSERT_EQ(store.Mount(), base::OkStatus());
    ASSERT_EQ(store.Write(1, BytesOf("a")), base::OkStatus());  // sequence 1
    ASSERT_EQ(store.Write(2, BytesOf("b")), base::OkStatus());  // sequence 2
    end = store.usage().append_offset;
  }
  AppendRawRecord(flash, end, 1, BytesOf("not after 2"), 2);
  EXPECT_EQ(ReadAfterRestart(flash, 1).value(), BytesOf("a"));
  AppendRawRecord(flash, end + FlashNvStore::RecordFootprint(11, 4), 1, BytesOf("z"), 3);
  EXPECT_EQ(ReadAfterRestart(flash, 1).value(), BytesOf("a")) << "nothing after the log's end counts";

  FakeFlash rising(4096, 2, 4);
  rising.SetContents(FlashBytes(flash, 0, end));
  AppendRawRecord(rising, end, 1, BytesOf("c"), 7);
  EXPECT_EQ(ReadAfterRestart(rising, 1).value(), BytesOf("c")) << "any rise will do";
}

TEST(FlashNvStore, TheCommittedSectorWithTheHighestGenerationIsActive) {
  FakeFlash flash(256, 3, 4);
  {
    FlashNvStore store(flash);
    ASSERT_EQ(store.Mount(), base::OkStatus());
    while (store.usage().generation < 3) ASSERT_EQ(store.Write(1, Pattern(60, 1)), base::OkStatus());
    ASSERT_EQ(store.usage().active_sector, 2u);
    ASSERT_EQ(store.Write(1, BytesOf("in sector 2")), base::OkStatus());
  }
  EXPECT_EQ(ReadAfterRestart(flash, 1).value(), BytesOf("in sector 2"));
  // Without its commit, sector 2 does not count: sector 1 (generation 2) holds the record.
  flash.FlipBits(2 * 256 + 16, 0x01);
  FlashNvStore store(flash);
  ASSERT_EQ(store.Mount(), base::OkStatus());
  EXPECT_EQ(store.usage().active_sector, 1u);
  EXPECT_EQ(store.usage().generation, 2u);
  EXPECT_EQ(ReadRecord(store, 1).value(), Pattern(60, 1));
  // The next compaction goes to sector 2 again (erasing it first) with generation 3.
  while (store.usage().active_sector == 1) ASSERT_EQ(store.Write(1, Pattern(60, 2)), base::OkStatus());
  EXPECT_EQ(store.usage().active_sector, 2u);
  EXPECT_EQ(store.usage().generation, 3u);
  EXPECT_EQ(ReadAfterRestart(flash, 1).value(), Pattern(60, 2));
  EXPECT_EQ(flash.violations(), 0);
}

TEST(FlashNvStore, ASectorWrittenWithAnotherProgramUnitIsNotOurs) {
  FakeFlash written(512, 2, 4);
  {
    FlashNvStore store(written);
    ASSERT_EQ(store.Mount(), base::OkStatus());
    ASSERT_EQ(store.Write(1, BytesOf("unit 4")), base::OkStatus());
  }
  FakeFlash other(512, 2, 8);
  other.SetContents(written.bytes());
  FlashNvStore store(other);
  ASSERT_EQ(store.Mount(), base::OkStatus());
  EXPECT_FALSE(store.usage().has_active);
  EXPECT_EQ(ReadRecord(store, 1).status(), base::NotFound());
  ASSERT_EQ(store.Write(1, BytesOf("unit 8")), base::OkStatus());
  EXPECT_EQ(ReadAfterRestart(other, 1).value(), BytesOf("unit 8"));
  EXPECT_EQ(other.violations(), 0);
}

TEST(FlashNvStore, ForeignContentsReadAsEmptyAndAreReplacedCleanly) {
  std::mt19937 random(7);
  for (int round = 0; round < 50; ++round) {
    FakeFlash flash(256, 2, 4);
    Bytes noise(512);
    for (std::uint8_t& byte : noise) byte = static_cast<std::uint8_t>(random());
    flash.SetContents(noise);
    FlashNvStore store(flash);
    ASSERT_EQ(store.Mount(), base::OkStatus());
    EXPECT_EQ(ReadRecord(store, 1).status(), base::NotFound());
    ASSERT_EQ(store.Write(1, BytesOf("mine")), base::OkStatus());
    EXPECT_EQ(ReadAfterRestart(flash, 1).value(), BytesOf("mine"));
    EXPECT_EQ(flash.violations(), 0);
  }
}

}  // namespace
}  // namespace hal
