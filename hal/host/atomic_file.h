// Files replaced whole, atomically against power loss: the card's NV records (FileNvStore) and the
// simulated inverter's EEPROM image (host::SimulatedInverter). docs/robustness.md "Power loss".
//
// ReplaceFileAtomically never touches the live file: it writes the new contents as `<name>.tmp` in the
// same directory, fsyncs it, renames it over `<name>` and fsyncs the directory. What that rests on:
// - rename(2) within one file system replaces the directory entry atomically: every observer, and the
//   file system after a crash, sees the old file or the new one, never neither and never a mix;
// - fsync(2) of the temp file returns only once its data and size are on stable storage, so the rename
//   can never make live a file whose blocks did not reach the disk;
// - fsync(2) of the directory makes the rename itself durable (until then a cut may undo it, which
//   leaves the old file: still a whole one).
// A cut before the rename leaves the old file and a partial temp file, which RemoveTempFiles deletes at
// the next start. The readers check the contents anyway (a CRC), for what atomicity cannot cover: a
// disk or file system that breaks its promises, a hand-edited or truncated copy.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "base/status.h"

namespace hal::host {

// A simulated power cut inside ReplaceFileAtomically, for tests: the process "dies" at that point and
// only what reached the disk is left (the page cache survives a killed process, so a written byte
// counts as on the disk).
struct PowerCut {
  enum class Stage : std::uint8_t {
    kWritingTempFile,  // `bytes` of the new contents reached the temp file (all of them: fsynced, not renamed)
    kAfterRename,      // renamed, the directory not yet synced
  };
  Stage stage = Stage::kWritingTempFile;
  std::size_t bytes = 0;
};

// Replaces `name` in the directory open as `dir_fd` with `contents` as described above. Errors from
// errno (StatusFromErrno); `error_text` (optional) receives a sentence naming the file and the cause.
// With `cut`: stops there and returns kInternal (the temp file is left as the cut left it).
base::Status ReplaceFileAtomically(int dir_fd, const std::string& name, std::span<const std::uint8_t> contents,
                                   std::string* error_text = nullptr,
                                   const std::optional<PowerCut>& cut = std::nullopt);

// The temp file ReplaceFileAtomically writes for `name`.
std::string TempFileName(std::string_view name);

// Deletes the temp files an interrupted ReplaceFileAtomically left in `directory` (open as `dir_fd`),
// those whose name starts with `prefix`. Best effort: a leftover temp file is harmless.
void RemoveTempFiles(int dir_fd, const std::string& directory, std::string_view prefix);

// ENOENT kNotFound, EACCES/EPERM/EROFS kPermissionDenied, ENOSPC/EDQUOT kResourceExhausted,
// ENOTDIR kFailedPrecondition, anything else kInternal.
base::Status StatusFromErrno(int err);

}  // namespace hal::host
