#include "pcap_writer.h"

#include <fcntl.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <vector>

namespace hal::host {
namespace {

void PutLe16(std::vector<std::uint8_t>& out, std::uint16_t value) {
  out.push_back(static_cast<std::uint8_t>(value));
  out.push_back(static_cast<std::uint8_t>(value >> 8));
}

void PutLe32(std::vector<std::uint8_t>& out, std::uint32_t value) {
  for (int i = 0; i < 4; ++i) out.push_back(static_cast<std::uint8_t>(value >> (8 * i)));
}

bool WriteAll(int fd, std::span<const std::uint8_t> bytes) {
  while (!bytes.empty()) {
    const ssize_t n = write(fd, bytes.data(), bytes.size());
    if (n < 0) {
      if (errno == EINTR) continue;
      return false;
    }
    bytes = bytes.subspan(static_cast<std::size_t>(n));
  }
  return true;
}

}  // namespace

Micros WallClockMicros() {
  timespec ts{};
  clock_gettime(CLOCK_REALTIME, &ts);
  return static_cast<Micros>(ts.tv_sec) * kMicrosPerSecond + static_cast<Micros>(ts.tv_nsec) / 1000;
}

base::Result<std::unique_ptr<PcapWriter>> PcapWriter::Open(const std::string& path,
                                                           std::string* error_text) {
  const int fd = open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) {
    const int err = errno;
    if (error_text != nullptr) *error_text = "pcap file '" + path + "': " + std::strerror(err);
    if (err == ENOENT) return base::NotFound();
    if (err == EACCES || err == EPERM || err == EROFS) return base::PermissionDenied();
    return base::Internal();
  }
  std::unique_ptr<PcapWriter> writer(new PcapWriter(path, fd));

  std::vector<std::uint8_t> header;
  header.reserve(kGlobalHeaderBytes);
  PutLe32(header, kMagicMicroseconds);
  PutLe16(header, 2);  // version major
  PutLe16(header, 4);  // version minor
  PutLe32(header, 0);  // thiszone: timestamps are UTC
  PutLe32(header, 0);  // sigfigs
  PutLe32(header, kSnapLength);
  PutLe32(header, kLinkTypeEthernet);
  if (!WriteAll(fd, header)) {
    if (error_text != nullptr) *error_text = "pcap file '" + path + "': " + std::strerror(errno);
    return base::Internal();
  }
  return writer;
}

PcapWriter::~PcapWriter() {
  if (fd_ >= 0) close(fd_);
}

base::Status PcapWriter::Write(std::span<const std::uint8_t> frame, Micros timestamp) {
  const std::size_t captured = std::min<std::size_t>(frame.size(), kSnapLength);
  std::vector<std::uint8_t> record;
  record.reserve(kRecordHeaderBytes + captured);
  // ts_sec is 32 bits unsigned in this format: good until 2106.
  PutLe32(record, static_cast<std::uint32_t>(timestamp / kMicrosPerSecond));
  PutLe32(record, static_cast<std::uint32_t>(timestamp % kMicrosPerSecond));
  PutLe32(record, static_cast<std::uint32_t>(captured));
  PutLe32(record, static_cast<std::uint32_t>(frame.size()));
  record.insert(record.end(), frame.begin(), frame.begin() + static_cast<std::ptrdiff_t>(captured));
  if (!WriteAll(fd_, record)) return base::Internal();
  ++frames_written_;
  return base::OkStatus();
}

}  // namespace hal::host
