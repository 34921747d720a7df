#include "hal/flash_nv_store.h"

#include <algorithm>
#include <array>
#include <limits>

#include "base/crc32.h"

namespace hal {
namespace {

constexpr std::array<std::uint8_t, FlashNvStore::kCommitBytes> kRecordCommit = {'C', 'M', 'I', 'T'};
constexpr std::array<std::uint8_t, FlashNvStore::kCommitBytes> kSectorCommit = {'L', 'I', 'V', 'E'};
// Generations 1..kMaxGeneration are valid: an erased field (~0xFFFFFFFF = 0) is none, and the last one
// is kept free so that generation + 1 is always representable.
constexpr std::uint32_t kMaxGeneration = 0xFFFFFFFEU;
constexpr std::size_t kMaxSectorBytes = std::size_t{1} << 30;
// Flash is read and copied in chunks of this size: a multiple of every supported program unit.
constexpr std::size_t kChunkBytes = 64;
static_assert(kChunkBytes % FlashNvStore::kMaxProgramUnit == 0);

std::size_t AlignTo(std::size_t bytes, std::size_t unit) { return (bytes + unit - 1) / unit * unit; }

void PutLe16(std::uint8_t* out, std::uint16_t value) {
  out[0] = static_cast<std::uint8_t>(value);
  out[1] = static_cast<std::uint8_t>(value >> 8);
}
void PutLe32(std::uint8_t* out, std::uint32_t value) {
  for (int i = 0; i < 4; ++i) out[i] = static_cast<std::uint8_t>(value >> (8 * i));
}
std::uint16_t GetLe16(const std::uint8_t* in) { return static_cast<std::uint16_t>(in[0] | (in[1] << 8)); }
std::uint32_t GetLe32(const std::uint8_t* in) {
  std::uint32_t value = 0;
  for (int i = 0; i < 4; ++i) value |= static_cast<std::uint32_t>(in[i]) << (8 * i);
  return value;
}

using SectorHeaderBytes = std::array<std::uint8_t, FlashNvStore::kSectorHeaderBytes>;
using RecordHeaderBytes = std::array<std::uint8_t, FlashNvStore::kRecordHeaderBytes>;

SectorHeaderBytes EncodeSectorHeader(std::size_t unit, std::uint32_t generation) {
  SectorHeaderBytes bytes{};
  PutLe32(&bytes[0], FlashNvStore::kSectorMagic);
  PutLe16(&bytes[4], FlashNvStore::kFormatVersion);
  PutLe16(&bytes[6], static_cast<std::uint16_t>(unit));
  PutLe32(&bytes[8], ~generation);
  PutLe32(&bytes[12], base::Crc32(std::span<const std::uint8_t>(bytes).first(12)));
  return bytes;
}

}  // namespace

// A change to apply: a record's new contents, or its erasure (a tombstone, no data).
struct FlashNvStore::Change {
  NvRecordId id = 0;
  std::uint16_t tag = kDataTag;
  std::span<const std::uint8_t> data;
};

// A record header as found in a sector, with its place.
struct FlashNvStore::RecordView {
  std::size_t offset = 0;  // of the header, within the sector
  std::uint16_t tag = 0;
  NvRecordId id = 0;
  std::uint32_t length = 0;
  std::uint32_t sequence = 0;
  std::uint32_t payload_crc = 0;
  std::size_t footprint = 0;

