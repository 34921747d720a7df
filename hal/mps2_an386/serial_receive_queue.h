// The receive side of a UART under hal::SerialPort's contract: the interrupt handler stores each byte
// and marks where bytes were lost (a hardware overrun, a framing or parity error, the queue full); the
// event loop reads the bytes before the loss, then gets kDataLoss once, then the bytes after it.
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <span>

#include "base/status.h"
#include "byte_ring.h"

namespace hal::mps2 {

template <std::size_t kCapacity>
class SerialReceiveQueue {
 public:
  // Interrupt side: one received byte. A full queue loses it (and says so at that place).
  void Store(std::uint8_t byte) {
    if (!ring_.Push(byte)) MarkLoss();
  }
  // Interrupt side: bytes were lost before the next byte stored. Losses before the loop catches up are
  // reported as one kDataLoss; losses() counts each.
  void MarkLoss() {
    if (!loss_pending_.load(std::memory_order_acquire)) {
      loss_at_ = ring_.pushed();
      loss_pending_.store(true, std::memory_order_release);
    }
    losses_.fetch_add(1, std::memory_order_relaxed);
  }

  // Loop side (hal::SerialPort::Read): the bytes waiting, up to the next loss; kDataLoss at the loss
  // (once); kUnavailable when none. (A byte that the interrupt stores while this reads may slip in just
  // before the loss is seen; the loss is then reported right after it, never dropped.)
  base::Result<std::size_t> Read(std::span<std::uint8_t> out) {
    if (out.empty()) return base::Unavailable();
    std::size_t count = 0;
    while (count < out.size() && !AtLoss()) {
      if (!ring_.Pop(out[count])) break;
      ++count;
    }
    if (count > 0) return count;
    if (AtLoss()) {
      loss_pending_.store(false, std::memory_order_release);
      return base::DataLoss();
    }
    return base::Unavailable();
  }

  bool empty() const { return ring_.empty() && !loss_pending_.load(std::memory_order_acquire); }
  std::uint32_t losses() const { return losses_.load(std::memory_order_relaxed); }

 private:
  // A loss is pending and every byte stored before it has been read.
  bool AtLoss() const {
    return loss_pending_.load(std::memory_order_acquire) &&
           static_cast<std::int32_t>(ring_.popped() - loss_at_) >= 0;
  }

  ByteRing<kCapacity> ring_;
  std::uint32_t loss_at_ = 0;  // written by the interrupt side before loss_pending_ is set
  std::atomic<bool> loss_pending_{false};
  std::atomic<std::uint32_t> losses_{0};
};

}  // namespace hal::mps2
