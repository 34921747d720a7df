#include "atomic_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>

namespace hal::host {
namespace {

constexpr std::string_view kTempSuffix = ".tmp";

bool WriteAll(int fd, const std::uint8_t* data, std::size_t size) {
  while (size > 0) {
    const ssize_t n = write(fd, data, size);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    data += n;
    size -= static_cast<std::size_t>(n);
  }
  return true;
}

base::Status Fail(int err, const std::string& file, std::string* error_text) {
  if (error_text != nullptr) *error_text = file + ": " + std::strerror(err);
  return StatusFromErrno(err);
}

}  // namespace

base::Status StatusFromErrno(int err) {
  switch (err) {
    case ENOENT: return base::NotFound();
    case EACCES:
    case EPERM:
    case EROFS: return base::PermissionDenied();
    case ENOSPC:
    case EDQUOT: return base::ResourceExhausted();
    case ENOTDIR: return base::FailedPrecondition();
    default: return base::Internal();
  }
}

std::string TempFileName(std::string_view name) {
  std::string temp(name);
  temp += kTempSuffix;
  return temp;
}

base::Status ReplaceFileAtomically(int dir_fd, const std::string& name, std::span<const std::uint8_t> contents,
                                   std::string* error_text, const std::optional<PowerCut>& cut) {
  const std::string temp = TempFileName(name);
  // O_TRUNC: a temp file left by an earlier failed write is simply overwritten.
  const int fd = openat(dir_fd, temp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0600);
  if (fd < 0) return Fail(errno, temp, error_text);

  if (cut.has_value() && cut->stage == PowerCut::Stage::kWritingTempFile) {
    // No fsync and no rename: the process dies here; what reached the disk is all that is left.
    WriteAll(fd, contents.data(), std::min(cut->bytes, contents.size()));
    close(fd);
    return base::Internal();
  }
  // The data must be durable before the rename makes it live; otherwise a cut just after the rename
  // could leave a live file whose blocks never reached the disk.
  if (!WriteAll(fd, contents.data(), contents.size()) || fsync(fd) != 0) {
    const int err = errno;
    close(fd);
    unlinkat(dir_fd, temp.c_str(), 0);
    return Fail(err, temp, error_text);
  }
  if (close(fd) != 0) {
    const int err = errno;
    unlinkat(dir_fd, temp.c_str(), 0);
    return Fail(err, temp, error_text);
  }
  if (renameat(dir_fd, temp.c_str(), dir_fd, name.c_str()) != 0) {
    const int err = errno;
    unlinkat(dir_fd, temp.c_str(), 0);
    return Fail(err, name, error_text);
  }
  if (cut.has_value()) return base::Internal();  // kAfterRename: the directory is never synced
  // The rename lives in the directory; until the directory is synced a cut may still undo it.
  if (fsync(dir_fd) != 0) return Fail(errno, "the directory of " + name, error_text);
  return base::OkStatus();
}

void RemoveTempFiles(int dir_fd, const std::string& directory, std::string_view prefix) {
  std::error_code ec;
  for (std::filesystem::directory_iterator it(directory, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.starts_with(prefix) && name.ends_with(kTempSuffix)) unlinkat(dir_fd, name.c_str(), 0);
  }
}

}  // namespace hal::host