  bool IsTombstone() const { return tag == kTombstoneTag; }
};

namespace {

RecordHeaderBytes EncodeRecordHeader(std::uint16_t tag, NvRecordId id, std::uint32_t length,
                                     std::uint32_t sequence, std::uint32_t payload_crc) {
  RecordHeaderBytes bytes{};
  PutLe16(&bytes[0], tag);
  PutLe16(&bytes[2], id);
  PutLe32(&bytes[4], length);
  PutLe32(&bytes[8], sequence);
  PutLe32(&bytes[12], payload_crc);
  PutLe32(&bytes[16], base::Crc32(std::span<const std::uint8_t>(bytes).first(16)));
  return bytes;
}

}  // namespace

// Reads the records of one sector; every read stays below a limit the caller gives. A unit the flash
// reports as damaged (kDataLoss: an ECC error, a torn unit) reads as garbage, never as data; any other
// read error is kept (failure()) and stops every walk, so that a flash that does not answer is never
// taken for an empty one.
class FlashNvStore::SectorReader {
 public:
  SectorReader(Flash& flash, std::size_t base, std::size_t unit) : flash_(flash), base_(base), unit_(unit) {}

  enum class Step { kRecord, kEnd, kFailed };

  // The first read error other than kDataLoss, or OK.
  base::Status failure() const { return failure_; }

  // Reads the record header at `offset`, which follows a record with sequence number `after` (0 at the
  // start of the log). kRecord: `view` is the record and `offset` is past it. kEnd: the log ends at
  // `offset`: 0xFF (nothing written), or a header that does not check (a torn write's, or a foreign
  // one) or whose sequence number does not rise, or no room for one before `limit`. kFailed: the flash
  // did not answer.
  Step Next(std::size_t& offset, std::size_t limit, std::uint32_t after, RecordView& view) const {
    if (offset > limit || limit - offset < kRecordHeaderBytes) return Step::kEnd;
    RecordHeaderBytes bytes{};
    if (!ReadAt(offset, bytes)) return failure_.ok() ? Step::kEnd : Step::kFailed;
    if (!Decode(bytes, offset, limit, view) || view.sequence <= after) return Step::kEnd;
    offset += view.footprint;
    return Step::kRecord;
  }

  // Visits every record from `start` (following a record with sequence number `after`) to `limit`, in
  // log order, until `visit` returns false or the log ends.
  template <typename Visit>
  void ForEach(std::size_t start, std::uint32_t after, std::size_t limit, Visit&& visit) const {
    std::size_t offset = start;
    RecordView view;
    while (Next(offset, limit, after, view) == Step::kRecord) {
      if (!visit(view)) return;
      after = view.sequence;
    }
  }

  bool Committed(const RecordView& view) const {
    std::array<std::uint8_t, kCommitBytes> commit{};
    const std::size_t at = view.offset + AlignTo(kRecordHeaderBytes, unit_) + AlignTo(view.length, unit_);
    return ReadAt(at, commit) && commit == kRecordCommit;
  }

  bool PayloadValid(const RecordView& view) const {
    base::Crc32Builder crc;
    std::array<std::uint8_t, kChunkBytes> chunk{};
    const std::size_t start = view.offset + AlignTo(kRecordHeaderBytes, unit_);
    for (std::size_t done = 0; done < view.length;) {
      const std::size_t n = std::min<std::size_t>(kChunkBytes, view.length - done);
      const std::span<std::uint8_t> piece = std::span<std::uint8_t>(chunk).first(n);
      if (!ReadAt(start + done, piece)) return false;
      crc.Add(piece);
      done += n;
    }
    return crc.value() == view.payload_crc;
  }

  bool Valid(const RecordView& view) const { return Committed(view) && PayloadValid(view); }

  // Copies the payload of `view` into `out` (at least view.length bytes) and checks it again.
  base::Status ReadPayload(const RecordView& view, std::span<std::uint8_t> out) const {
    const std::span<std::uint8_t> payload = out.first(view.length);
    const std::size_t start = view.offset + AlignTo(kRecordHeaderBytes, unit_);
    if (!ReadAt(start, payload)) return failure_.ok() ? base::DataLoss() : failure_;
    if (base::Crc32(payload) != view.payload_crc) return base::DataLoss();
    return base::OkStatus();
  }

