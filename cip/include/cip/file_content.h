// The content of a read-only file the card serves (the CIP File object 0x37's EDS instance, the HTTP
// download) without storing it: a deterministic generator behind a read window (docs/eds.md "Serving").
//
//   Size()      the number of bytes of the whole file
//   Checksum()  the CIP File object's checksum: the two's complement of the 16-bit sum of every byte
//               (so the sum of all bytes plus the checksum is 0 modulo 2^16)
//   ReadAt()    copies bytes [offset, offset + out.size()) of the file, fewer at its end; returns the
//               number copied (0 at or past the end)
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

namespace cip {

class FileContent {
 public:
  virtual std::uint32_t Size() const = 0;
  virtual std::uint16_t Checksum() const = 0;
  virtual std::size_t ReadAt(std::uint32_t offset, std::span<std::uint8_t> out) const = 0;

 protected:
  ~FileContent() = default;  // not owned through this interface
};

}  // namespace cip
