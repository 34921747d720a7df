// StreamFramer: cuts the received byte stream into frames the way the inverter's receiver does (p.6-7).
#include "drive_link/wire/toshiba_frame.h"
#include "toshiba_internal.h"

namespace drive_link::wire {
namespace {

// Index of the first position where an ASCII frame's CR may stand: after "(", the optional 2-character
// inverter number, the letter and the 4-character field. A CR before it is a field character (p.21:
// "(R11)CR" takes "11)CR" as the communication number and keeps waiting for the CR).
std::size_t FirstAsciiEndIndex(std::span<const std::uint8_t> partial) {
  constexpr std::size_t kWithoutNumber = 1 + 1 + 4;
  const bool has_number = partial.size() > 1 && (internal::IsDecimalDigit(partial[1]) || partial[1] == '*');
  return has_number ? kWithoutNumber + 2 : kWithoutNumber;
}

}  // namespace

StreamFramer::FeedResult StreamFramer::Feed(std::span<const std::uint8_t> bytes) {
  if (state_ == State::kReady) {
    state_ = State::kHunting;
    length_ = 0;
  }
  for (std::size_t i = 0; i < bytes.size(); ++i) {
    Step(bytes[i]);
    if (state_ == State::kReady) {
      ++counters_.frames;
      return {.consumed = i + 1, .frame_ready = true};
    }
  }
  return {.consumed = bytes.size(), .frame_ready = false};
}

std::span<const std::uint8_t> StreamFramer::frame() const {
  if (state_ != State::kReady) return {};
  return std::span<const std::uint8_t>(buffer_).first(length_);
}

void StreamFramer::GapElapsed() {
  if (state_ == State::kAscii || state_ == State::kBinary) ++counters_.dropped_frames;
  state_ = State::kHunting;
  length_ = 0;
}

void StreamFramer::Reset() {
  state_ = State::kHunting;
  length_ = 0;
  expected_ = 0;
}

void StreamFramer::Step(std::uint8_t byte) {
  switch (state_) {
    case State::kHunting:
    case State::kReady:
      Hunt(byte);
      return;
    case State::kAscii:
      StepAscii(byte);
      return;
    case State::kBinary:
      StepBinary(byte);
      return;
  }
}

// Everything before a start code is ignored (p.6).
void StreamFramer::Hunt(std::uint8_t byte) {
  if (byte == kAsciiStartCode) {
    Start(byte, State::kAscii);
  } else if (byte == kBinaryStartCode) {
    Start(byte, State::kBinary);
  } else {
    ++counters_.garbage_bytes;
  }
}

void StreamFramer::Start(std::uint8_t byte, State state) {
  state_ = state;
  buffer_[0] = byte;
  length_ = 1;
  expected_ = 0;
}

void StreamFramer::Drop() {
  ++counters_.dropped_frames;
  state_ = State::kHunting;
  length_ = 0;
}

void StreamFramer::StepAscii(std::uint8_t byte) {
  if (byte == kAsciiStartCode) {  // "the '(' entered last will be valid" (p.6)
    ++counters_.dropped_frames;
    Start(byte, State::kAscii);
    return;
  }
  buffer_[length_++] = byte;
  if (byte == kCarriageReturn && length_ - 1 >= FirstAsciiEndIndex(std::span(buffer_).first(length_))) {
    state_ = State::kReady;
  } else if (length_ == buffer_.size()) {
    // Over 17 bytes without the CR: a transmission error (p.6). The byte may start the next frame.
    Drop();
    Hunt(byte);
  }
}

void StreamFramer::StepBinary(std::uint8_t byte) {
  buffer_[length_++] = byte;
  if (expected_ != 0) {
    if (length_ == expected_) state_ = State::kReady;
    return;
  }
  const std::size_t index = length_ - 1;
  if (index == 1 && internal::IsBinaryAddressByte(direction_, byte)) return;  // inverter number
  const std::size_t command_index = internal::IsBinaryAddressByte(direction_, buffer_[1]) ? 2 : 1;
  if (index == command_index && byte == kBinaryStartCode) {  // "the 2FH entered last" (p.7)
    ++counters_.dropped_frames;
    Start(byte, State::kBinary);
    return;
  }
  bool impossible = false;
  expected_ = BinaryLengthFrom(command_index, impossible);
  if (impossible) {
    // Unknown command or block count out of range: nothing to wait for. The byte may start a frame.
    Drop();
    Hunt(byte);
  } else if (expected_ != 0 && length_ == expected_) {
    state_ = State::kReady;
  }
}

// Total length of the binary frame in the buffer once its command (and a block frame's count) are in;
// 0 while they are not. `impossible` when no frame can follow this header.
std::size_t StreamFramer::BinaryLengthFrom(std::size_t command_index, bool& impossible) const {
  const std::size_t tail = internal::BinaryTailLength(direction_, buffer_[command_index]);
  if (tail == 0) {
    impossible = true;
    return 0;
  }
  if (tail != internal::kBlockTail) return command_index + 1 + tail;
  // Block count: write groups in a request (5 in LED mode), read groups in a reply.
  const std::size_t count_index = command_index + 1;
  if (length_ <= count_index) return 0;
  const std::uint8_t count = buffer_[count_index];
  const std::size_t limit = direction_ == Direction::kRequests ? kMaxLedBlockWrites : kMaxBlockReads;
  if (count > limit) {
    impossible = true;
    return 0;
  }
  return command_index + 1 + internal::BlockTailLength(count);
}

}  // namespace drive_link::wire
