// A hal::FramePort held entirely in memory: tests push frames in and read what the card sent.
#pragma once

#include <algorithm>
#include <cstdint>
#include <deque>
#include <vector>

#include "hal/frame_port.h"

namespace hal::test {

class FakeFramePort final : public FramePort {
 public:
  struct Sent {
    PortId port;
    std::vector<std::uint8_t> bytes;
  };

  explicit FakeFramePort(base::MacAddress mac, std::size_t ports = 1) : mac_(mac), ports_(ports) {
    for (auto& link : links_) link = LinkState{true, LinkSpeed::k100Mbps, true, true};
  }

  base::MacAddress Mac() const override { return mac_; }
  std::size_t PortCount() const override { return ports_; }
  LinkState Link(PortId port) const override { return links_[PortIndex(port)]; }
  PortCounters Counters(PortId) const override { return {}; }

  base::Result<ReceivedFrame> Receive(std::span<std::uint8_t> buffer) override {
    if (inbox_.empty()) return base::Unavailable();
    Sent frame = std::move(inbox_.front());
    inbox_.pop_front();
    if (frame.bytes.size() > buffer.size()) return base::OutOfRange();
    std::copy(frame.bytes.begin(), frame.bytes.end(), buffer.begin());
    return ReceivedFrame{frame.bytes.size(), frame.port};
  }

  base::Status Transmit(PortId port, std::span<const std::uint8_t> frame) override {
    if (!links_[PortIndex(port)].up) return base::FailedPrecondition();
    sent_.push_back(Sent{port, std::vector<std::uint8_t>(frame.begin(), frame.end())});
    return base::OkStatus();
  }

  base::Status JoinMulticast(const base::MacAddress& group) override {
    joined_.push_back(group);
    return base::OkStatus();
  }
  base::Status LeaveMulticast(const base::MacAddress& group) override {
    const auto found = std::find(joined_.begin(), joined_.end(), group);
    if (found == joined_.end()) return base::NotFound();
    joined_.erase(found);
    return base::OkStatus();
  }
  // The multicast groups joined and not left, in the order joined (a group joined twice is there twice).
  const std::vector<base::MacAddress>& joined() const { return joined_; }

  void Inject(std::vector<std::uint8_t> frame, PortId port = PortId::kLeft) {
    inbox_.push_back(Sent{port, std::move(frame)});
  }
  void SetLink(PortId port, bool up) { links_[PortIndex(port)].up = up; }
  void SetSpeed(PortId port, LinkSpeed speed) { links_[PortIndex(port)].speed = speed; }
  std::vector<Sent>& sent() { return sent_; }
  std::size_t pending() const { return inbox_.size(); }

 private:
  base::MacAddress mac_;
  std::size_t ports_;
  LinkState links_[kMaxPorts];
  std::deque<Sent> inbox_;
  std::vector<Sent> sent_;
  std::vector<base::MacAddress> joined_;
};

}  // namespace hal::test
