// libFuzzer target for ARP parsing and Address Conflict Detection (net/arp.h, net/acd.h).
// The input is a script of records: one byte kind, two bytes of time step in ms, then for a frame one
// length byte and that many bytes (the time advances, as lwIP's fuzzer feeds time from the input).
// Kinds: 0 frame, 1 poll, 2 link up, 3 start, 4 stop, 5 clear attribute 11; the rest: poll.
// Oracles: nothing is read outside a frame (ASan); a parsed frame re-encodes to its first 42 bytes;
// every frame ACD sends is a broadcast ARP request from our MAC for our address, with sender IP 0 (probe)
// or our address (announcement); announcements only while the address is usable; attribute 11
// round-trips through its 35 bytes; a deadline never lies before the poll that set it.
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "hal/random.h"
#include "net/acd.h"
#include "net/arp.h"

namespace {

void Require(bool condition) {
  if (!condition) __builtin_trap();
}

constexpr base::MacAddress kOwnMac = {0x00, 0x00, 0x5E, 0x00, 0x53, 0x01};
constexpr base::Ipv4Address kAddress(0xC000020Au);

class CountingRandom final : public hal::RandomSource {
 public:
  void Fill(std::span<std::uint8_t> out) override {
    for (auto& byte : out) byte = static_cast<std::uint8_t>(next_ += 0x9D);
  }

 private:
  std::uint8_t next_ = 0;
};

class CheckingSink final : public net::ArpSink {
 public:
  explicit CheckingSink(const net::Acd*& acd) : acd_(acd) {}
  void SendArp(std::span<const std::uint8_t, net::kArpFrameSize> frame) override {
    const base::Result<net::ArpPacket> packet = net::ParseArpFrame(frame);
    Require(packet.ok());
    Require(packet->destination == base::kBroadcastMac && packet->source == kOwnMac);
    Require(packet->operation == net::ArpOperation::kRequest && packet->sender_mac == kOwnMac);
    Require(packet->target_mac == base::kZeroMac && packet->target_ip == kAddress);
    Require(packet->sender_ip.IsUnspecified() || packet->sender_ip == kAddress);
    // An announcement claims the address: only from a state that may use it (checked after the
    // transition, which happens before the frame is sent).
    if (packet->sender_ip == kAddress) Require(acd_ != nullptr && acd_->AddressUsable());
  }

 private:
  const net::Acd*& acd_;
};

void CheckParse(std::span<const std::uint8_t> frame) {
  const base::Result<net::ArpPacket> packet = net::ParseArpFrame(frame);
  if (!packet.ok()) return;
  const net::ArpFrame again = net::EncodeArpFrame(packet.value());
  for (std::size_t i = 0; i < again.size(); ++i) Require(again[i] == frame[i]);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::span<const std::uint8_t> rest(data, size);
  CheckParse(rest);
  CountingRandom random;
  const net::Acd* observed = nullptr;
  CheckingSink sink(observed);
  net::Acd acd(kOwnMac, net::kEtherNetIpTimings, random, sink);
  observed = &acd;
  hal::Micros now = 0;
  acd.Start(kAddress, now);
  while (rest.size() >= 3) {
    const std::uint8_t kind = rest[0];
    now += static_cast<hal::Micros>(rest[1] << 8 | rest[2]) * hal::kMicrosPerMilli;
    rest = rest.subspan(3);
    switch (kind) {
      case 0: {
        if (rest.empty()) return 0;
        const std::size_t length = rest[0] < rest.size() - 1 ? rest[0] : rest.size() - 1;
        const std::span<const std::uint8_t> frame = rest.subspan(1, length);
        rest = rest.subspan(1 + length);
        CheckParse(frame);
        const net::AcdEvent event = acd.OnFrame(frame, now);
        if (event == net::AcdEvent::kProbeConflict || event == net::AcdEvent::kYielded) {
          Require(acd.State() == net::AcdState::kConflict && !acd.AddressUsable() && acd.DuplicateDetected());
        }
        if (event != net::AcdEvent::kNone) {
          Require(acd.LastConflict().activity != net::AcdActivity::kNoConflictDetected);
        }
        break;
      }
      case 2:
        acd.LinkUp(now);
        break;
      case 3:
        acd.Start(kAddress, now);
        break;
      case 4:
        acd.Stop();
        break;
      case 5:
        acd.ClearLastConflict();
        break;
      default:
        acd.Poll(now);
        Require(acd.NextDeadline() >= now);
        break;
    }
    std::array<std::uint8_t, net::kLastConflictDetectedSize> encoded{};
    net::EncodeLastConflictDetected(acd.LastConflict(), encoded);
    const base::Result<net::AcdConflictRecord> decoded = net::DecodeLastConflictDetected(encoded);
    Require(decoded.ok() && decoded.value() == acd.LastConflict());
  }
  return 0;
}
