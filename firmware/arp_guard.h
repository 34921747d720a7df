// What the card lets into its ARP cache (docs/security.md "ARP"). lwIP 2.1.3 learns the sender of every
// ARP request or reply addressed to the card, recycling the oldest entry when its table is full
// (etharp_input: ETHARP_FLAG_TRY_HARD). A stream of requests from ever-new senders therefore evicts the
// entries of the card's real peers, and every T->O datagram to a PLC then waits for a new ARP exchange
// that lwIP repeats only once a second: class 1 production stops (integration.hostile_eip measured gaps of
// up to 1 s at RPI 10 ms). The guard sits in front of lwIP (CardNetif) and decides per received ARP frame:
//
//   request or reply for the card's address from a sender in
//     the cache or asked for by the card in the last kAwaitMs  -> lwIP (answers, completes or refreshes)
//   request for the card's address from anybody else          -> answered here, nothing learned
//   reply for the card's address from anybody else            -> dropped (unsolicited)
//   sender address 0.0.0.0 or the card's own (ACD probes and
//     conflicts), or another target (gratuitous ARP, requests
//     for other hosts: lwIP only updates entries it has)        -> lwIP
//
// So the cache holds only hosts the card itself has talked to: lwIP adds an entry when it sends to a host
// (etharp_query), which a host that asked for the card does at once when it opens a connection (one extra
// ARP exchange on its first packet). Frames are read and written with net/arp.h's codec. Device-path code:
// no lwIP here, fixed-size state.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "net/arp.h"

namespace firmware {

// The ARP cache as the guard asks it (CardNetif: lwIP's etharp_find_addr, stable entries).
class ArpCacheQuery {
 public:
  virtual ~ArpCacheQuery() = default;
  virtual bool Has(base::Ipv4Address address) const = 0;
};

struct ArpGuardCounters {
  std::uint64_t answered = 0;  // requests from senders not in the cache, answered by the guard
  std::uint64_t dropped = 0;   // replies nobody asked for
};

class ArpGuard {
 public:
  // How long a reply to a request of the card is awaited (lwIP's ARP_MAXPENDING, 5 timer ticks of 1 s).
  static constexpr std::uint32_t kAwaitMs = 5000;
  // Addresses the card may be waiting for at once; beyond, the oldest is forgotten (its reply is then
  // dropped, and lwIP asks again a second later).
  static constexpr std::size_t kMaxAwaited = 8;

  enum class Verdict : std::uint8_t {
    kPass,    // hand the frame to lwIP
    kAnswer,  // send reply() instead, do not hand the frame to lwIP
    kDrop,    // neither
  };

  // The card's own addresses (address 0.0.0.0 while it has none: every ARP frame passes).
  void SetIdentity(const base::MacAddress& mac, base::Ipv4Address address);

  // A received frame (any type: frames other than ARP for IPv4 over Ethernet pass). Times are lwIP's
  // sys_now() milliseconds, compared modulo 2^32 (the clock wraps after 49 days).
  Verdict Inspect(std::span<const std::uint8_t> frame, const ArpCacheQuery& cache, std::uint32_t now_ms);
  // The answer of the last kAnswer verdict (net::kArpFrameSize bytes).
  std::span<const std::uint8_t> reply() const { return reply_; }
  // A frame the card sends: its own ARP requests are remembered as awaited.
  void NoteSent(std::span<const std::uint8_t> frame, std::uint32_t now_ms);

  const ArpGuardCounters& counters() const { return counters_; }

 private:
  struct Awaited {
    base::Ipv4Address address;  // 0.0.0.0: free
    std::uint32_t sent_ms = 0;
  };
  bool IsAwaited(base::Ipv4Address address, std::uint32_t now_ms) const;

  base::MacAddress mac_{};
  base::Ipv4Address address_;
  std::array<Awaited, kMaxAwaited> awaited_{};
  net::ArpFrame reply_{};
  ArpGuardCounters counters_;
};

}  // namespace firmware
