// Class 1 (implicit I/O) connections: what the connection manager needs from the rest of the card,
// what it tells it, and the UDP 2222 datagram format.
//
// Interfaces (docs/connections.md "Interfaces"):
// - IoApplication: the connection points (assemblies). For a (configuration, O->T, T->O) triple it says
//   whether that connection exists, which kind it is (exclusive owner, input only, listen only) and the
//   data sizes; it consumes O->T data and produces T->O data.
// - MulticastAddressProvider: the multicast groups for T->O multicast (the firmware computes them from
//   the TCP/IP object's attribute 9).
// - ConnectionEvents: timeouts, run/idle changes, opened/closed connections (the firmware runs c100 /
//   c101 from the timeout, the Identity status and the LEDs from the rest).
//
// Datagram (CIP Vol. 2 §3-3): Common Packet Format, item count 2,
//   sequenced address item 0x8002 (length 8): connection ID, 32-bit encapsulation sequence number
//   connected data item 0x00B1: 16-bit CIP sequence count, then
//     O->T: the 32-bit run/idle header (bit 0 = run) and the data (a heartbeat point, size 0, has no
//           header unless the originator asked for one: docs/connections.md)
//     T->O: the data (modeless)
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>

#include "base/byte_reader.h"
#include "base/byte_writer.h"
#include "cip/explicit_messaging.h"
#include "cip/forward_open.h"
#include "cip/providers.h"
#include "hal/clock.h"

namespace cip {

inline constexpr std::uint16_t kIoPort = 2222;

enum class IoConnectionKind : std::uint8_t { kExclusiveOwner, kInputOnly, kListenOnly };

// The application paths of a class 1 Forward_Open.
struct IoPoints {
  std::optional<std::uint32_t> configuration;  // the path's instance segment; none when absent
  std::uint32_t consumed = 0;                  // O->T connection point
  std::uint32_t produced = 0;                  // T->O connection point

  constexpr bool operator==(const IoPoints&) const = default;
};

// The data sizes a Forward_Open asks for: its O->T connection size less the sequence count and the
// run/idle header (0 when it has no room for them: a heartbeat), its T->O size less the sequence count.
// For points whose size is chosen per connection (100/150: 2 to 8 words).
struct IoRequestedSizes {
  std::uint16_t consumed = 0;
  std::uint16_t produced = 0;

