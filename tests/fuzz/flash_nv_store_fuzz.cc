// libFuzzer target for hal::FlashNvStore (hal/flash_nv_store.h) on the fake flash of the unit tests
// (hal/test/fake_flash.h): it mounts arbitrary flash contents, then runs a script of changes, reads,
// restarts and power cuts from the input.
//
// Input: [geometry] [contents length u16 LE] [contents] [script...]
//   geometry: bits 0-2 program unit (1, 2, 4, 8, 16, 32, 3, 64: the last two unusable), bits 3-4
//   sector count - 1 (1..4: one sector is unusable), bits 5-6 sector size (128, 256, 512, 1024 bytes);
//   contents: the flash from offset 0 (the rest 0xFF); units not all 0xFF count as programmed.
//   Each script step is 3 bytes: operation, id (0..7, so the ids collide), argument; at most 48 steps
//   (a compaction walks its sector once per record: long scripts on small sectors only cost time).
//
// Oracles: the fake flash never sees a call its contract forbids (a read past the end, a misaligned or
// repeated program, an erase of a sector that does not exist), and sanitizers see no access outside the
// store's buffers or the input; Mount is kInvalidArgument exactly for an unusable geometry; a record the
// script wrote reads back exactly (before and after restarts, through compactions), an erased one is
// kNotFound, a too-small buffer is kOutOfRange with nothing copied; a record that was already on the
// flash reads within the caller's buffer with a length of at most kMaxRecordBytes; a write is refused
// only as too large (kInvalidArgument, over kMaxRecordBytes) or as not fitting (kResourceExhausted,
// nothing changed); after a power cut in a change the record is the old or the new contents.
#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "fake_flash.h"
#include "hal/flash_nv_store.h"

namespace {

using Bytes = std::vector<std::uint8_t>;
using hal::FlashNvStore;
using hal::test::CutMix;
using hal::test::FakeFlash;

void Require(bool condition) {
  if (!condition) __builtin_trap();
}

constexpr std::size_t kIds = 8;
constexpr std::size_t kMaxSteps = 48;

// What the script knows of each id: nothing yet (foreign contents), or exactly what it holds.
struct Known {
  bool known = false;
  std::optional<Bytes> data;  // nullopt: absent
};

Bytes Payload(std::size_t length, std::uint8_t seed) {
  Bytes bytes(length);
  for (std::size_t i = 0; i < length; ++i) bytes[i] = static_cast<std::uint8_t>(seed + i * 13);
  return bytes;
}

void CheckRead(hal::NvStore& store, hal::NvRecordId id, const Known& known, std::size_t room) {
  std::vector<std::uint8_t> out(room + 8, 0xA5);
  const base::Result<std::size_t> n = store.Read(id, std::span<std::uint8_t>(out).first(room));
  for (std::size_t i = room; i < out.size(); ++i) Require(out[i] == 0xA5);  // nothing past the buffer
  if (!known.known) {
    Require(!n.ok() || (*n <= room && *n <= hal::kMaxRecordBytes));
    const base::StatusCode code = n.status().code();
    Require(n.ok() || code == base::StatusCode::kNotFound || code == base::StatusCode::kOutOfRange ||
            code == base::StatusCode::kDataLoss);
    return;
  }
  if (!known.data) {
    Require(n.status() == base::NotFound());
  } else if (known.data->size() > room) {
    Require(n.status() == base::OutOfRange());
    Require(std::all_of(out.begin(), out.end(), [](std::uint8_t b) { return b == 0xA5; }));
  } else {
    Require(n.ok() && *n == known.data->size());
    Require(std::equal(known.data->begin(), known.data->end(), out.begin()));
  }
}

class Run {
 public:
  Run(FakeFlash& flash, bool usable) : flash_(flash), usable_(usable) {}

  // A start: a new store on the flash, mounted.
  bool Start() {
    store_.emplace(flash_);
    const base::Status mounted = store_->Mount();
    Require(mounted.ok() == usable_);
    Require(usable_ || mounted == base::InvalidArgument());
    return mounted.ok();
  }

