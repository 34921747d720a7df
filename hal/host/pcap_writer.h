// Capture file writer: classic libpcap format (what tcpdump -w writes), so a capture of the card's
// traffic opens in Wireshark/tshark with the CIP and Modbus dissectors.
//
// Layout, little-endian: a 24-byte global header (magic 0xa1b2c3d4 = microsecond timestamps, version
// 2.4, thiszone 0, sigfigs 0, snaplen 65535, LINKTYPE_ETHERNET 1), then per frame a 16-byte record
// header (ts_sec, ts_usec, captured length, original length) and the frame bytes.
//
// Timestamps are wall-clock time (microseconds since the Unix epoch, CLOCK_REALTIME), not hal::Clock:
// tshark prints them as dates and users line them up with host-side captures and logs, which use
// wall-clock time too. WallClockMicros() provides it; the caller passes the stamp so tests can fix it.
//
// Every record goes to the file with a single write() on an unbuffered descriptor, so a reader (a test,
// `tshark -r` while the firmware runs) always sees whole records.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <utility>

#include "base/status.h"
#include "hal/clock.h"

namespace hal::host {

// CLOCK_REALTIME in microseconds since 1970-01-01T00:00:00Z.
Micros WallClockMicros();

class PcapWriter {
 public:
  static constexpr std::uint32_t kMagicMicroseconds = 0xa1b2c3d4;
  static constexpr std::uint32_t kSnapLength = 65535;
  static constexpr std::uint32_t kLinkTypeEthernet = 1;
  static constexpr std::size_t kGlobalHeaderBytes = 24;
  static constexpr std::size_t kRecordHeaderBytes = 16;

  // Creates (or truncates) `path` and writes the global header. kNotFound: the directory does not
  // exist; kPermissionDenied: not writable. `error_text` (optional) receives a sentence naming the file.
  static base::Result<std::unique_ptr<PcapWriter>> Open(const std::string& path, std::string* error_text);

  ~PcapWriter();
  PcapWriter(const PcapWriter&) = delete;
  PcapWriter& operator=(const PcapWriter&) = delete;

  // Appends one frame stamped `timestamp` (µs since the Unix epoch). Frames longer than the snap length
  // are cut to it, with their original length kept in the record header. kInternal: the write failed.
  base::Status Write(std::span<const std::uint8_t> frame, Micros timestamp);

  std::size_t frames_written() const { return frames_written_; }
  const std::string& path() const { return path_; }

 private:
  PcapWriter(std::string path, int fd) : path_(std::move(path)), fd_(fd) {}

  std::string path_;
  int fd_ = -1;
  std::size_t frames_written_ = 0;
};

}  // namespace hal::host
