// Capture decorator for any hal::FramePort: forwards every call to the inner port and records each frame
// received and each frame successfully transmitted to a pcap file (both ports into one file, in the
// order the firmware saw them). Frames the inner port refused (link down, queue full) never went on the
// wire and are not recorded. A failing capture file never affects traffic.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>

#include "base/status.h"
#include "hal/frame_port.h"
#include "pcap_writer.h"

namespace hal::host {

class CapturingFramePort final : public FramePort {
 public:
  // Stamps records with `now` (µs since the Unix epoch; wall clock by default, see pcap_writer.h).
  // `inner` and `writer` must outlive this object.
  CapturingFramePort(FramePort& inner, PcapWriter& writer,
                     std::function<Micros()> now = WallClockMicros);

  base::MacAddress Mac() const override { return inner_.Mac(); }
  std::size_t PortCount() const override { return inner_.PortCount(); }
  LinkState Link(PortId port) const override { return inner_.Link(port); }
  PortCounters Counters(PortId port) const override { return inner_.Counters(port); }
  base::Result<ReceivedFrame> Receive(std::span<std::uint8_t> buffer) override;
  base::Status Transmit(PortId port, std::span<const std::uint8_t> frame) override;
  base::Status JoinMulticast(const base::MacAddress& group) override { return inner_.JoinMulticast(group); }
  base::Status LeaveMulticast(const base::MacAddress& group) override { return inner_.LeaveMulticast(group); }

  // Records that could not be written to the capture file.
  std::size_t capture_errors() const { return capture_errors_; }

 private:
  void Capture(std::span<const std::uint8_t> frame);

  FramePort& inner_;
  PcapWriter& writer_;
  std::function<Micros()> now_;
  std::size_t capture_errors_ = 0;
};

}  // namespace hal::host
