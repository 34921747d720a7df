#include "capturing_frame_port.h"

#include <utility>

namespace hal::host {

CapturingFramePort::CapturingFramePort(FramePort& inner, PcapWriter& writer,
                                       std::function<Micros()> now)
    : inner_(inner), writer_(writer), now_(std::move(now)) {}

base::Result<ReceivedFrame> CapturingFramePort::Receive(std::span<std::uint8_t> buffer) {
  const base::Result<ReceivedFrame> received = inner_.Receive(buffer);
  if (received.ok()) Capture(buffer.first(received->length));
  return received;
}

base::Status CapturingFramePort::Transmit(PortId port, std::span<const std::uint8_t> frame) {
  const base::Status status = inner_.Transmit(port, frame);
  if (status.ok()) Capture(frame);
  return status;
}

void CapturingFramePort::Capture(std::span<const std::uint8_t> frame) {
  if (!writer_.Write(frame, now_()).ok()) ++capture_errors_;
}

}  // namespace hal::host
