// IPv4 Address Conflict Detection (RFC 5227, with the EtherNet/IP timings of CIP Vol 2 Appendix F;
// NET-4, docs/network.md "Address Conflict Detection"): a pure state machine over ARP frames and time.
//
//   Start(address) ──> kProbing ──(no conflict)──> kAnnouncing ──> kOngoing
//                         │                              │              │ 1st conflict: defend (one
//                         │ conflict                     │ 2nd conflict │ announcement); 2nd within
//                         v                              v   within     │ DEFEND_INTERVAL: yield
//                      kConflict <──────────────────────────────────────┘
//                         └── after retry_interval: probe again (the other host may have left)
//
// kProbing: PROBE_WAIT (random), then PROBE_NUM ARP probes PROBE_MIN..PROBE_MAX apart, then
//   ANNOUNCE_WAIT. A conflict is any ARP packet from another MAC whose sender IP is the address, or an
//   ARP probe from another MAC for the same address (someone else probing for it right now) (§2.1.1).
//   The address must not be used in this state.
// kAnnouncing: the address is ours: ANNOUNCE_NUM announcements ANNOUNCE_INTERVAL apart (§2.3).
// kOngoing (and kAnnouncing): a conflict is an ARP packet from another MAC whose sender IP is ours
//   (§2.4). Policy (b): defend once with an announcement; a second conflict within DEFEND_INTERVAL of
//   the first makes the card stop using the address (kConflict). EtherNet/IP adds periodic ongoing
//   probes (random ONGOING_PROBE_MIN..MAX apart) and, when a port's link comes up while the address is
//   in use, a "semi-active" burst of probes (LinkUp).
// kConflict: the address is not used; after retry_interval the card probes for it again.
//
// Frames from our own MAC (a switch or a tap reflecting our broadcast) are never conflicts. The ACD only
// reads frames; it does not consume them (lwIP still gets every ARP frame).
//
// Not here: when to install the address in lwIP (AddressUsable()), the LEDs (DuplicateDetected()),
// persistence of attribute 11: the wiring's.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>

#include "base/status.h"
#include "hal/clock.h"
#include "hal/random.h"
#include "net/arp.h"
#include "base/addresses.h"

namespace net {

// ---- TCP/IP Interface attributes 10 and 11 (CIP Vol 2 §5-4.3.2) ---------------------------------

// LastConflictDetected.AcdActivity: the state ACD was in when it saw the last conflict.
enum class AcdActivity : std::uint8_t {
  kNoConflictDetected = 0,
  kProbeIpv4Address = 1,
  kOngoingDetection = 2,  // kOngoing, and the defence that follows
  kSemiActiveProbe = 3,   // during a link-up probe burst, and the defence that follows
};

// Attribute 11 LastConflictDetected: STRUCT of AcdActivity USINT, RemoteMAC USINT[6] (the ARP sender
// hardware address of the conflicting packet), ArpPdu USINT[28] (that packet's ARP PDU, verbatim, in
// network byte order). 35 bytes; all zeros = no conflict since the attribute was last cleared.
struct AcdConflictRecord {
  AcdActivity activity = AcdActivity::kNoConflictDetected;
  base::MacAddress remote_mac{};
  std::array<std::uint8_t, kArpPduSize> arp_pdu{};