  // Reads `bytes.size()` bytes of the payload region of `view` from `from` on (0xFF past the payload).
  bool ReadPayloadChunk(const RecordView& view, std::size_t from, std::span<std::uint8_t> bytes) const {
    std::fill(bytes.begin(), bytes.end(), std::uint8_t{0xFF});
    if (from >= view.length) return true;
    const std::size_t n = std::min<std::size_t>(bytes.size(), view.length - from);
    const std::size_t start = view.offset + AlignTo(kRecordHeaderBytes, unit_);
    return ReadAt(start + from, bytes.first(n));
  }

  // The generation of this sector when its header is valid and committed; 0 otherwise.
  std::uint32_t CommittedGeneration() const {
    SectorHeaderBytes header{};
    if (!ReadAt(0, header)) return 0;
    const std::uint32_t generation = ~GetLe32(&header[8]);
    if (header != EncodeSectorHeader(unit_, generation)) return 0;  // magic, format, unit and CRC
    if (generation == 0 || generation > kMaxGeneration) return 0;
    std::array<std::uint8_t, kCommitBytes> commit{};
    if (!ReadAt(AlignTo(kSectorHeaderBytes, unit_), commit)) return 0;
    return commit == kSectorCommit ? generation : 0;
  }

 private:
  bool ReadAt(std::size_t offset, std::span<std::uint8_t> out) const {
    const base::Status status = flash_.Read(base_ + offset, out);
    if (!status.ok() && status != base::DataLoss() && failure_.ok()) failure_ = status;
    return status.ok();
  }

  bool Decode(const RecordHeaderBytes& bytes, std::size_t offset, std::size_t limit, RecordView& view) const {
    view.offset = offset;
    view.tag = GetLe16(&bytes[0]);
    view.id = GetLe16(&bytes[2]);
    view.length = GetLe32(&bytes[4]);
    view.sequence = GetLe32(&bytes[8]);
    view.payload_crc = GetLe32(&bytes[12]);
    if (view.tag != kDataTag && view.tag != kTombstoneTag) return false;
    if (GetLe32(&bytes[16]) != base::Crc32(std::span<const std::uint8_t>(bytes).first(16))) return false;
    if (view.length > kMaxRecordBytes || (view.IsTombstone() && view.length != 0)) return false;
    view.footprint = RecordFootprint(view.length, unit_);
    return view.footprint <= limit - offset;
  }

