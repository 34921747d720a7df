// Stores c-parameters in the inverter on behalf of the CIP objects (TCP/IP Interface, Ethernet Link):
// a bounded queue of writes, sent one at a time through the register proxy as W writes (RAM and
// EEPROM: these are user settings, effective after the next reset, seed 000 §3.1 "(*3)").
//
// A request is queued whole or not at all, so a Set_Attribute_Single is either stored completely or
// refused. A later value for a number still queued replaces the earlier one (one EEPROM write). A write
// the inverter refuses is counted and dropped; one the proxy cannot start yet is retried.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "base/pool_stats.h"
#include "base/status.h"
#include "drive_link/register_proxy.h"
#include "event_loop.h"

namespace firmware {

struct ParameterValue {
  std::uint16_t number = 0;
  std::uint16_t value = 0;
};

struct ParameterWriterCounters {
  std::uint32_t written = 0;
  std::uint32_t failed = 0;  // refused by the inverter or timed out
  drive_link::AccessError last_error = drive_link::AccessError::kNone;
};

class ParameterWriter final : public Service, private drive_link::AccessListener {
 public:
  // TCP/IP attributes 3, 5 and 6 at once: c504, c505-c516 and c081-c096, plus room for c501.
  static constexpr std::size_t kMaxQueued = 1 + 12 + 16 + 3;
  static constexpr hal::Micros kRetryInterval = 10 * hal::kMicrosPerMilli;

  explicit ParameterWriter(drive_link::RegisterProxy& proxy) : proxy_(proxy) {}
  ~ParameterWriter() override { proxy_.Cancel(*this); }

  // kFailedPrecondition: the drive link is down or the configuration not read yet (nothing can be
  // stored); kResourceExhausted: the queue has no room for every item. Nothing is queued then.
  base::Status Enqueue(std::span<const ParameterValue> items);
  std::size_t pending() const { return count_ + (in_flight_ ? 1 : 0); }
  const ParameterWriterCounters& counters() const { return counters_; }
  // The queue (docs/robustness.md "Exhaustion"), without the write on its way; refused: an Enqueue
  // answered kResourceExhausted.
  base::PoolStats queue_pool() const { return queue_marks_.Stats(count_, kMaxQueued); }

  void Poll(hal::Micros now) override;
  hal::Micros NextDeadline() const override;

 private:
  void OnAccessDone(drive_link::AccessToken token, const drive_link::AccessResult& result) override;
  ParameterValue* Find(std::uint16_t number);

  drive_link::RegisterProxy& proxy_;
  std::array<ParameterValue, kMaxQueued> queue_{};  // [0, count_) in order
  std::size_t count_ = 0;
  bool in_flight_ = false;
  drive_link::AccessToken token_ = drive_link::kNoAccess;
  hal::Micros retry_at_ = 0;
  ParameterWriterCounters counters_;
  base::PoolWatermark queue_marks_;
};

}  // namespace firmware
