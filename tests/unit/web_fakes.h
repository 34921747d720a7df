// Fakes for the web server's password store and access control: a random source whose bytes count up
// (so salts and tokens are known exactly) and an NV store in memory that can be told to fail.
#pragma once

#include <algorithm>
#include <cstdint>
#include <map>
#include <span>
#include <vector>

#include "hal/nv_store.h"
#include "hal/random.h"

namespace web::test {

// Byte n of all the bytes ever handed out is (n mod 256) xor (n / 256 mod 256): the first Fill of 16
// gives 00..0f, the next 10..1f, and so on; after 256 bytes the values go on in another order, so
// that tokens drawn later do not repeat earlier ones.
class CountingRandom final : public hal::RandomSource {
 public:
  void Fill(std::span<std::uint8_t> out) override {
    for (std::uint8_t& byte : out) {
      byte = static_cast<std::uint8_t>(next_ ^ (next_ >> 8));
      ++next_;
    }
  }

 private:
  std::uint32_t next_ = 0;
};

class MemoryNvStore final : public hal::NvStore {
 public:
  base::Result<std::size_t> Read(hal::NvRecordId id, std::span<std::uint8_t> out) override {
    if (!read_status.ok()) return read_status;
    const auto it = records.find(id);
    if (it == records.end()) return base::NotFound();
    if (it->second.size() > out.size()) return base::OutOfRange();
    std::copy(it->second.begin(), it->second.end(), out.begin());
    return it->second.size();
  }
  base::Status Write(hal::NvRecordId id, std::span<const std::uint8_t> data) override {
    ++writes;
    if (!write_status.ok()) return write_status;
    records[id].assign(data.begin(), data.end());
    return base::OkStatus();
  }
  base::Status Erase(hal::NvRecordId id) override {
    records.erase(id);
    return base::OkStatus();
  }

  std::map<hal::NvRecordId, std::vector<std::uint8_t>> records;
  base::Status read_status;
  base::Status write_status;
  int writes = 0;
};

}  // namespace web::test
