// Power loss at every step of every kind of change to a hal::FlashNvStore (docs/robustness.md "Power
// loss"): a record write, a tombstone, the first write on a blank part, a write and an erase that
// compact, and long runs of changes with repeated compactions. A step is each byte programmed and each
// sector erase (hal/test/fake_flash.h); the cut leaves the unit or sector being written in one of the
// mixes hal/flash.h allows (old bits, the new bits partly applied, a seeded random mix, all new), on
// parts with program units of 1 to 32 bytes and 2 or 3 sectors, and with torn units readable or
// answering ECC errors.
//
// After every cut, the card starts again (a new store, Mount) and must read, for every id, exactly
// the contents it had before the change, except the changed id, which may be the complete new contents
// (or absent after an erase); the next start must read the same; the same store object, powered again
// without a restart, must read the same too; and a further change through either must work and last,
// without ever breaking a flash rule (programming a unit twice, a torn unit, an unerased sector).
#include <gtest/gtest.h>

#include <cstdint>
#include <map>
#include <optional>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "fake_flash.h"
#include "hal/flash_nv_store.h"

namespace hal {
namespace {

using test::CutMix;
using test::FakeFlash;
using Bytes = std::vector<std::uint8_t>;
// The records a store holds; an absent id is not in the map.
using Contents = std::map<NvRecordId, Bytes>;

// A change: a write of `data`, or an erase when there is none.
struct Change {
  NvRecordId id = 0;
  std::optional<Bytes> data;
};

Contents Applied(Contents contents, const Change& change) {
  if (change.data) {
    contents[change.id] = *change.data;
  } else {
    contents.erase(change.id);
  }
  return contents;
}

base::Status Make(NvStore& store, const Change& change) {
  return change.data ? store.Write(change.id, *change.data) : store.Erase(change.id);
}

Bytes Pattern(std::size_t size, std::uint32_t seed) {
  Bytes bytes(size);
  for (std::size_t i = 0; i < size; ++i) bytes[i] = static_cast<std::uint8_t>(seed * 31 + i * 7 + (seed >> 8));
  return bytes;
}

std::string Describe(const Contents& contents) {
  std::ostringstream text;
  for (const auto& [id, bytes] : contents) text << id << ":" << bytes.size() << "B ";
  return text.str();
}

// Every id in `ids` as `store` reads it. Any status but kOk and kNotFound fails the test.
Contents ReadAll(NvStore& store, const std::set<NvRecordId>& ids) {
  Contents contents;
  for (NvRecordId id : ids) {
    Bytes buffer(kMaxRecordBytes);
    const base::Result<std::size_t> n = store.Read(id, buffer);
    if (n.status() == base::NotFound()) continue;
    EXPECT_TRUE(n.ok()) << "id " << id << ": " << base::StatusName(n.status());
    buffer.resize(n.ok() ? *n : 0);
    contents[id] = buffer;
  }
  return contents;
}

// What the card reads after a start on `flash`.
Contents ReadAfterStart(FakeFlash& flash, const std::set<NvRecordId>& ids) {
  FlashNvStore store(flash);
  EXPECT_EQ(store.Mount(), base::OkStatus());
  return ReadAll(store, ids);
}

struct Part {
  std::size_t sector_size;
  std::size_t sectors;
  std::size_t unit;
  CutMix mix;
  bool torn_unreadable;
};

std::string PartName(const ::testing::TestParamInfo<Part>& info) {
  static const char* const kMixes[] = {"OldBits", "PartlyNew", "RandomMix", "AllNew"};
  const Part& part = info.param;
  return std::to_string(part.sectors) + "x" + std::to_string(part.sector_size) + "_unit" +
         std::to_string(part.unit) + "_" + kMixes[static_cast<int>(part.mix)] +
         (part.torn_unreadable ? "_EccErrors" : "");
}

class FlashNvStorePowerCut : public ::testing::TestWithParam<Part> {
 protected:
  FakeFlash NewFlash() const {
    FakeFlash flash(GetParam().sector_size, GetParam().sectors, GetParam().unit);
    flash.set_torn_units_unreadable(GetParam().torn_unreadable);
    return flash;
  }

