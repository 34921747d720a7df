#include "file_nv_store.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <vector>

#include "atomic_file.h"
#include "base/crc32.h"

namespace hal::host {
namespace {

constexpr std::size_t kMaxFileBytes = FileNvStore::kHeaderBytes + kMaxRecordBytes;

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
  PutLe32(&file[12], base::Crc32(payload));
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
  if (base::Crc32(payload) != GetLe32(header + 12)) return base::DataLoss();
  return payload;
}

}  // namespace

std::string FileNvStore::RecordFileName(NvRecordId id) {
  return "nv-" + std::to_string(id) + ".rec";
}

std::string FileNvStore::TempFileName(NvRecordId id) {
  return hal::host::TempFileName(RecordFileName(id));
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
  const std::optional<PowerCut> cut = power_cut_;
  power_cut_.reset();
  return ReplaceFileAtomically(dir_fd_, RecordFileName(id), file, nullptr, cut);
}

base::Status FileNvStore::Erase(NvRecordId id) {
  if (unlinkat(dir_fd_, RecordFileName(id).c_str(), 0) != 0 && errno != ENOENT) {
    return StatusFromErrno(errno);
  }
  if (fsync(dir_fd_) != 0) return StatusFromErrno(errno);
  return base::OkStatus();
}

void FileNvStore::RemoveStaleTempFiles() { RemoveTempFiles(dir_fd_, directory_, "nv-"); }

}  // namespace hal::host
