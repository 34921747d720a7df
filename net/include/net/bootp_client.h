// The BOOTP client of IP mode c504 = 1 (RFC 951, RFC 1542, vendor extensions RFC 1497/2132; NET-1,
// docs/network.md "BOOTP"). lwIP 2.1.3 has none; this core builds BOOTREQUESTs and reads BOOTREPLYs,
// and the wiring moves them over a raw UDP PCB (port 68 -> 255.255.255.255:67, source 0.0.0.0).
//
// Message (300 bytes as sent; a reply may be longer, with a larger options area):
//   0 op (1 request, 2 reply)  1 htype 1  2 hlen 6  3 hops  4 xid (4)  8 secs (2)  10 flags (2, bit 15
//   broadcast, RFC 1542)  12 ciaddr  16 yiaddr  20 siaddr  24 giaddr  28 chaddr (16)  44 sname (64)
//   108 file (128)  236 vend (64: magic cookie, options, end, zero padding)
//
// Requests: chaddr = the card's MAC (the server knows the card by it), a random xid kept for all
// retransmissions of one Start (so that a late answer to an earlier copy still matches), secs = whole
// seconds since Start, the broadcast flag set (the card cannot take unicast before it has an address:
// RFC 1542 §3.1.1), vend = cookie + end.
// Retransmission (RFC 951 §7.2, with the concrete numbers of RFC 2131 §4.1): 4 s after the first
// request, then 8, 16, 32, 64 s, each randomised by -1..+1 s; 64 s +-1 s from then on. BOOTP mode never
// gives up: the card has no other way to an address.
// Replies: op 2, htype 1, hlen 6, our xid and our MAC in chaddr, a usable unicast yiaddr, and if the
// vendor area carries options, well-formed ones (net/dhcp_options.h). Anything else is ignored.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>

#include "base/status.h"
#include "hal/clock.h"
#include "hal/random.h"
#include "net/dhcp_options.h"
#include "base/addresses.h"

namespace net {

inline constexpr std::uint16_t kBootpServerPort = 67;
inline constexpr std::uint16_t kBootpClientPort = 68;
inline constexpr std::size_t kBootpFixedSize = 236;      // up to the vendor area
inline constexpr std::size_t kBootpVendorSize = 64;      // RFC 951 "vend"
inline constexpr std::size_t kBootpMessageSize = kBootpFixedSize + kBootpVendorSize;  // 300
inline constexpr std::uint16_t kBootpBroadcastFlag = 0x8000;

inline constexpr hal::Micros kBootpFirstRetransmit = 4 * hal::kMicrosPerSecond;
inline constexpr hal::Micros kBootpMaxRetransmit = 64 * hal::kMicrosPerSecond;
inline constexpr hal::Micros kBootpRetransmitJitter = 1 * hal::kMicrosPerSecond;

struct BootRequest {
  base::MacAddress mac{};
  std::uint32_t xid = 0;
  std::uint16_t secs = 0;
  bool broadcast = true;
};

void EncodeBootRequest(const BootRequest& request, std::span<std::uint8_t, kBootpMessageSize> out);

struct BootReply {
  base::Ipv4Address your_address;    // yiaddr
  base::Ipv4Address server_address;  // siaddr (informational)
  std::optional<base::Ipv4Address> subnet_mask;
  std::optional<base::Ipv4Address> router;

  bool operator==(const BootReply&) const = default;
};

// Checks a UDP payload received on port 68 against the request (`xid`, `mac`); reads nothing past it.
//   kOutOfRange        shorter than the fixed part (236 bytes)
//   kInvalidArgument   not a BOOTREPLY for Ethernet (op, htype, hlen), an unusable yiaddr (0, loopback,
//                      multicast, broadcast, class E), a non-contiguous subnet mask, bad option lengths
//   kNotFound          another transaction (xid) or another client (chaddr): not ours
//   kDataLoss          the options area is truncated
base::Result<BootReply> ParseBootReply(std::span<const std::uint8_t> payload, std::uint32_t xid,
                                       const base::MacAddress& mac);

// A usable unicast host address: not 0.0.0.0/8, 127/8, 224/4 (multicast) or 240/4 (class E, broadcast).
bool IsUsableUnicast(base::Ipv4Address address);
// A subnet mask of contiguous one bits from the top (0.0.0.0 excluded).
bool IsContiguousMask(base::Ipv4Address mask);

class BootpClient {
 public:
  enum class State : std::uint8_t { kIdle, kRequesting, kBound };

  BootpClient(const base::MacAddress& mac, hal::RandomSource& random) : mac_(mac), random_(random) {}

  // Begins a transaction: a new xid, the first request due at `now`.
  void Start(hal::Micros now);
  // Back to kIdle (communication reset); a reply that comes later is ignored.
  void Stop();

  // The request due at `now`, if any, written to `out`: returns kBootpMessageSize, or 0 when nothing is
  // due. Like every periodic duty of the card, it schedules the next copy from `now`.
  std::size_t Poll(hal::Micros now, std::span<std::uint8_t, kBootpMessageSize> out);
  hal::Micros NextDeadline() const { return deadline_; }

  // A UDP payload from port 67. kOk: it answered our request; the client is kBound and Lease() holds
  // the result. Otherwise the ParseBootReply error (or kFailedPrecondition when not requesting), and
  // nothing changes: a stray or broken reply never ends the transaction.
  base::Status OnReply(std::span<const std::uint8_t> payload);

  State state() const { return state_; }
  const BootReply& Lease() const { return lease_; }
  std::uint32_t xid() const { return xid_; }
  std::uint32_t transmissions() const { return transmissions_; }

 private:
  hal::Micros RetransmitDelay();

  base::MacAddress mac_;
  hal::RandomSource& random_;
  State state_ = State::kIdle;
  std::uint32_t xid_ = 0;
  hal::Micros started_ = 0;
  hal::Micros deadline_ = hal::kNever;
  std::uint32_t transmissions_ = 0;
  BootReply lease_{};
};

}  // namespace net