  // Makes `changes` one after the other in one session (a start, then the changes through one store)
  // on `flash`, which holds `contents`: once without a cut, which must store them all; then, from the
  // same start each time, once with power cut at each step they took. Power fails during change i:
  // the changes before it must have succeeded, change i must not report success, and what a start
  // reads afterwards must be the contents before change i or after it. Returns the cuts tried.
  std::uint64_t CheckSession(FakeFlash& flash, Contents& contents, const std::vector<Change>& changes) {
    const FakeFlash start = flash;
    std::vector<Contents> states = {contents};
    std::set<NvRecordId> ids = {0x7777};  // and one never written
    for (const auto& entry : contents) ids.insert(entry.first);
    for (const Change& change : changes) {
      states.push_back(Applied(states.back(), change));
      ids.insert(change.id);
    }

    std::vector<std::uint64_t> ends;  // steps done when each change is done, from the start
    {
      FlashNvStore store(flash);
      EXPECT_EQ(store.Mount(), base::OkStatus());
      const std::uint64_t first = flash.steps();
      for (std::size_t i = 0; i < changes.size(); ++i) {
        EXPECT_EQ(Make(store, changes[i]), base::OkStatus()) << "uncut change " << i;
        ends.push_back(flash.steps() - first);
        EXPECT_EQ(ReadAll(store, ids), states[i + 1]) << "uncut change " << i;
      }
      EXPECT_EQ(ReadAfterStart(flash, ids), states.back());
    }
    contents = states.back();

    for (std::uint64_t cut = 0; cut < ends.back(); ++cut) {
      std::size_t i = 0;
      while (ends[i] <= cut) ++i;
      const std::string where = "cut at step " + std::to_string(cut) + " of " + std::to_string(ends.back()) +
                                ", in change " + std::to_string(i) + " (id " + std::to_string(changes[i].id) +
                                ") from " + Describe(states[i]);
      FakeFlash cut_flash = start;
      FlashNvStore dying(cut_flash);
      EXPECT_EQ(dying.Mount(), base::OkStatus()) << where;
      cut_flash.CutPowerAtStep(cut_flash.steps() + cut, GetParam().mix, static_cast<std::uint32_t>(cut * 7919 + 13));
      for (std::size_t j = 0; j < i; ++j) EXPECT_EQ(Make(dying, changes[j]), base::OkStatus()) << where;
      EXPECT_NE(Make(dying, changes[i]), base::OkStatus()) << "a change power never finished reported success; " << where;
      EXPECT_FALSE(cut_flash.powered()) << where;
      cut_flash.PowerOn();
      const FakeFlash after_cut = cut_flash;

      // The card starts again.
      const Contents seen = ReadAfterStart(cut_flash, ids);
      EXPECT_TRUE(seen == states[i] || seen == states[i + 1])
          << where << ": read " << Describe(seen) << ", expected that or " << Describe(states[i + 1]);
      EXPECT_EQ(ReadAfterStart(cut_flash, ids), seen) << "a second start reads otherwise; " << where;
      FollowUp(cut_flash, nullptr, seen, changes[i].id, ids, where + ", after a start");

      // The same store, powered again without a start (as after a program the part reported failed).
      cut_flash = after_cut;
      EXPECT_EQ(ReadAll(dying, ids), seen) << "the store that failed reads otherwise; " << where;
      FollowUp(cut_flash, &dying, seen, changes[i].id, ids, where + ", same store");
      if (HasFailure()) break;  // one cut's report is enough
    }
    return ends.back();
  }

  // A further write of `id` (through `store`, or a newly started one) must work and last.
  void FollowUp(FakeFlash& flash, FlashNvStore* store, const Contents& seen, NvRecordId id,
                const std::set<NvRecordId>& ids, const std::string& where) {
    FlashNvStore started(flash);
    if (store == nullptr) {
      EXPECT_EQ(started.Mount(), base::OkStatus()) << where;
      store = &started;
    }
    const Change next{id, Bytes{0xC0, 0xFF, 0xEE}};
    EXPECT_EQ(Make(*store, next), base::OkStatus()) << "the change after the cut; " << where;
    EXPECT_EQ(ReadAll(*store, ids), Applied(seen, next)) << where;
    EXPECT_EQ(ReadAfterStart(flash, ids), Applied(seen, next)) << where;
    EXPECT_EQ(flash.violations(), 0) << "a flash rule was broken; " << where;
  }

