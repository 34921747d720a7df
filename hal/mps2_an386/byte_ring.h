// A ring of bytes between one interrupt handler and the event loop: one side only pushes, the other
// only pops, so neither ever waits for the other and no interrupt has to be masked. The indices run
// freely (wrapping at 2^32) and are atomics, so each side sees the other's bytes complete.
#pragma once

#include <array>
#include <atomic>
#include <cstddef>
#include <cstdint>

namespace hal::mps2 {

template <std::size_t kCapacity>
class ByteRing {
  static_assert(kCapacity >= 2 && (kCapacity & (kCapacity - 1)) == 0, "capacity: a power of two");

 public:
  // Producer side. False when full (the byte is not stored).
  bool Push(std::uint8_t byte) {
    const std::uint32_t head = head_.load(std::memory_order_relaxed);
    if (head - tail_.load(std::memory_order_acquire) == kCapacity) return false;
    bytes_[head & (kCapacity - 1)] = byte;
    head_.store(head + 1, std::memory_order_release);
    return true;
  }

  // Consumer side. False when empty.
  bool Pop(std::uint8_t& byte) {
    const std::uint32_t tail = tail_.load(std::memory_order_relaxed);
    if (head_.load(std::memory_order_acquire) == tail) return false;
    byte = bytes_[tail & (kCapacity - 1)];
    tail_.store(tail + 1, std::memory_order_release);
    return true;
  }

  std::size_t size() const { return head_.load(std::memory_order_acquire) - tail_.load(std::memory_order_acquire); }
  bool empty() const { return size() == 0; }
  std::size_t free() const { return kCapacity - size(); }
  static constexpr std::size_t capacity() { return kCapacity; }
  // How many bytes were ever pushed / popped (the producer's and the consumer's positions).
  std::uint32_t pushed() const { return head_.load(std::memory_order_acquire); }
  std::uint32_t popped() const { return tail_.load(std::memory_order_acquire); }

 private:
  std::array<std::uint8_t, kCapacity> bytes_{};
  std::atomic<std::uint32_t> head_{0};
  std::atomic<std::uint32_t> tail_{0};
};

}  // namespace hal::mps2
