#include "ram_nv_store.h"

#include <algorithm>

namespace firmware::board {

RamNvStore::Record* RamNvStore::Find(hal::NvRecordId id) {
  for (Record& record : records_) {
    if (record.used && record.id == id) return &record;
  }
  return nullptr;
}

base::Result<std::size_t> RamNvStore::Read(hal::NvRecordId id, std::span<std::uint8_t> out) {
  const Record* record = Find(id);
  if (record == nullptr) return base::NotFound();
  if (out.size() < record->length) return base::OutOfRange();
  std::copy_n(record->bytes.begin(), record->length, out.begin());
  return record->length;
}

base::Status RamNvStore::Write(hal::NvRecordId id, std::span<const std::uint8_t> data) {
  if (data.size() > hal::kMaxRecordBytes) return base::InvalidArgument();
  if (data.size() > kRecordBytes) return base::ResourceExhausted();
  Record* record = Find(id);
  if (record == nullptr) {
    const auto free = std::find_if(records_.begin(), records_.end(), [](const Record& r) { return !r.used; });
    if (free == records_.end()) return base::ResourceExhausted();
    record = &*free;
  }
  record->used = true;
  record->id = id;
  record->length = data.size();
  std::copy(data.begin(), data.end(), record->bytes.begin());
  return base::OkStatus();
}

base::Status RamNvStore::Erase(hal::NvRecordId id) {
  Record* record = Find(id);
  if (record != nullptr) *record = Record{};
  return base::OkStatus();
}

}  // namespace firmware::board