  // Brings `flash` to `contents` with uncut changes.
  void Prepare(FakeFlash& flash, Contents& contents, const std::vector<Change>& changes) {
    FlashNvStore store(flash);
    ASSERT_EQ(store.Mount(), base::OkStatus());
    for (const Change& change : changes) {
      ASSERT_EQ(Make(store, change), base::OkStatus());
      contents = Applied(contents, change);
    }
  }

  std::uint32_t Generation(FakeFlash& flash) {
    FlashNvStore store(flash);
    EXPECT_EQ(store.Mount(), base::OkStatus());
    return store.usage().generation;
  }

  std::size_t Footprint(std::size_t payload) const { return FlashNvStore::RecordFootprint(payload, GetParam().unit); }

  // Sized so that about five of these fill a sector.
  std::size_t RecordSize() const {
    const std::size_t room = GetParam().sector_size - FlashNvStore::SectorOverhead(GetParam().unit);
    return room / 5 > Footprint(0) ? room / 5 - Footprint(0) : 1;
  }
};

TEST_P(FlashNvStorePowerCut, FirstWriteOnABlankPart) {
  FakeFlash flash = NewFlash();
  Contents contents;
  EXPECT_GT(CheckSession(flash, contents, {{1, Pattern(RecordSize(), 1)}}), 0u);
  EXPECT_EQ(Generation(flash), 1u);
}

// The first change of a session compacts; the next ones append: records, a new id, a tombstone, an
// empty record.
TEST_P(FlashNvStorePowerCut, RecordWritesAndATombstoneAppended) {
  FakeFlash flash = NewFlash();
  Contents contents;
  Prepare(flash, contents, {{1, Pattern(3, 1)}, {2, Pattern(RecordSize(), 2)}, {3, Bytes{}}});
  const std::uint32_t generation = Generation(flash);
  CheckSession(flash, contents,
               {{2, Pattern(RecordSize(), 3)},      // compacts (the first change since the start)
                {2, Pattern(RecordSize() / 2, 4)},  // shorter
                {4, Pattern(1, 5)},                 // a new id
                {3, std::nullopt},                  // a tombstone
                {1, Bytes{}}});                     // an empty record
  EXPECT_EQ(Generation(flash), generation + 1) << "only the first change was meant to compact";
}

TEST_P(FlashNvStorePowerCut, WriteThatCompactsAFullSector) {
  FakeFlash flash = NewFlash();
  Contents contents;
  Prepare(flash, contents, {{1, Pattern(RecordSize(), 1)}, {2, Pattern(RecordSize(), 2)}});
  const std::uint32_t generation = Generation(flash);
  // The first write compacts; then record 2 is overwritten until the sector is full; the last compacts.
  std::vector<Change> changes = {{2, Pattern(RecordSize(), 3)}};
  std::size_t used = FlashNvStore::SectorOverhead(GetParam().unit) + 2 * Footprint(RecordSize());
  for (std::uint32_t i = 4; used + Footprint(RecordSize()) <= GetParam().sector_size; ++i) {
    changes.push_back({2, Pattern(RecordSize(), i)});
    used += Footprint(RecordSize());
  }
  changes.push_back({2, Pattern(RecordSize(), 99)});
  CheckSession(flash, contents, changes);
  EXPECT_EQ(Generation(flash), generation + 2) << "the first and the last change were meant to compact";
}

TEST_P(FlashNvStorePowerCut, EraseThatCompactsAFullSector) {
  FakeFlash flash = NewFlash();
  Contents contents;
  Prepare(flash, contents, {{1, Pattern(RecordSize(), 1)}, {2, Pattern(RecordSize(), 2)}});
  const std::uint32_t generation = Generation(flash);
  // Empty records take what a tombstone takes: once one no longer fits, neither does the tombstone.
  std::vector<Change> changes = {{3, Bytes{}}};
  std::size_t used = FlashNvStore::SectorOverhead(GetParam().unit) + 2 * Footprint(RecordSize()) + Footprint(0);
  while (used + Footprint(0) <= GetParam().sector_size) {
    changes.push_back({3, Bytes{}});
    used += Footprint(0);
  }
  changes.push_back({1, std::nullopt});
  CheckSession(flash, contents, changes);
  EXPECT_EQ(Generation(flash), generation + 2) << "the first change and the erase were meant to compact";
}

// Sessions of random changes of three ids (sizes up to a fifth of the sector, erases among them), every
// one cut at every step: appends, compactions round the ring, compactions after a torn tail.
TEST_P(FlashNvStorePowerCut, RepeatedCompactions) {
  FakeFlash flash = NewFlash();
  Contents contents;
  std::mt19937 random(static_cast<std::uint32_t>(GetParam().unit * 100 + GetParam().sectors));
  for (std::uint32_t session = 0; session < 4 && !HasFailure(); ++session) {
    std::vector<Change> changes;
    for (std::uint32_t i = 0; i < 6; ++i) {
      const auto id = static_cast<NvRecordId>(1 + random() % 3);
      if (random() % 6 == 0) {
        changes.push_back({id, std::nullopt});
      } else {
        changes.push_back({id, Pattern(random() % (RecordSize() + 1), session * 10 + i)});
      }
    }
    CheckSession(flash, contents, changes);
  }
  EXPECT_GE(Generation(flash), 5u) << "one compaction per session start, and more for full sectors";
}

// Two cuts in a row: the first write of a session cut short (at 16 steps spread over it, the first and
// the last among them), then the session after it (whose first change compacts a sector that may hold
// a torn tail or a torn compaction) cut at every step.
TEST_P(FlashNvStorePowerCut, CutsInTwoSessionsInARow) {
  FakeFlash flash = NewFlash();
  Contents contents;
  Prepare(flash, contents, {{1, Pattern(RecordSize(), 1)}, {2, Pattern(RecordSize(), 2)}});
  const std::set<NvRecordId> ids = {1, 2, 3};
  const Change first{2, Pattern(RecordSize(), 3)};
  std::uint64_t first_steps = 0;
  {
    FakeFlash probe = flash;
    FlashNvStore store(probe);
    ASSERT_EQ(store.Mount(), base::OkStatus());
    ASSERT_EQ(Make(store, first), base::OkStatus());
    first_steps = probe.steps() - flash.steps();
  }
  std::set<std::uint64_t> cuts;
  for (std::uint64_t k = 0; k < 16; ++k) cuts.insert(k * (first_steps - 1) / 15);
  for (const std::uint64_t cut : cuts) {
    FakeFlash cut_flash = flash;
    {
      FlashNvStore store(cut_flash);
      ASSERT_EQ(store.Mount(), base::OkStatus());
      cut_flash.CutPowerAtStep(cut_flash.steps() + cut, GetParam().mix, static_cast<std::uint32_t>(cut));
      ASSERT_NE(Make(store, first), base::OkStatus());
      cut_flash.PowerOn();
    }
    Contents state = ReadAfterStart(cut_flash, ids);
    ASSERT_TRUE(state == contents || state == Applied(contents, first)) << "first cut at step " << cut;
    CheckSession(cut_flash, state, {{3, Pattern(RecordSize(), 4)}, {1, std::nullopt}});
    ASSERT_FALSE(HasFailure()) << "first cut at step " << cut;
  }
}

INSTANTIATE_TEST_SUITE_P(
    Parts, FlashNvStorePowerCut,
    ::testing::Values(Part{256, 2, 4, CutMix::kOld, false}, Part{256, 2, 4, CutMix::kPartlyNew, false},
                      Part{256, 2, 4, CutMix::kRandom, false}, Part{256, 2, 4, CutMix::kNew, false},
                      Part{256, 2, 4, CutMix::kRandom, true}, Part{256, 3, 1, CutMix::kPartlyNew, false},
                      Part{256, 3, 1, CutMix::kRandom, false}, Part{256, 2, 1, CutMix::kOld, true},
                      Part{512, 2, 8, CutMix::kRandom, false}, Part{512, 3, 8, CutMix::kPartlyNew, true},
                      Part{512, 2, 8, CutMix::kNew, false}, Part{1024, 2, 32, CutMix::kRandom, false},
                      Part{1024, 3, 32, CutMix::kOld, true}),
    PartName);

}  // namespace
}  // namespace hal
