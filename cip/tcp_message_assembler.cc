#include "cip/tcp_message_assembler.h"

#include <algorithm>

namespace cip {

TcpMessageAssembler::PushResult TcpMessageAssembler::Push(std::span<const std::uint8_t> bytes) {
  PushResult result;
  while (state_ != State::kReady && result.consumed < bytes.size()) {
    const std::span<const std::uint8_t> rest = bytes.subspan(result.consumed);
    switch (state_) {
      case State::kHeader:
        result.consumed += TakeHeader(rest);
        break;
      case State::kBody:
        result.consumed += TakeBody(rest);
        break;
      case State::kDiscard:
        result.consumed += TakeDiscard(rest);
        break;
      case State::kReady:
        break;
    }
  }
  result.message_ready = state_ == State::kReady;
  return result;
}

std::size_t TcpMessageAssembler::TakeHeader(std::span<const std::uint8_t> bytes) {
  const std::size_t take = std::min(kEncapsulationHeaderSize - filled_, bytes.size());
  std::copy_n(bytes.begin(), take, buffer_.begin() + static_cast<std::ptrdiff_t>(filled_));
  filled_ += take;
  if (filled_ < kEncapsulationHeaderSize) return take;
  // 24 bytes are present, so decoding cannot fail.
  header_ = DecodeEncapsulationHeader(std::span<const std::uint8_t>(buffer_).first(filled_)).value();
  if (header_.length > kMaxEncapsulationData) {
    oversized_ = true;
    discard_left_ = header_.length;
    state_ = State::kDiscard;
  } else {
    state_ = header_.length == 0 ? State::kReady : State::kBody;
  }
  return take;
}

std::size_t TcpMessageAssembler::TakeBody(std::span<const std::uint8_t> bytes) {
  const std::size_t total = kEncapsulationHeaderSize + header_.length;
  const std::size_t take = std::min(total - filled_, bytes.size());
  std::copy_n(bytes.begin(), take, buffer_.begin() + static_cast<std::ptrdiff_t>(filled_));
  filled_ += take;
  if (filled_ == total) state_ = State::kReady;
  return take;
}

std::size_t TcpMessageAssembler::TakeDiscard(std::span<const std::uint8_t> bytes) {
  const std::size_t take = std::min(discard_left_, bytes.size());
  discard_left_ -= take;
  if (discard_left_ == 0) state_ = State::kReady;
  return take;
}

std::span<const std::uint8_t> TcpMessageAssembler::body() const {
  if (state_ != State::kReady || oversized_) return {};
  return std::span<const std::uint8_t>(buffer_).subspan(kEncapsulationHeaderSize, header_.length);
}

void TcpMessageAssembler::Next() {
  filled_ = 0;
  discard_left_ = 0;
  header_ = EncapsulationHeader{};
  state_ = State::kHeader;
  oversized_ = false;
}

}  // namespace cip
