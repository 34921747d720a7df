// The card's LLDP agent (IEEE 802.1AB; docs/network.md "LLDP"): transmits the card's LLDPDU on each
// port with link and keeps a fixed table of the neighbours heard on each port. No clock of its own
// (time comes in as hal::Micros), no allocation.
//
// Transmit, per port (index 0 = L, 1 = R): the first frame kLldpFirstFrameDelay after the link comes up,
// then every kLldpTxInterval (msgTxInterval 30 s); TTL = 30 s x msgTxHold 4 = 120 s. A change of what
// the card advertises (system name, management address) is sent at the next poll, but never sooner
// than kLldpMinGap after the port's previous frame. No shutdown LLDPDU: a card that loses power cannot
// send one, and its neighbours age it out after the TTL.
//
// Receive: a valid LLDPDU creates or refreshes the entry keyed by (port, chassis ID, port ID), which
// expires TTL seconds later; TTL 0 removes it at once. A full table keeps the neighbours it has: the
// newcomer is dropped and counted (table_full) until an entry ages out. A port whose link goes down
// forgets its neighbours (802.1AB: the remote data of a port is deleted when it stops operating).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>

#include "base/addresses.h"
#include "hal/clock.h"
#include "net/lldp_frame.h"

namespace net {

inline constexpr std::size_t kLldpPorts = 2;
inline constexpr std::size_t kLldpMaxNeighbours = 4;
inline constexpr hal::Micros kLldpTxInterval = 30 * hal::kMicrosPerSecond;  // msgTxInterval
inline constexpr std::uint16_t kLldpTxHold = 4;                             // msgTxHold
inline constexpr std::uint16_t kLldpTtlSeconds =
    static_cast<std::uint16_t>(kLldpTxInterval / hal::kMicrosPerSecond * kLldpTxHold);  // 120
inline constexpr hal::Micros kLldpFirstFrameDelay = 1 * hal::kMicrosPerSecond;
inline constexpr hal::Micros kLldpMinGap = 1 * hal::kMicrosPerSecond;
inline constexpr std::size_t kLldpSystemNameMax = 24;

// Where the agent's frames go: out of one port only (LLDP is per link).
class LldpSink {
 public:
  virtual ~LldpSink() = default;
  virtual void SendLldp(std::size_t port, std::span<const std::uint8_t> frame) = 0;
};

// What never changes while the card runs.
struct LldpIdentity {
  base::MacAddress mac;
  std::string_view product;             // the system name's fallback: "<product>-XXXXXX"
  std::string_view system_description;  // static storage
};

struct LldpNeighbour {
  std::uint8_t port = 0;  // 0 = L, 1 = R
  LldpNeighbourInfo info;
  hal::Micros expires = 0;
};

struct LldpCounters {
  std::uint32_t frames_in = 0;   // LLDP frames received (malformed ones included)
  std::uint32_t frames_out = 0;  // LLDPDUs handed to a port
  std::uint32_t malformed = 0;   // LLDPDUs refused by the parser
  std::uint32_t table_full = 0;  // new neighbours dropped because the table was full
  std::uint32_t aged_out = 0;    // entries removed when their TTL ran out
};

class LldpAgent {
 public:
  LldpAgent(const LldpIdentity& identity, LldpSink& sink);

  // The device name (c081-c096); empty: "<product>-" and the MAC's last three octets in hex.
  void SetSystemName(std::string_view name);
  // The address in use; 0.0.0.0: none (no Management Address TLV).
  void SetManagementAddress(base::Ipv4Address address);
  void LinkUp(std::size_t port, hal::Micros now);
  void LinkDown(std::size_t port);

  // A frame received on `port`; false when it is not an LLDP frame (the caller passes it on).
  bool OnFrame(std::size_t port, std::span<const std::uint8_t> frame, hal::Micros now);
  // Ages the table and sends what is due at `now`.
  void Poll(hal::Micros now);
  hal::Micros NextDeadline() const;

  std::span<const LldpNeighbour> neighbours() const { return {table_.data(), count_}; }
  const LldpCounters& counters() const { return counters_; }
  std::string_view system_name() const { return {name_.data(), name_size_}; }

 private:
  void Remove(std::size_t index);
  void Send(std::size_t port, hal::Micros now);
  void AdvertiseChange();

  LldpIdentity identity_;
  LldpSink& sink_;
  std::array<char, kLldpSystemNameMax> name_{};
  std::size_t name_size_ = 0;
  base::Ipv4Address management_;
  std::array<bool, kLldpPorts> up_{};
  std::array<hal::Micros, kLldpPorts> next_tx_{hal::kNever, hal::kNever};
  std::array<hal::Micros, kLldpPorts> earliest_tx_{};  // the first frame after link-up, then kLldpMinGap
  std::array<LldpNeighbour, kLldpMaxNeighbours> table_{};
  std::size_t count_ = 0;
  LldpCounters counters_;
};

}  // namespace net
