// hal::NvStore on NOR flash (hal/flash.h): the card's records on a board, which has no file system.
//
// A log of records in one sector at a time. A change (a write, or an erase as a tombstone record) is
// appended to the active sector; the newest valid copy of each id is the record. A compaction writes
// the current records and the change into the next sector (in ring order, so the wear spreads over
// every sector of the flash) and commits that sector; the old one is left as it is and erased only when
// the ring comes back to it. A change compacts when it does not fit, and when it is the first since
// the start (or since a failed change): a cut at the start of a record header may have left the unit
// after the log torn yet reading 0xFF, and a torn unit must not be programmed again (hal/flash.h), so
// only units this session erased are ever programmed. Capacity is one sector; further sectors add
// endurance, not room.
//
// On-flash layout. U = flash.ProgramUnit(); A(n) = n rounded up to a multiple of U; all integers
// little-endian; padding and unused bytes are 0xFF (left erased or programmed as 0xFF).
//
//   Sector header, at offset 0 of a sector:
//     0  u32 magic 0x464E5049 ("IPNF")
//     4  u16 format 1
//     6  u16 U the sector was written with (a sector written with another unit is not ours)
//     8  u32 generation, stored inverted (~g): the sector with the highest generation is the active one
//    12  u32 CRC-32 of bytes 0..11
//   Sector commit at A(16): 4 bytes "LIVE", programmed after every record of a compaction is written.
//   Records from A(16) + A(4) on, one right after the other (each at a multiple of U); the log ends
//   at the first header that is 0xFF or does not check:
//     0  u16 tag: 0x4452 ("RD", data) or 0x4254 ("TB", tombstone: the id is erased)
//     2  u16 record id
//     4  u32 payload length n (0..kMaxRecordBytes; 0 in a tombstone)
//     8  u32 sequence number: 1, 2, ... along the sector's log (a compaction renumbers); the log ends
//          at a record whose number does not rise, and the newest valid copy of an id is its last one
//    12  u32 CRC-32 of the payload
//    16  u32 CRC-32 of bytes 0..15 (the header: its length can be trusted to find the next record)
//     A(20)          the payload, n bytes, padded to A(n)
//     A(20) + A(n)   the record commit: 4 bytes "CMIT", programmed last
//   A record takes RecordFootprint(n) = A(20) + A(n) + A(4) bytes (U = 4: 24 + A(n)).
//
// Commit rules (what a power cut leaves, docs/robustness.md "Power loss"):
// - A record counts only when its commit reads exactly "CMIT", its header CRC and its payload CRC
//   match. Its units are programmed in address order, commit last, so a cut anywhere before the commit
//   leaves the previous copy current; a cut in the commit itself leaves the old or the new copy.
// - A sector counts only when its header is valid and its commit reads exactly "LIVE". A compaction
//   erases the target sector, writes its header (generation + 1) and the records, then the commit: a
//   cut before the commit leaves the old sector active (the target is ignored), after it the new one.
//   The inverted generation means that a cut while erasing an old sector can only lower the
//   generation it seems to have (an erase only sets bits), never raise it above the active one's.
// - A cut can leave a unit torn (any mix of bits, counting as programmed even when it reads 0xFF,
//   hal/flash.h): the store programs only units of a sector it erased in the same session, in order,
//   and never after a failed program (the next change compacts).
// - A change that fails (the flash reported an error) may have left anything a cut there would leave;
//   the next call reads the flash again, so that the store always reads what a restart would.
//
// Device-path code: no heap; RAM is this object (about 50 bytes) and about 0.6 KiB of stack in the
// deepest path (a compaction copying a record and reading it back; 64-byte chunks, no sector buffer).
// Reads walk the active sector (no index in RAM), so Read and Write cost a scan of the used part of
// one sector, and a compaction O(records^2) header reads; the card changes its records only on
// configuration changes.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

#include "base/status.h"
#include "hal/flash.h"
#include "hal/nv_store.h"

namespace hal {

class FlashNvStore final : public NvStore {
 public:
  static constexpr std::uint32_t kSectorMagic = 0x464E5049;  // "IPNF"
  static constexpr std::uint16_t kFormatVersion = 1;
  static constexpr std::size_t kSectorHeaderBytes = 16;
  static constexpr std::size_t kRecordHeaderBytes = 20;
  static constexpr std::size_t kCommitBytes = 4;
  static constexpr std::uint16_t kDataTag = 0x4452;       // "RD"
  static constexpr std::uint16_t kTombstoneTag = 0x4254;  // "TB"
  // Program units the layout supports: powers of two up to this (NOR bytes, STM32 words and double
  // words, 256-bit flash words).
  static constexpr std::size_t kMaxProgramUnit = 32;

