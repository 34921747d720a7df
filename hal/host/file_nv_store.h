// hal::NvStore on the host: one file per record in a directory (`nv-<id>.rec`, id in decimal).
//
// Record file (all fields little-endian), 16-byte header then the payload:
//   offset 0  u32 magic   0x564E5049 ("IPNV" on disk)
//   offset 4  u16 format  1
//   offset 6  u16 record id (catches a file copied or renamed to the wrong name)
//   offset 8  u32 payload length (0..kMaxRecordBytes; must equal file size - 16)
//   offset 12 u32 CRC-32 (IEEE 802.3, as zlib) of the payload
//
// Power-loss atomicity comes from never touching the live file (atomic_file.h, which says what it rests
// on): Write() writes the whole new file as `nv-<id>.rec.tmp` in the same directory, fsyncs it, renames
// it over `nv-<id>.rec` and fsyncs the directory. A cut before the rename leaves the old file intact
// plus a partial temp file, which Open() deletes. The header check catches what atomicity cannot (a bad
// disk, a hand-edited or truncated file) and reports it as kDataLoss, which every reader treats as a
// record that was never written.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <utility>

#include "atomic_file.h"
#include "base/status.h"
#include "hal/nv_store.h"

namespace hal::host {

class FileNvStore final : public NvStore {
 public:
  static constexpr std::size_t kHeaderBytes = 16;
  static constexpr std::uint32_t kMagic = 0x564E5049;
  static constexpr std::uint16_t kFormatVersion = 1;

  // Uses `directory`, creating it (one level) if missing, and deletes temp files a crash left behind.
  // kNotFound: the parent directory does not exist. kPermissionDenied: not accessible.
  // `error_text` (optional) receives a sentence naming the directory and the cause.
  static base::Result<std::unique_ptr<FileNvStore>> Open(const std::string& directory,
                                                         std::string* error_text);

  ~FileNvStore() override;
  FileNvStore(const FileNvStore&) = delete;
  FileNvStore& operator=(const FileNvStore&) = delete;

  // hal::NvStore. Write: kInvalidArgument when data exceeds kMaxRecordBytes. Erase of a record that
  // does not exist succeeds (erasing is idempotent, as factory defaults needs).
  base::Result<std::size_t> Read(NvRecordId id, std::span<std::uint8_t> out) override;
  base::Status Write(NvRecordId id, std::span<const std::uint8_t> data) override;
  base::Status Erase(NvRecordId id) override;

  // File names, for tests and diagnostics ("nv-7.rec", "nv-7.rec.tmp").
  static std::string RecordFileName(NvRecordId id);
  static std::string TempFileName(NvRecordId id);
  const std::string& directory() const { return directory_; }

  // Host-only test hooks, one shot: the next Write() loses power once `bytes` bytes of the new record
  // file (header + payload) have reached the disk. It leaves the temp file holding exactly that prefix,
  // never renames it, and returns kInternal; the store must not be used afterwards. A test then opens
  // a fresh FileNvStore on the same directory, as the card does when power returns. `bytes` equal to
  // the whole file models a cut after the data is safe but before the rename.
  void CutPowerAfterBytesForTest(std::size_t bytes) { power_cut_ = PowerCut{PowerCut::Stage::kWritingTempFile, bytes}; }
  // The same after the rename, before the directory is synced (the new record is live).
  void CutPowerAfterRenameForTest() { power_cut_ = PowerCut{PowerCut::Stage::kAfterRename, 0}; }

 private:
  FileNvStore(std::string directory, int dir_fd) : directory_(std::move(directory)), dir_fd_(dir_fd) {}
  // Deletes the `nv-*.rec.tmp` files of an interrupted Write().
  void RemoveStaleTempFiles();

  std::string directory_;
  int dir_fd_ = -1;  // kept open for openat/renameat and to fsync the directory after a rename
  std::optional<PowerCut> power_cut_;
};

}  // namespace hal::host