  constexpr bool operator==(const IoRequestedSizes&) const = default;
};

// What the application says about one IoPoints triple.
struct IoConnectionSpec {
  // 0: the connection exists. Otherwise the refusal: 0x0129 (no such configuration point), 0x012A (no
  // such consumed point), 0x012B (no such produced point), 0x012F (the points exist but do not form a
  // connection).
  std::uint16_t extended = 0;
  IoConnectionKind kind = IoConnectionKind::kExclusiveOwner;
  // The data sizes of the connection. When they differ from the requested ones the Forward_Open is
  // refused with 0x0127 / 0x0128 naming the connection size these sizes need (so a point with a choice
  // of sizes returns the requested size when it is valid, else the one to suggest, e.g. the largest).
  std::uint16_t consumed_size = 0;       // O->T data bytes; 0 is a heartbeat point
  std::uint16_t produced_size = 0;       // T->O data bytes
  std::uint16_t configuration_size = 0;  // bytes a data segment must have (0x0126 otherwise)
  // An exclusive owner of this point would be a second master of what an open exclusive owner of another
  // point already commands (the application's rule, e.g. two drive command outputs): refused with
  // 0x0106 in the place of the ownership check (docs/connections.md, rule 19).
  bool owner_conflict = false;
};

class IoApplication {
 public:
  virtual ~IoApplication() = default;
  virtual IoConnectionSpec Describe(const IoPoints& points, const IoRequestedSizes& requested) const = 0;
  // The configuration data of a Forward_Open that is otherwise accepted (only when its path has a data
  // segment, of exactly configuration_size bytes). Returns 0, or the extended status to refuse with.
  virtual std::uint16_t Configure(std::uint32_t /*configuration_point*/, std::span<const std::uint8_t> /*data*/) {
    return 0;
  }
  // New O->T data (the sequence count advanced) for a consumed point of size > 0, with the connection's
  // run/idle bit. Exactly the connection's consumed_size bytes.
  virtual void Consume(std::uint32_t point, std::span<const std::uint8_t> data, bool run) = 0;
  // The current data of a produced point: fills exactly the connection's produced_size bytes.
  virtual void Produce(std::uint32_t point, std::span<std::uint8_t> out) = 0;
};

class MulticastAddressProvider {
 public:
  virtual ~MulticastAddressProvider() = default;
  // The group (host order) for the card's multicast producer number `index` (0, 1, ...), or 0 when
  // the allocation (TCP/IP attribute 9) has no more addresses.
  virtual std::uint32_t MulticastGroup(std::size_t index) const = 0;
};

// One open connection, as the listeners see it.
struct ConnectionInfo {
  std::uint8_t transport_class = 0;                           // 1 or 3
  IoConnectionKind kind = IoConnectionKind::kExclusiveOwner;  // class 1 only
  IoPoints points;                                            // class 1 only
  ConnectionTriad triad;
  base::Ipv4Address originator_address;
  std::uint32_t o_to_t_connection_id = 0;
  std::uint32_t t_to_o_connection_id = 0;
  std::uint32_t o_to_t_api = 0;  // µs
  std::uint32_t t_to_o_api = 0;
  hal::Micros timeout = 0;       // RPI x 4 x 2^multiplier
  bool run = false;              // class 1: the last O->T run/idle bit (idle until data arrives)
  bool multicast = false;        // class 1: T->O multicast
};

// Why a connection closed.
enum class CloseReason : std::uint8_t {
  kForwardClose,   // the originator closed it
  kTimedOut,       // its inactivity watchdog ran out
  kSessionClosed,  // class 3: its encapsulation session ended
  kProducerGone,   // listen only: the last connection producing its point closed
};

class ConnectionEvents {
 public:
  virtual ~ConnectionEvents() = default;
  // The connection's inactivity watchdog ran out; it is closed (the firmware applies c100/c101 when it
  // is the one that controls the drive).
  virtual void OnConnectionTimedOut(const ConnectionInfo& connection) = 0;
  // An exclusive owner's O->T run/idle bit changed (new data with the other value).
  virtual void OnRunIdleChanged(const ConnectionInfo& connection, bool run) = 0;
  // A connection opened or closed for any reason (Identity status, Message Router attribute 3, LEDs).
  virtual void OnConnectionsChanged() = 0;
  // One connection closed (before OnConnectionsChanged; a timeout also gets OnConnectionTimedOut).
  virtual void OnConnectionClosed(const ConnectionInfo& /*connection*/, CloseReason /*reason*/) {}
};

// What the rest of the card may ask about the open connections (implemented by ConnectionManager).
class ConnectionTable {
 public:
  virtual ~ConnectionTable() = default;
  // The open connections (at most out.size() of them, in table order); returns how many were written.
  virtual std::size_t ListConnections(std::span<ConnectionInfo> out) const = 0;
  // Whether any connection is open (the NS LED asks after every event of the loop: a table answers
  // without copying a ConnectionInfo).
  virtual bool AnyOpen() const {
    std::array<ConnectionInfo, 1> one{};
    return ListConnections(one) > 0;
  }
  // Whether an exclusive owner connection consumes `point` (explicit writes to it are refused).
  virtual bool IsOwned(std::uint32_t consumed_point) const = 0;
  // Whether an exclusive-owner connection opened from another IP address than `originator_address` is
  // open: the drive then belongs to that originator (docs/security.md "Exclusive-owner write lock").
  virtual bool OwnedByAnotherOriginator(base::Ipv4Address originator_address) const = 0;
  // The Identity status bits 4-7 the connections call for.
  virtual ExtendedDeviceStatus IoStatus() const = 0;
};

// A T->O datagram to send from UDP port 2222.
struct IoDatagram {
  Ipv4Endpoint to;  // the originator (point-to-point) or the multicast group, port 2222 unless asked
  bool multicast = false;
  ConnectionPriority priority = ConnectionPriority::kLow;  // of the T->O parameters: the DSCP it is sent with
  std::span<const std::uint8_t> bytes;  // valid until the next TakeDueProduction
};

// ---- Datagram codec and timing rules ----------------------------------------------------------------

struct ReceivedIoDatagram {
  std::uint32_t connection_id = 0;
  std::uint32_t encapsulation_sequence = 0;
  std::span<const std::uint8_t> data;  // the connected data item (CIP sequence count first)
};
// kInvalidArgument unless the CPF holds exactly a sequenced address item (length 8) and a connected
// data item, in that order; kOutOfRange when it is cut short.
base::Result<ReceivedIoDatagram> ParseIoDatagram(std::span<const std::uint8_t> bytes);
void EncodeIoDatagram(std::uint32_t connection_id, std::uint32_t encapsulation_sequence, std::uint16_t sequence_count,
                      std::span<const std::uint8_t> data, base::ByteWriter& out);

// "a is later than b" for wrapping sequence numbers (serial number arithmetic).
constexpr bool SequenceAfter16(std::uint16_t a, std::uint16_t b) {
  return a != b && static_cast<std::uint16_t>(a - b) < 0x8000;
}
constexpr bool SequenceAfter32(std::uint32_t a, std::uint32_t b) {
  return a != b && static_cast<std::uint32_t>(a - b) < 0x80000000U;
}

// Connection timeout = RPI × 4 × 2^multiplier (multiplier 0-7).
constexpr hal::Micros ConnectionTimeout(std::uint32_t rpi, std::uint8_t multiplier) {
  return static_cast<hal::Micros>(rpi) * 4 << multiplier;
}

// The next production slot after producing at `now` for the slot `due` (<= now): due + api, or the
// first later slot that is still in the future; `missed` counts the slots skipped. Slots stay on the
// grid due + k × api, so production never drifts and never bursts.
hal::Micros NextProductionSlot(hal::Micros due, hal::Micros api, hal::Micros now, std::uint32_t& missed);

}  // namespace cip