  // Uses every sector of `flash`. Nothing is read or written before Mount.
  explicit FlashNvStore(Flash& flash) : flash_(flash) {}
  FlashNvStore(const FlashNvStore&) = delete;
  FlashNvStore& operator=(const FlashNvStore&) = delete;

  // Scans the flash: the active sector is the committed one with the highest generation (none on a
  // blank or foreign flash: an empty store, which the first change formats). An interrupted compaction
  // is undone or finished by that choice alone: before its commit the old sector stays active and the
  // target is erased when next used; after it the new sector is active and the old one is left to the
  // ring. A record write cut short leaves at most a torn tail after the log, which the first change
  // (a compaction) leaves behind. Mount writes nothing (a start costs no wear and no erase time) and
  // may be called again at any time. A flash read error other than kDataLoss is returned (the store
  // is then not mounted): a part that does not answer is never taken for an empty one.
  // kInvalidArgument: a geometry the layout cannot use (fewer than 2 sectors, a program unit that is
  // not a power of two up to kMaxProgramUnit or does not divide the sector, a sector too small for an
  // empty record or larger than 1 GiB); the store then refuses every call with kFailedPrecondition.
  base::Status Mount();

  // hal::NvStore, once mounted (before: kFailedPrecondition).
  // Read: kNotFound (never written, or erased), kOutOfRange (`out` smaller than the record; nothing
  // copied), kDataLoss (every committed copy fails its CRC: damaged flash, not a power cut).
  // Write: kInvalidArgument (more than kMaxRecordBytes), kResourceExhausted (the records with this one
  // do not fit in a sector; nothing changes), kDataLoss (a program did not read back) or the flash's
  // error: the record is then the old or the new contents, as after a power cut at that point, and
  // Read tells which.
  // Erase: succeeds at once when the id is absent; otherwise writes a tombstone (or compacts), with
  // the errors of Write.
  base::Result<std::size_t> Read(NvRecordId id, std::span<std::uint8_t> out) override;
  base::Status Write(NvRecordId id, std::span<const std::uint8_t> data) override;
  base::Status Erase(NvRecordId id) override;

  // Bytes a record of `payload_bytes` takes in a sector, and the bytes of a sector before the first
  // record (header and commit), for program unit `unit`.
  static std::size_t RecordFootprint(std::size_t payload_bytes, std::size_t unit);
  static std::size_t SectorOverhead(std::size_t unit);

  // Where the store stands, for diagnostics and tests.
  struct Usage {
    bool has_active = false;     // false: nothing written yet (or nothing valid found)
    std::size_t active_sector = 0;
    std::uint32_t generation = 0;  // compactions so far, counting the first format as 1
    std::size_t append_offset = 0;  // in the active sector; SectorSize(): the next change compacts
                                    // (always so after Mount)
  };
  Usage usage() const { return Usage{has_active_, active_, generation_, append_at_}; }

 private:
  struct Change;
  struct RecordView;
  class SectorReader;

  std::size_t Align(std::size_t bytes) const { return (bytes + unit_ - 1) / unit_ * unit_; }
  std::size_t RecordsStart() const { return SectorOverhead(unit_); }
  std::size_t SectorBase(std::size_t sector) const { return sector * sector_size_; }
  SectorReader Active() const;

  // Finds the active sector and the end of its log (Mount without the geometry check).
  base::Status Scan();
  // kFailedPrecondition before Mount; scans again after a failed change.
  base::Status Ready();
  base::Status Apply(const Change& change);
  base::Status Append(const Change& change);
  bool Live(const SectorReader& reader, const RecordView& view, NvRecordId changed) const;
  base::Status Compact(const Change& change);
  // Programs record `change` with `sequence` at `offset` of `sector` and reads it back.
  base::Status ProgramRecord(std::size_t sector, std::size_t offset, const Change& change,
                             std::uint32_t sequence);
  // Copies the valid record `from` of the active sector to `to_offset` of `to_sector`, renumbered.
  base::Status CopyRecord(const RecordView& from, std::size_t to_sector, std::size_t to_offset,
                          std::uint32_t sequence);
  base::Status VerifyRecord(std::size_t sector, std::size_t offset, const RecordView& expected);
  base::Status ProgramPadded(std::size_t offset, std::span<const std::uint8_t> bytes);

  Flash& flash_;
  std::size_t sector_size_ = 0;
  std::size_t sector_count_ = 0;
  std::size_t unit_ = 1;
  bool mounted_ = false;
  bool rescan_needed_ = false;  // a change failed: what it left is read from the flash again
  bool has_active_ = false;
  std::size_t active_ = 0;
  std::uint32_t generation_ = 0;
  std::size_t used_end_ = 0;   // walks of the active sector stop here (0xFF or unusable beyond)
  std::size_t append_at_ = 0;  // where the next record goes; sector_size_: compact first
  std::uint32_t next_sequence_ = 1;
};

}  // namespace hal