  bool operator==(const AcdConflictRecord&) const = default;
};

inline constexpr std::size_t kLastConflictDetectedSize = 1 + 6 + kArpPduSize;  // 35

void EncodeLastConflictDetected(const AcdConflictRecord& record,
                                std::span<std::uint8_t, kLastConflictDetectedSize> out);
// Exactly 35 bytes with an activity of 0..3, else kOutOfRange (length) / kInvalidArgument (activity).
base::Result<AcdConflictRecord> DecodeLastConflictDetected(std::span<const std::uint8_t> bytes);

// Attribute 10 SelectAcd: BOOL, one byte, 0 (ACD off) or 1 (on, the CIP default). Anything else:
// kOutOfRange (length) / kInvalidArgument (value).
base::Result<bool> DecodeSelectAcd(std::span<const std::uint8_t> bytes);
constexpr std::uint8_t EncodeSelectAcd(bool select) { return select ? 1 : 0; }

// ---- Timings -------------------------------------------------------------------------------------

struct AcdTimings {
  hal::Micros probe_wait_min;  // first probe after a random wait in [min, max] (PROBE_WAIT)
  hal::Micros probe_wait_max;
  std::uint8_t probe_num;  // PROBE_NUM
  hal::Micros probe_min;   // between probes (PROBE_MIN..PROBE_MAX)
  hal::Micros probe_max;
  hal::Micros announce_wait;  // last probe to first announcement (ANNOUNCE_WAIT)
  std::uint8_t announce_num;  // ANNOUNCE_NUM
  hal::Micros announce_interval;
  hal::Micros defend_interval;    // DEFEND_INTERVAL
  hal::Micros ongoing_probe_min;  // 0: no ongoing probes (RFC 5227)
  hal::Micros ongoing_probe_max;
  std::uint8_t semi_active_probe_num;  // 0: LinkUp does nothing
  hal::Micros semi_active_probe_interval;
  hal::Micros retry_interval;  // kConflict -> probe again; 0: never
};

// RFC 5227 §1.1; retry after RATE_LIMIT_INTERVAL (60 s).
inline constexpr AcdTimings kRfc5227Timings{
    .probe_wait_min = 0,
    .probe_wait_max = 1 * hal::kMicrosPerSecond,
    .probe_num = 3,
    .probe_min = 1 * hal::kMicrosPerSecond,
    .probe_max = 2 * hal::kMicrosPerSecond,
    .announce_wait = 2 * hal::kMicrosPerSecond,
    .announce_num = 2,
    .announce_interval = 2 * hal::kMicrosPerSecond,
    .defend_interval = 10 * hal::kMicrosPerSecond,
    .ongoing_probe_min = 0,
    .ongoing_probe_max = 0,
    .semi_active_probe_num = 0,
    .semi_active_probe_interval = 0,
    .retry_interval = 60 * hal::kMicrosPerSecond,
};

// EtherNet/IP (CIP Vol 2 Appendix F, as published implementations of it state; docs/network.md):
// 200 ms probe wait and spacing, 4 probes, 200 ms announce wait, ongoing probes 90-150 s apart, two
// semi-active probes 200 ms apart. DEFEND_INTERVAL stays at RFC 5227's 10 s (see docs/network.md).
inline constexpr AcdTimings kEtherNetIpTimings{
    .probe_wait_min = 0,
    .probe_wait_max = 200 * hal::kMicrosPerMilli,
    .probe_num = 4,
    .probe_min = 200 * hal::kMicrosPerMilli,
    .probe_max = 200 * hal::kMicrosPerMilli,
    .announce_wait = 200 * hal::kMicrosPerMilli,
    .announce_num = 2,
    .announce_interval = 2 * hal::kMicrosPerSecond,
    .defend_interval = 10 * hal::kMicrosPerSecond,
    .ongoing_probe_min = 90 * hal::kMicrosPerSecond,
    .ongoing_probe_max = 150 * hal::kMicrosPerSecond,
    .semi_active_probe_num = 2,
    .semi_active_probe_interval = 200 * hal::kMicrosPerMilli,
    .retry_interval = 60 * hal::kMicrosPerSecond,
};

// ---- The state machine ---------------------------------------------------------------------------

// Where ACD's frames go (on the card: out of every port with link). Called from Poll and OnFrame.
class ArpSink {
 public:
  virtual ~ArpSink() = default;
  virtual void SendArp(std::span<const std::uint8_t, kArpFrameSize> frame) = 0;
};

enum class AcdState : std::uint8_t { kIdle, kProbing, kAnnouncing, kOngoing, kConflict };

// What a received frame did.
enum class AcdEvent : std::uint8_t {
  kNone,           // not ARP, malformed, ours, or no conflict
  kProbeConflict,  // the address is in use: it is not taken (kProbing -> kConflict)
  kDefended,       // a conflict while using the address: one announcement sent, address kept
  kYielded,        // a second conflict within DEFEND_INTERVAL: the address must go (-> kConflict)
};

class Acd {
 public:
  Acd(const base::MacAddress& own_mac, const AcdTimings& timings, hal::RandomSource& random, ArpSink& sink);

  // Starts probing for `address` (manual, BOOTP or DHCP); forgets any earlier conflict state except
  // LastConflict(). The first probe goes out from Poll after the probe wait.
  void Start(base::Ipv4Address address, hal::Micros now);
  // Takes `address` without probing (kAnnouncing from `now`): for an address another check has already
  // probed (lwIP's DHCP client ARP-checks an offered address before binding it). Ongoing detection and
  // the defence then run as after a probe.
  void Claim(base::Ipv4Address address, hal::Micros now);
  // Back to kIdle (communication reset, address change): nothing more is sent.
  void Stop();
  // A port's link came up. While the address is in use, starts a semi-active probe burst.
  void LinkUp(hal::Micros now);

  // Reads a received Ethernet frame (any kind: non-ARP frames are ignored).
  AcdEvent OnFrame(std::span<const std::uint8_t> frame, hal::Micros now);
  // Sends what is due at `now`: at most one frame per call; the next is scheduled from `now`, so a late
  // call never produces a burst.
  void Poll(hal::Micros now);
  hal::Micros NextDeadline() const { return deadline_; }

  AcdState State() const { return state_; }
  base::Ipv4Address Address() const { return address_; }
  // The address may be installed and used: kAnnouncing or kOngoing.
  bool AddressUsable() const { return state_ == AcdState::kAnnouncing || state_ == AcdState::kOngoing; }
  // A conflict made the card refuse or give up the address, and it has not claimed it back since
  // (true in kConflict and while re-probing from it): the "duplicate IP" indication.
  bool DuplicateDetected() const { return duplicate_; }

  const AcdConflictRecord& LastConflict() const { return last_conflict_; }
  void ClearLastConflict() { last_conflict_ = AcdConflictRecord{}; }

 private:
  void EnterProbing(hal::Micros now);
  void EnterConflict(hal::Micros now);
  void PollProbing(hal::Micros now);
  void PollAnnouncing(hal::Micros now);
  void PollOngoing(hal::Micros now);
  void ScheduleOngoing(hal::Micros now);
  void Send(const ArpPacket& packet);
  void Record(AcdActivity activity, const ArpPacket& packet, std::span<const std::uint8_t> frame);
  hal::Micros Random(hal::Micros min, hal::Micros max);

  base::MacAddress own_mac_;
  AcdTimings timings_;
  hal::RandomSource& random_;
  ArpSink& sink_;

  AcdState state_ = AcdState::kIdle;
  base::Ipv4Address address_;
  hal::Micros deadline_ = hal::kNever;
  std::uint8_t probes_sent_ = 0;
  std::uint8_t announcements_sent_ = 0;
  std::uint8_t semi_active_left_ = 0;
  bool semi_active_ = false;  // a semi-active burst runs (until one interval after its last probe)
  std::optional<hal::Micros> last_conflict_at_;  // for DEFEND_INTERVAL
  bool duplicate_ = false;
  AcdConflictRecord last_conflict_{};
};

}  // namespace net
