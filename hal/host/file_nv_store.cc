#include "file_nv_store.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <vector>

namespace hal::host {
namespace {

constexpr std::size_t kMaxFileBytes = FileNvStore::kHeaderBytes + kMaxRecordBytes;

constexpr std::array<std::uint32_t, 256> MakeCrc32Table() {
  std::array<std::uint32_t, 256> table{};
  for (std::uint32_t i = 0; i < 256; ++i) {
    std::uint32_t crc = i;
    for (int bit = 0; bit < 8; ++bit) crc = (crc & 1U) != 0 ? (crc >> 1) ^ 0xEDB88320U : crc >> 1;
    table[i] = crc;
  }
  return table;
}
constexpr std::array<std::uint32_t, 256> kCrc32Table = MakeCrc32Table();

// CRC-32 as in IEEE 802.3 and zlib (reflected 0x04C11DB7, initial and final XOR 0xFFFFFFFF).
std::uint32_t Crc32(std::span<const std::uint8_t> bytes) {
  std::uint32_t crc = 0xFFFFFFFFU;
  for (std::uint8_t byte : bytes) crc = (crc >> 8) ^ kCrc32Table[(crc ^ byte) & 0xFFU];
  return crc ^ 0xFFFFFFFFU;
}

void PutLe16(std::uint8_t* out, std::uint16_t value) {
  out[0] = static_cast<std::uint8_t>(value);
  out[1] = static_cast<std::uint8_t>(value >> 8);
}
void PutLe32(std::uint8_t* out, std::uint32_t value) {
  for (int i = 0; i < 4; ++i) out[i] = static_cast<std::uint8_t>(value >> (8 * i));
}
std::uint16_t GetLe16(const std::uint8_t* in) {
  return static_cast<std::uint16_t>(in[0] | (in[1] << 8));
}
std::uint32_t GetLe32(const std::uint8_t* in) {
  std::uint32_t value = 0;
  for (int i = 0; i < 4; ++i) value |= static_cast<std::uint32_t>(in[i]) << (8 * i);
  return value;
}

std::vector<std::uint8_t> EncodeRecord(NvRecordId id, std::span<const std::uint8_t> payload) {
  std::vector<std::uint8_t> file(FileNvStore::kHeaderBytes + payload.size());
  PutLe32(&file[0], FileNvStore::kMagic);
  PutLe16(&file[4], FileNvStore::kFormatVersion);
  PutLe16(&file[6], id);
  PutLe32(&file[8], static_cast<std::uint32_t>(payload.size()));
  PutLe32(&file[12], Crc32(payload));
  std::copy(payload.begin(), payload.end(), file.begin() + FileNvStore::kHeaderBytes);
  return file;
}

// The payload of a well-formed record file, or kDataLoss.
base::Result<std::span<const std::uint8_t>> DecodeRecord(NvRecordId id,
                                                         std::span<const std::uint8_t> file) {
  if (file.size() < FileNvStore::kHeaderBytes || file.size() > kMaxFileBytes) return base::DataLoss();
  const std::uint8_t* header = file.data();
  const std::uint32_t length = GetLe32(header + 8);
  if (GetLe32(header) != FileNvStore::kMagic || GetLe16(header + 4) != FileNvStore::kFormatVersion ||
      GetLe16(header + 6) != id || length != file.size() - FileNvStore::kHeaderBytes) {
    return base::DataLoss();
  }
  const std::span<const std::uint8_t> payload = file.subspan(FileNvStore::kHeaderBytes);
  if (Crc32(payload) != GetLe32(header + 12)) return base::DataLoss();
  return payload;
}

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

bool WriteAll(int fd, const std::uint8_t* data, std::size_t size) {
  while (size > 0) {
    const ssize_t n = write(fd, data, size);
    if (n < 0) {
      if (errno == EINTR) continue;
      return false;
    }
    data += n;
    size -= static_cast<std::size_t>(n);
  }
  return true;
}

}  // namespace

std::string FileNvStore::RecordFileName(NvRecordId id) {
  return "nv-" + std::to_string(id) + ".rec";
}

std::string FileNvStore::TempFileName(NvRecordId id) {
  return RecordFileName(id) + ".tmp";
}

base::Result<std::unique_ptr<FileNvStore>> FileNvStore::Open(const std::string& directory,
                                                             std::string* error_text) {
  const auto fail = [&](int err) -> base::Status {
    if (error_text != nullptr) {
      *error_text = "NV store directory '" + directory + "': " + std::strerror(err);
    }
    return StatusFromErrno(err);
  };
  if (mkdir(directory.c_str(), 0700) != 0 && errno != EEXIST) return fail(errno);
  const int dir_fd = open(directory.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dir_fd < 0) return fail(errno);
  std::unique_ptr<FileNvStore> store(new FileNvStore(directory, dir_fd));
  store->RemoveStaleTempFiles();
  return store;
}

FileNvStore::~FileNvStore() {
  if (dir_fd_ >= 0) close(dir_fd_);
}

base::Result<std::size_t> FileNvStore::Read(NvRecordId id, std::span<std::uint8_t> out) {
  const int fd = openat(dir_fd_, RecordFileName(id).c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return StatusFromErrno(errno);
  // One byte more than the largest valid file, so that an overlong file is seen as such.
  std::vector<std::uint8_t> file(kMaxFileBytes + 1);
  std::size_t size = 0;
  while (size < file.size()) {
    const ssize_t n = read(fd, file.data() + size, file.size() - size);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      const int err = errno;
      close(fd);
      return StatusFromErrno(err);
    }
    if (n == 0) break;
    size += static_cast<std::size_t>(n);
  }
  close(fd);

  const base::Result<std::span<const std::uint8_t>> payload =
      DecodeRecord(id, std::span<const std::uint8_t>(file).first(size));
  if (!payload.ok()) return payload.status();
  if (payload->size() > out.size()) return base::OutOfRange();
  std::copy(payload->begin(), payload->end(), out.begin());
  return payload->size();
}

base::Status FileNvStore::Write(NvRecordId id, std::span<const std::uint8_t> data) {
  if (data.size() > kMaxRecordBytes) return base::InvalidArgument();
  const std::vector<std::uint8_t> file = EncodeRecord(id, data);
  const std::string temp_name = TempFileName(id);

  // O_TRUNC: a temp file left by an earlier failed Write() is simply overwritten.
  const int fd = openat(dir_fd_, temp_name.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0600);
  if (fd < 0) return StatusFromErrno(errno);

  if (power_cut_after_.has_value()) {
    const std::size_t reached_disk = std::min(*power_cut_after_, file.size());
    power_cut_after_.reset();
    // No fsync and no rename: the process "dies" here; what reached the disk is all that is left.
    WriteAll(fd, file.data(), reached_disk);
    close(fd);
    return base::Internal();
  }

  // The data must be durable before the rename makes it the live record; otherwise a cut just after
  // the rename could leave a live file whose blocks never reached the disk.
  if (!WriteAll(fd, file.data(), file.size()) || fsync(fd) != 0) {
    const int err = errno;
    close(fd);
    unlinkat(dir_fd_, temp_name.c_str(), 0);
    return StatusFromErrno(err);
  }
  if (close(fd) != 0) {
    const int err = errno;
    unlinkat(dir_fd_, temp_name.c_str(), 0);
    return StatusFromErrno(err);
  }
  if (renameat(dir_fd_, temp_name.c_str(), dir_fd_, RecordFileName(id).c_str()) != 0) {
    const int err = errno;
    unlinkat(dir_fd_, temp_name.c_str(), 0);
    return StatusFromErrno(err);
  }
  // The rename lives in the directory; until the directory is synced a cut may still undo it.
  if (fsync(dir_fd_) != 0) return StatusFromErrno(errno);
  return base::OkStatus();
}

base::Status FileNvStore::Erase(NvRecordId id) {
  if (unlinkat(dir_fd_, RecordFileName(id).c_str(), 0) != 0 && errno != ENOENT) {
    return StatusFromErrno(errno);
  }
  if (fsync(dir_fd_) != 0) return StatusFromErrno(errno);
  return base::OkStatus();
}

void FileNvStore::RemoveStaleTempFiles() {
  // Best effort with error codes: a directory that cannot be listed only leaves harmless temp files.
  std::error_code ec;
  for (std::filesystem::directory_iterator it(directory_, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.starts_with("nv-") && name.ends_with(".rec.tmp")) unlinkat(dir_fd_, name.c_str(), 0);
  }
}

}  // namespace hal::host
