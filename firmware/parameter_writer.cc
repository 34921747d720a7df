#include "parameter_writer.h"

#include <algorithm>

namespace firmware {

ParameterValue* ParameterWriter::Find(std::uint16_t number) {
  for (std::size_t i = 0; i < count_; ++i) {
    if (queue_[i].number == number) return &queue_[i];
  }
  return nullptr;
}

base::Status ParameterWriter::Enqueue(std::span<const ParameterValue> items) {
  if (!proxy_.config_loaded() || proxy_.link().state() == drive_link::LinkState::kFault) {
    return base::FailedPrecondition();
  }
  std::size_t needed = 0;
  for (std::size_t i = 0; i < items.size(); ++i) {
    const bool repeated = std::any_of(items.begin(), items.begin() + static_cast<std::ptrdiff_t>(i),
                                      [&](const ParameterValue& v) { return v.number == items[i].number; });
    if (!repeated && Find(items[i].number) == nullptr) ++needed;
  }
  if (count_ + needed > queue_.size()) {
    queue_marks_.NoteRefused();
    return base::ResourceExhausted();
  }
  for (const ParameterValue& item : items) {
    if (ParameterValue* queued = Find(item.number)) {
      queued->value = item.value;
    } else {
      queue_[count_++] = item;
    }
  }
  queue_marks_.NoteTaken(count_);
  return base::OkStatus();
}

void ParameterWriter::Poll(hal::Micros now) {
  if (in_flight_ || count_ == 0 || now < retry_at_) return;
  const ParameterValue next = queue_[0];
  const base::Result<drive_link::AccessToken> token =
      proxy_.Write(next.number, next.value, drive_link::WriteMode::kRamAndEeprom, *this);
  if (!token.ok()) {
    // Busy pool or the link down for now: the queue waits (a write is never dropped for that).
    retry_at_ = now + kRetryInterval;
    return;
  }
  token_ = *token;
  in_flight_ = true;
  std::copy(queue_.begin() + 1, queue_.begin() + static_cast<std::ptrdiff_t>(count_), queue_.begin());
  --count_;
}

hal::Micros ParameterWriter::NextDeadline() const {
  if (in_flight_ || count_ == 0) return hal::kNever;
  return retry_at_;
}

void ParameterWriter::OnAccessDone(drive_link::AccessToken token, const drive_link::AccessResult& result) {
  if (!in_flight_ || token != token_) return;
  in_flight_ = false;
  token_ = drive_link::kNoAccess;
  retry_at_ = 0;
  if (result.ok()) {
    ++counters_.written;
  } else {
    ++counters_.failed;
    counters_.last_error = result.error;
  }
}

}  // namespace firmware