  Flash& flash_;
  std::size_t base_;
  std::size_t unit_;
  mutable base::Status failure_;
};

std::size_t FlashNvStore::RecordFootprint(std::size_t payload_bytes, std::size_t unit) {
  return AlignTo(kRecordHeaderBytes, unit) + AlignTo(payload_bytes, unit) + AlignTo(kCommitBytes, unit);
}

std::size_t FlashNvStore::SectorOverhead(std::size_t unit) {
  return AlignTo(kSectorHeaderBytes, unit) + AlignTo(kCommitBytes, unit);
}

FlashNvStore::SectorReader FlashNvStore::Active() const {
  return SectorReader(flash_, SectorBase(active_), unit_);
}

base::Status FlashNvStore::Mount() {
  mounted_ = false;
  sector_size_ = flash_.SectorSize();
  sector_count_ = flash_.SectorCount();
  unit_ = flash_.ProgramUnit();
  const bool unit_ok = unit_ != 0 && (unit_ & (unit_ - 1)) == 0 && unit_ <= kMaxProgramUnit;
  if (!unit_ok || sector_count_ < 2 || sector_size_ % unit_ != 0 || sector_size_ > kMaxSectorBytes ||
      sector_size_ < SectorOverhead(unit_) + RecordFootprint(0, unit_) ||
      sector_count_ > std::numeric_limits<std::size_t>::max() / sector_size_) {
    unit_ = 1;
    return base::InvalidArgument();
  }
  const base::Status scanned = Scan();
  mounted_ = scanned.ok();
  rescan_needed_ = false;
  return scanned;
}

base::Status FlashNvStore::Scan() {
  has_active_ = false;
  generation_ = 0;
  for (std::size_t sector = 0; sector < sector_count_; ++sector) {
    const SectorReader reader(flash_, SectorBase(sector), unit_);
    const std::uint32_t generation = reader.CommittedGeneration();
    if (!reader.failure().ok()) return reader.failure();
    if (generation > generation_) {
      generation_ = generation;
      active_ = sector;
      has_active_ = true;
    }
  }
  next_sequence_ = 1;
  used_end_ = append_at_ = sector_size_;
  if (!has_active_) return base::OkStatus();  // the first change formats a sector (a compaction)

  // The end of the log, where reads stop. Nothing is appended after it in this session: the unit there
  // may be torn yet read 0xFF (a cut at the start of a header), so the first change compacts into a
  // sector erased for it.
  const SectorReader reader = Active();
  std::size_t offset = RecordsStart();
  RecordView view;
  SectorReader::Step step = SectorReader::Step::kRecord;
  while (step == SectorReader::Step::kRecord) step = reader.Next(offset, sector_size_, view.sequence, view);
  if (step == SectorReader::Step::kFailed) return reader.failure();
  used_end_ = offset;
  return base::OkStatus();
}

base::Status FlashNvStore::Ready() {
  if (!mounted_) return base::FailedPrecondition();
  if (!rescan_needed_) return base::OkStatus();
  const base::Status scanned = Scan();
  rescan_needed_ = !scanned.ok();
  return scanned;
}

base::Result<std::size_t> FlashNvStore::Read(NvRecordId id, std::span<std::uint8_t> out) {
  const base::Status ready = Ready();
  if (!ready.ok()) return ready;
  if (!has_active_) return base::NotFound();
  const SectorReader reader = Active();
  RecordView best;
  bool found = false;
  bool damaged = false;
  // The newest valid copy: the last one in the log (sequence numbers rise along it).
  reader.ForEach(RecordsStart(), 0, used_end_, [&](const RecordView& view) {
    if (view.id != id || !reader.Committed(view)) return true;
    if (!reader.PayloadValid(view)) {
      damaged = true;
      return true;
    }
    best = view;
    found = true;
    return true;
  });
  if (!reader.failure().ok()) return reader.failure();
  if (!found) return damaged ? base::DataLoss() : base::NotFound();
  if (best.IsTombstone()) return base::NotFound();
  if (best.length > out.size()) return base::OutOfRange();
  const base::Status read = reader.ReadPayload(best, out);
  if (!read.ok()) return read;
  return std::size_t{best.length};
}

base::Status FlashNvStore::Write(NvRecordId id, std::span<const std::uint8_t> data) {
  const base::Status ready = Ready();
  if (!ready.ok()) return ready;
  if (data.size() > kMaxRecordBytes) return base::InvalidArgument();
  return Apply(Change{id, kDataTag, data});
}

base::Status FlashNvStore::Erase(NvRecordId id) {
  // Read with no room tells absent (kNotFound) from present (kOutOfRange, or kOk when empty) and
  // damaged (kDataLoss: erased all the same).
  const base::Status current = Read(id, {}).status();
  if (current == base::NotFound()) return base::OkStatus();
  if (current != base::OkStatus() && current != base::OutOfRange() && current != base::DataLoss()) {
    return current;
  }
  return Apply(Change{id, kTombstoneTag, {}});
}

base::Status FlashNvStore::Apply(const Change& change) {
  const std::size_t footprint = RecordFootprint(change.data.size(), unit_);
  if (footprint > sector_size_ - RecordsStart()) return base::ResourceExhausted();
  const bool fits = has_active_ && footprint <= sector_size_ - append_at_;
  const base::Status status = fits ? Append(change) : Compact(change);
  // A change that failed may have left anything from nothing to a committed record or sector (a
  // program the part reported as failed may still have landed): the next call reads the flash again.
  if (!status.ok() && status != base::ResourceExhausted()) rescan_needed_ = true;
  return status;
}

base::Status FlashNvStore::Append(const Change& change) {
  const std::size_t offset = append_at_;
  const std::size_t end = offset + RecordFootprint(change.data.size(), unit_);
  const base::Status status = ProgramRecord(active_, offset, change, next_sequence_);
  if (!status.ok()) return status;
  used_end_ = append_at_ = end;
  if (++next_sequence_ == 0) append_at_ = sector_size_;  // renumbered by the next compaction
  return base::OkStatus();
}

// A record of the active sector moves on at a compaction when it is the newest valid copy of its id
// (no valid copy follows it in the log), holds data, and is not the one being changed.
bool FlashNvStore::Live(const SectorReader& reader, const RecordView& view, NvRecordId changed) const {
  if (view.IsTombstone() || view.id == changed || !reader.Valid(view)) return false;
  bool newest = true;
  reader.ForEach(view.offset + view.footprint, view.sequence, used_end_, [&](const RecordView& later) {
    if (later.id == view.id && reader.Valid(later)) newest = false;
    return newest;
  });
  return newest;
}

base::Status FlashNvStore::Compact(const Change& change) {
  if (generation_ >= kMaxGeneration) return base::ResourceExhausted();  // 4e9 compactions: never
  const std::size_t change_bytes = change.tag == kDataTag ? RecordFootprint(change.data.size(), unit_) : 0;
  const SectorReader reader = Active();
  std::size_t needed = RecordsStart() + change_bytes;
  if (has_active_) {
    reader.ForEach(RecordsStart(), 0, used_end_, [&](const RecordView& view) {
      if (Live(reader, view, change.id)) needed += view.footprint;
      return true;
    });
  }
  if (!reader.failure().ok()) return reader.failure();  // nothing written yet
  if (needed > sector_size_) return base::ResourceExhausted();

  const std::size_t target = has_active_ ? (active_ + 1) % sector_count_ : 0;
  const std::uint32_t generation = generation_ + 1;
  base::Status status = flash_.Erase(target);
  if (status.ok()) status = ProgramPadded(SectorBase(target), EncodeSectorHeader(unit_, generation));
  std::size_t offset = RecordsStart();
  std::uint32_t sequence = 1;
  if (status.ok() && has_active_) {
    reader.ForEach(RecordsStart(), 0, used_end_, [&](const RecordView& view) {
      if (!Live(reader, view, change.id)) return true;
      // The records counted above, unless the flash reads otherwise now.
      status = view.footprint <= sector_size_ - offset ? CopyRecord(view, target, offset, sequence++)
                                                      : base::DataLoss();
      offset += view.footprint;
      return status.ok();
    });
    if (status.ok() && !reader.failure().ok()) status = reader.failure();
  }
  if (status.ok() && change.tag == kDataTag) {
    status = change_bytes <= sector_size_ - offset ? ProgramRecord(target, offset, change, sequence++)
                                                   : base::DataLoss();
    offset += change_bytes;
  }
  if (status.ok()) {
    status = ProgramPadded(SectorBase(target) + AlignTo(kSectorHeaderBytes, unit_), kSectorCommit);
  }
  if (status.ok()) {
    const SectorReader committed(flash_, SectorBase(target), unit_);
    if (committed.CommittedGeneration() != generation) {
      status = committed.failure().ok() ? base::DataLoss() : committed.failure();
    }
  }
  if (!status.ok()) return status;  // not committed (as far as we know): the old sector stays active

  has_active_ = true;
  active_ = target;
  generation_ = generation;
  used_end_ = append_at_ = offset;
  next_sequence_ = sequence;
  return base::OkStatus();
}

// Reads back the record just written at `offset` of `sector`: a program the part did not report as
// failed may still not hold. It must be a valid record with the tag, id, length and sequence expected.
base::Status FlashNvStore::VerifyRecord(std::size_t sector, std::size_t offset, const RecordView& expected) {
  const SectorReader reader(flash_, SectorBase(sector), unit_);
  std::size_t at = offset;
  RecordView view;
  const bool back = reader.Next(at, offset + RecordFootprint(expected.length, unit_), 0, view) ==
                        SectorReader::Step::kRecord &&
                    view.offset == offset && view.tag == expected.tag && view.id == expected.id &&
                    view.length == expected.length && view.sequence == expected.sequence &&
                    reader.Valid(view);
  if (!reader.failure().ok()) return reader.failure();
  return back ? base::OkStatus() : base::DataLoss();
}

base::Status FlashNvStore::ProgramRecord(std::size_t sector, std::size_t offset, const Change& change,
                                         std::uint32_t sequence) {
  const std::size_t base = SectorBase(sector) + offset;
  const std::size_t payload_at = base + AlignTo(kRecordHeaderBytes, unit_);
  const std::span<const std::uint8_t> data = change.data;
  RecordView record;
  record.tag = change.tag;
  record.id = change.id;
  record.length = static_cast<std::uint32_t>(data.size());
  record.sequence = sequence;
  base::Status status = ProgramPadded(
      base, EncodeRecordHeader(record.tag, record.id, record.length, sequence, base::Crc32(data)));
  const std::size_t whole = data.size() / unit_ * unit_;
  if (status.ok() && whole > 0) status = flash_.Program(payload_at, data.first(whole));
  if (status.ok()) status = ProgramPadded(payload_at + whole, data.subspan(whole));
  if (status.ok()) status = ProgramPadded(payload_at + AlignTo(data.size(), unit_), kRecordCommit);
  if (!status.ok()) return status;
  return VerifyRecord(sector, offset, record);
}

base::Status FlashNvStore::CopyRecord(const RecordView& from, std::size_t to_sector, std::size_t to_offset,
                                      std::uint32_t sequence) {
  const SectorReader source = Active();
  const std::size_t base = SectorBase(to_sector) + to_offset;
  const std::size_t payload_at = base + AlignTo(kRecordHeaderBytes, unit_);
  base::Status status =
      ProgramPadded(base, EncodeRecordHeader(from.tag, from.id, from.length, sequence, from.payload_crc));
  const std::size_t padded = AlignTo(from.length, unit_);
  std::array<std::uint8_t, kChunkBytes> chunk{};
  for (std::size_t done = 0; status.ok() && done < padded;) {
    const std::size_t n = std::min<std::size_t>(kChunkBytes, padded - done);  // a multiple of the unit
    const std::span<std::uint8_t> piece = std::span<std::uint8_t>(chunk).first(n);
    if (source.ReadPayloadChunk(from, done, piece)) {
      status = flash_.Program(payload_at + done, piece);
    } else {
      status = source.failure().ok() ? base::DataLoss() : source.failure();
    }
    done += n;
  }
  if (status.ok()) status = ProgramPadded(payload_at + padded, kRecordCommit);
  if (!status.ok()) return status;
  RecordView copy = from;
  copy.sequence = sequence;
  return VerifyRecord(to_sector, to_offset, copy);
}

// Programs `bytes` (a header, a commit, the tail of a payload: at most kChunkBytes) padded with 0xFF to
// a whole number of units.
base::Status FlashNvStore::ProgramPadded(std::size_t offset, std::span<const std::uint8_t> bytes) {
  if (bytes.empty()) return base::OkStatus();
  std::array<std::uint8_t, kChunkBytes> padded{};
  if (bytes.size() > padded.size()) return base::Internal();
  std::fill(padded.begin(), padded.end(), std::uint8_t{0xFF});
  std::copy(bytes.begin(), bytes.end(), padded.begin());
  return flash_.Program(offset, std::span<const std::uint8_t>(padded).first(AlignTo(bytes.size(), unit_)));
}

}  // namespace hal
