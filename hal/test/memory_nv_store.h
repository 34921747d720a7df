// An NV store in memory for tests: records in a map, a count of writes, and statuses a test sets to make
// the next reads or writes fail.
#pragma once

#include <algorithm>
#include <cstdint>
#include <map>
#include <span>
#include <vector>

#include "hal/nv_store.h"

namespace hal::test {

class MemoryNvStore final : public NvStore {
 public:
  base::Result<std::size_t> Read(NvRecordId id, std::span<std::uint8_t> out) override {
    if (!read_status.ok()) return read_status;
    const auto it = records.find(id);
    if (it == records.end()) return base::NotFound();
    if (it->second.size() > out.size()) return base::OutOfRange();
    std::copy(it->second.begin(), it->second.end(), out.begin());
    return it->second.size();
  }
  base::Status Write(NvRecordId id, std::span<const std::uint8_t> data) override {
    ++writes;
    if (!write_status.ok()) return write_status;
    records[id].assign(data.begin(), data.end());
    return base::OkStatus();
  }
  base::Status Erase(NvRecordId id) override {
    records.erase(id);
    return base::OkStatus();
  }

  std::map<NvRecordId, std::vector<std::uint8_t>> records;
  base::Status read_status;
  base::Status write_status;
  int writes = 0;
};

}  // namespace hal::test
