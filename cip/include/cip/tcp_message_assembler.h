// Reassembles encapsulation messages from one TCP connection's byte stream: a segment may hold part of
// a message, exactly one, or several back to back; a message may arrive one byte at a time.
//
// Limit: a message is at most kMaxEncapsulationMessage bytes (header + kMaxEncapsulationData). A longer
// one cannot be buffered, but the stream stays in step: its header is kept, its body is counted off
// and dropped as it arrives, and the message is then delivered with oversized() set and an empty body,
// so the server can answer it with status 0x0002 (insufficient memory) and carry on with the next one.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "cip/encapsulation.h"

namespace cip {

// Largest command-specific data the card buffers. An unconnected explicit message carries at most 504
// bytes of message router data (the usual CIP limit); 600 leaves room for the Common Packet Format, an
// Unconnected_Send wrapper and socket address items.
inline constexpr std::size_t kMaxEncapsulationData = 600;
inline constexpr std::size_t kMaxEncapsulationMessage = kEncapsulationHeaderSize + kMaxEncapsulationData;

class TcpMessageAssembler {
 public:
  struct PushResult {
    std::size_t consumed = 0;    // bytes taken from the input
    bool message_ready = false;  // a whole message is waiting: read it, then call Next()
  };

  // Takes bytes until one message is complete or the input is used up. While a message is ready,
  // takes nothing.
  PushResult Push(std::span<const std::uint8_t> bytes);

  // Valid while a message is ready.
  const EncapsulationHeader& header() const { return header_; }
  std::span<const std::uint8_t> body() const;
  bool oversized() const { return state_ == State::kReady && oversized_; }

  // Drops the delivered message; the next Push starts a new one.
  void Next();
  // Drops everything (the connection was reused).
  void Reset() { Next(); }

 private:
  enum class State : std::uint8_t { kHeader, kBody, kDiscard, kReady };

  std::size_t TakeHeader(std::span<const std::uint8_t> bytes);
  std::size_t TakeBody(std::span<const std::uint8_t> bytes);
  std::size_t TakeDiscard(std::span<const std::uint8_t> bytes);

  std::array<std::uint8_t, kMaxEncapsulationMessage> buffer_{};
  std::size_t filled_ = 0;
  std::size_t discard_left_ = 0;
  EncapsulationHeader header_;
  State state_ = State::kHeader;
  bool oversized_ = false;
};

}  // namespace cip
