#include "net/acd.h"

#include <algorithm>

namespace net {

// ---- Attributes 10 and 11 ------------------------------------------------------------------------

void EncodeLastConflictDetected(const AcdConflictRecord& record,
                                std::span<std::uint8_t, kLastConflictDetectedSize> out) {
  // 35 bytes into 35: cannot fail.
  base::ByteWriter writer(out);
  writer.U8(static_cast<std::uint8_t>(record.activity));
  record.remote_mac.Write(writer);
  writer.Bytes(record.arp_pdu);
}

base::Result<AcdConflictRecord> DecodeLastConflictDetected(std::span<const std::uint8_t> bytes) {
  if (bytes.size() != kLastConflictDetectedSize) return base::OutOfRange();
  base::ByteReader reader(bytes);
  const std::uint8_t activity = reader.U8();
  if (activity > static_cast<std::uint8_t>(AcdActivity::kSemiActiveProbe)) return base::InvalidArgument();
  AcdConflictRecord record;
  record.activity = static_cast<AcdActivity>(activity);
  record.remote_mac = base::MacAddress::Read(reader);
  const std::span<const std::uint8_t> pdu = reader.Bytes(kArpPduSize);
  std::copy(pdu.begin(), pdu.end(), record.arp_pdu.begin());
  return record;
}

base::Result<bool> DecodeSelectAcd(std::span<const std::uint8_t> bytes) {
  if (bytes.size() != 1) return base::OutOfRange();
  if (bytes[0] > 1) return base::InvalidArgument();
  return bytes[0] == 1;
}

// ---- State machine -------------------------------------------------------------------------------

Acd::Acd(const base::MacAddress& own_mac, const AcdTimings& timings, hal::RandomSource& random, ArpSink& sink)
    : own_mac_(own_mac), timings_(timings), random_(random), sink_(sink) {}

void Acd::Start(base::Ipv4Address address, hal::Micros now) {
  address_ = address;
  duplicate_ = false;
  EnterProbing(now);
}

void Acd::Claim(base::Ipv4Address address, hal::Micros now) {
  address_ = address;
  duplicate_ = false;
  state_ = AcdState::kAnnouncing;
  probes_sent_ = 0;
  announcements_sent_ = 0;
  semi_active_left_ = 0;
  semi_active_ = false;
  last_conflict_at_.reset();
  deadline_ = now;
}

void Acd::Stop() {
  state_ = AcdState::kIdle;
  deadline_ = hal::kNever;
  semi_active_left_ = 0;
  semi_active_ = false;
}

void Acd::LinkUp(hal::Micros now) {
  // Only an address in steady use is re-checked: probing and announcing are checks already, and a
  // yielded address comes back through the retry.
  if (state_ != AcdState::kOngoing || timings_.semi_active_probe_num == 0) return;
  semi_active_ = true;
  semi_active_left_ = timings_.semi_active_probe_num;
  // The first probe waits one interval too: a link that has just come up may not pass frames yet.
  deadline_ = now + timings_.semi_active_probe_interval;
}

AcdEvent Acd::OnFrame(std::span<const std::uint8_t> frame, hal::Micros now) {
  const base::Result<ArpPacket> parsed = ParseArpFrame(frame);
  if (!parsed.ok()) return AcdEvent::kNone;
  const ArpPacket& packet = parsed.value();
  // Our own broadcast coming back (the switch, a tap) says nothing about other hosts (RFC 5227 §2.1.1).
  if (packet.sender_mac == own_mac_) return AcdEvent::kNone;

  switch (state_) {
    case AcdState::kProbing: {
      const bool claims = packet.sender_ip == address_;
      const bool probes_too = packet.operation == ArpOperation::kRequest && packet.sender_ip.IsUnspecified() &&
                              packet.target_ip == address_;
      if (!claims && !probes_too) return AcdEvent::kNone;
      Record(AcdActivity::kProbeIpv4Address, packet, frame);
      EnterConflict(now);
      return AcdEvent::kProbeConflict;
    }
    case AcdState::kAnnouncing:
    case AcdState::kOngoing: {
      // Another host probing for our address (sender IP 0) is not a conflict: lwIP's ARP reply, sent
      // because the address is installed, is what tells it the address is taken.
      if (packet.sender_ip != address_) return AcdEvent::kNone;
      Record(semi_active_ ? AcdActivity::kSemiActiveProbe : AcdActivity::kOngoingDetection, packet, frame);
      const bool recent = last_conflict_at_.has_value() && now < *last_conflict_at_ + timings_.defend_interval;
      if (!recent) {
        // RFC 5227 §2.4 (b): remember when, and defend with one announcement.
        last_conflict_at_ = now;
        Send(ArpAnnouncement(own_mac_, address_));
        return AcdEvent::kDefended;
      }
      EnterConflict(now);
      return AcdEvent::kYielded;
    }
    case AcdState::kIdle:
    case AcdState::kConflict:
      return AcdEvent::kNone;
  }
  return AcdEvent::kNone;
}

void Acd::Poll(hal::Micros now) {
  if (deadline_ == hal::kNever || now < deadline_) return;
  switch (state_) {
    case AcdState::kProbing:
      PollProbing(now);
      return;
    case AcdState::kAnnouncing:
      PollAnnouncing(now);
      return;
    case AcdState::kOngoing:
      PollOngoing(now);
      return;
    case AcdState::kConflict:
      EnterProbing(now);  // the retry: is the other host still there?
      return;
    case AcdState::kIdle:
      deadline_ = hal::kNever;
      return;
  }
}

void Acd::EnterProbing(hal::Micros now) {
  state_ = AcdState::kProbing;
  probes_sent_ = 0;
  announcements_sent_ = 0;
  semi_active_left_ = 0;
  semi_active_ = false;
  last_conflict_at_.reset();
  deadline_ = now + Random(timings_.probe_wait_min, timings_.probe_wait_max);
}

void Acd::EnterConflict(hal::Micros now) {
  state_ = AcdState::kConflict;
  duplicate_ = true;
  semi_active_left_ = 0;
  semi_active_ = false;
  deadline_ = timings_.retry_interval == 0 ? hal::kNever : now + timings_.retry_interval;
}

void Acd::PollProbing(hal::Micros now) {
  if (probes_sent_ < timings_.probe_num) {
    Send(ArpProbe(own_mac_, address_));
    ++probes_sent_;
    deadline_ = now + (probes_sent_ < timings_.probe_num ? Random(timings_.probe_min, timings_.probe_max)
                                                          : timings_.announce_wait);
    return;
  }
  // ANNOUNCE_WAIT after the last probe went by without a conflict: the address is ours (§2.1.1).
  state_ = AcdState::kAnnouncing;
  duplicate_ = false;
  PollAnnouncing(now);
}

void Acd::PollAnnouncing(hal::Micros now) {
  if (announcements_sent_ < timings_.announce_num) {
    Send(ArpAnnouncement(own_mac_, address_));
    ++announcements_sent_;
    if (announcements_sent_ < timings_.announce_num) {
      deadline_ = now + timings_.announce_interval;
      return;
    }
  }
  state_ = AcdState::kOngoing;
  ScheduleOngoing(now);
}

void Acd::PollOngoing(hal::Micros now) {
  if (semi_active_left_ > 0) {
    Send(ArpProbe(own_mac_, address_));
    --semi_active_left_;
    // The next probe of the burst, or after the last one the window in which its answer still counts
    // as a semi-active conflict.
    deadline_ = now + timings_.semi_active_probe_interval;
    return;
  }
  if (semi_active_) {
    semi_active_ = false;
    ScheduleOngoing(now);
    return;
  }
  Send(ArpProbe(own_mac_, address_));
  ScheduleOngoing(now);
}

void Acd::ScheduleOngoing(hal::Micros now) {
  deadline_ = timings_.ongoing_probe_min == 0
                  ? hal::kNever
                  : now + Random(timings_.ongoing_probe_min, timings_.ongoing_probe_max);
}

void Acd::Send(const ArpPacket& packet) {
  const ArpFrame frame = EncodeArpFrame(packet);
  sink_.SendArp(frame);
}

void Acd::Record(AcdActivity activity, const ArpPacket& packet, std::span<const std::uint8_t> frame) {
  last_conflict_.activity = activity;
  last_conflict_.remote_mac = packet.sender_mac;
  // ParseArpFrame accepted the frame, so its first 42 bytes exist.
  const std::span<const std::uint8_t> pdu = frame.subspan(kEthernetHeaderSize, kArpPduSize);
  std::copy(pdu.begin(), pdu.end(), last_conflict_.arp_pdu.begin());
}

hal::Micros Acd::Random(hal::Micros min, hal::Micros max) {
  if (max <= min) return min;
  // Every range in use is far below 2^32 µs (71 min), so one 32-bit draw covers it; the modulo bias is
  // immaterial for spreading ARP traffic.
  return min + static_cast<hal::Micros>(random_.NextU32()) % (max - min + 1);
}

}  // namespace net