  void Step(std::uint8_t operation, std::uint8_t id_byte, std::uint8_t argument) {
    const auto id = static_cast<hal::NvRecordId>(id_byte % kIds);
    switch (operation % 6) {
      case 0:
      case 1: Write(id, Payload(std::size_t{argument} * 5, id_byte)); break;  // 0..1275 bytes
      case 2: Erase(id); break;
      case 3: CheckRead(*store_, id, known_[id], std::size_t{argument} * 5); break;
      case 4: Start(); break;
      case 5: CutDuringWrite(id, argument); break;
    }
    Require(flash_.violations() == 0);
  }

  void CheckAll() {
    for (std::size_t id = 0; id < kIds; ++id) CheckRead(*store_, static_cast<hal::NvRecordId>(id), known_[id], hal::kMaxRecordBytes);
  }

 private:
  void Write(hal::NvRecordId id, const Bytes& data) {
    const base::Status status = store_->Write(id, data);
    if (data.size() > hal::kMaxRecordBytes) {
      Require(status == base::InvalidArgument());
    } else if (status.ok()) {
      known_[id] = Known{true, data};
    } else {
      Require(status == base::ResourceExhausted());
    }
  }

  void Erase(hal::NvRecordId id) {
    const base::Status status = store_->Erase(id);
    if (status.ok()) {
      known_[id] = Known{true, std::nullopt};
    } else {
      Require(status == base::ResourceExhausted());
    }
  }

  // Power fails after `argument` * 3 steps of a write of id; then a start.
  void CutDuringWrite(hal::NvRecordId id, std::uint8_t argument) {
    const Known old = known_[id];
    const Bytes data = Payload(argument % 64, argument);
    flash_.CutPowerAtStep(flash_.steps() + std::uint64_t{argument} * 3, static_cast<CutMix>(argument % 4), argument);
    const base::Status status = store_->Write(id, data);
    const bool cut = !flash_.powered();
    flash_.PowerOn();
    Start();
    if (status.ok()) {
      known_[id] = Known{true, data};
    } else if (!cut) {
      Require(status == base::ResourceExhausted());
    } else {
      // The old or the new contents; which one, a read says.
      std::array<std::uint8_t, 64> out{};
      const base::Result<std::size_t> n = store_->Read(id, out);
      const bool is_new = n.ok() && *n == data.size() && std::equal(data.begin(), data.end(), out.begin());
      if (is_new) {
        known_[id] = Known{true, data};
      } else {
        CheckRead(*store_, id, old, hal::kMaxRecordBytes);
      }
    }
  }

  FakeFlash& flash_;
  bool usable_;
  std::optional<FlashNvStore> store_;
  std::array<Known, kIds> known_{};
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 3) return 0;
  static constexpr std::size_t kUnits[] = {1, 2, 4, 8, 16, 32, 3, 64};
  static constexpr std::size_t kSectorSizes[] = {128, 256, 512, 1024};
  const std::size_t unit = kUnits[data[0] & 0x07];
  const std::size_t sectors = 1 + ((data[0] >> 3) & 0x03);
  const std::size_t sector_size = kSectorSizes[(data[0] >> 5) & 0x03];
  const bool usable = unit <= FlashNvStore::kMaxProgramUnit && unit != 3 && sectors >= 2 &&
                      sector_size >= FlashNvStore::SectorOverhead(unit) + FlashNvStore::RecordFootprint(0, unit);
  const std::size_t contents = std::min<std::size_t>(data[1] | (data[2] << 8), size - 3);

  // A program unit of 3 does not divide the sizes: the fake gets one that does (the store refuses it).
  FakeFlash flash(sector_size - sector_size % unit, sectors, unit);
  flash.SetContents(std::span<const std::uint8_t>(data + 3, contents));
  Run run(flash, usable);
  if (!run.Start()) return 0;
  run.CheckAll();
  const std::size_t end = std::min(size, 3 + contents + 3 * kMaxSteps);
  for (std::size_t at = 3 + contents; at + 3 <= end; at += 3) run.Step(data[at], data[at + 1], data[at + 2]);
  run.CheckAll();
  run.Start();
  run.CheckAll();
  return 0;
}
