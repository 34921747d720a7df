#include "card_qos.h"

#include <algorithm>
#include <array>

namespace firmware {
namespace {

constexpr std::uint8_t kQosRecordVersion = 1;
constexpr std::size_t kQosRecordBytes = 1 + cip::kQosAttributes;

bool InRange(const cip::QosSettings& settings) {
  const std::uint8_t tag = settings[cip::QosAttribute::kTagEnable];
  return tag <= 1 && std::all_of(settings.values.begin() + 1, settings.values.end(), [](std::uint8_t dscp) {
           return dscp <= 63;
         });
}

}  // namespace

CardQos::CardQos(hal::NvStore& store) : store_(store) {
  std::array<std::uint8_t, kQosRecordBytes> record{};
  const base::Result<std::size_t> read = store_.Read(kNvQos, record);
  if (read.ok() && *read == record.size() && record[0] == kQosRecordVersion) {
    cip::QosSettings loaded;
    std::copy(record.begin() + 1, record.end(), loaded.values.begin());
    if (InRange(loaded)) stored_ = loaded;
  }
  active_ = stored_;
}

base::Status CardQos::StoreQos(const cip::QosSettings& settings) {
  if (!InRange(settings)) return base::InvalidArgument();
  if (settings == stored_) return base::OkStatus();  // the store wears: an unchanged value is not written
  std::array<std::uint8_t, kQosRecordBytes> record{kQosRecordVersion};
  std::copy(settings.values.begin(), settings.values.end(), record.begin() + 1);
  if (base::Status written = store_.Write(kNvQos, record); !written.ok()) return written;
  stored_ = settings;
  return base::OkStatus();
}

}  // namespace firmware
