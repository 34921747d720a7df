// Connection Manager object 0x06 (manual §4.4) and the card's CIP connections (docs/connections.md).
//
//   class attributes  1 revision 1, 2 max instance 1, 3 instances 1, 4 optional attributes (1-8),
//                     6 max class attribute 7, 7 max instance attribute 8
//   class services    Get_Attribute_Single 0x0E
//   instance 1        1 open requests, 2 open format rejects, 3 open resource rejects, 4 open other
//                     rejects, 5 close requests, 6 close format requests, 7 close other requests,
//                     8 connection timeouts (UINT counters, wrapping)
//   instance services Get_Attribute_Single 0x0E, Forward_Close 0x4E, Forward_Open 0x54,
//                     Large_Forward_Open 0x5B (Unconnected_Send 0x52 is the message router's)
//
// A fixed table of kMaxCipConnections (16) connections:
// - class 3 (explicit, to the Message Router over SendUnitData on the session that opened it): a
//   repeated sequence count gets the previous reply again without executing the request again;
// - class 1 (implicit I/O on UDP 2222): exclusive owner, input only, listen only; T->O point-to-point
//   or multicast (one production shared by every multicast connection of the same point).
// Production runs on absolute deadlines (next = previous + API); a late production skips the slots
// that passed instead of bursting, and counts them. A connection whose O->T traffic stops for
// RPI × 4 × 2^multiplier closes (listen-only connections that depended on it close with it).
//
// The firmware calls (docs/connections.md "In the firmware"):
//   AttachConnectionManager(device, cm)   registers class 0x06, the SendUnitData handler, MR attr 3
//   OnIoDatagram(bytes, from, now)         every datagram on UDP 2222
//   TakeDueProduction(now, out)            until false, when now >= NextDeadline(); sends `out`
//   CheckTimeouts(now)                     (TakeDueProduction does it too)
//   IoStatus()                             the Identity status bits 4-7
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>

#include "base/pool_stats.h"
#include "cip/cip_device.h"
#include "cip/forward_open.h"
#include "cip/io_connection.h"
#include "cip/message_router.h"
#include "cip/message_router_object.h"
#include "cip/object_model.h"
#include "cip/providers.h"
#include "hal/clock.h"
#include "hal/random.h"

namespace cip {

// Class 3 connections keep their last reply for a repeated sequence count: at most this many class 3
// connections, each with a reply of at most kMaxExplicitReply bytes (sequence count included: a
// Forward_Open connection size is at most 511).
inline constexpr std::size_t kMaxExplicitConnections = 6;
inline constexpr std::size_t kMaxExplicitReply = 512;
// The largest class 1 data the card exchanges (consumed or produced, without sequence count and run/idle
// header): its largest assembly is 18 bytes (cip/drive kMaxAssemblySize, static_assert there); 32 leaves
// room for a larger one. An application point needing more is refused 0x01 / 0x012A (consuming) or
// 0x012B (producing); CIP's own bound would be 509 (T->O connection size 511).
inline constexpr std::size_t kMaxIoData = 32;
// The largest class 1 datagram: CPF with the sequenced address and data items (18 bytes), sequence count
// (2), run/idle header (O->T, 4) and the data. Longer datagrams on UDP 2222 are dropped and counted.
inline constexpr std::size_t kMaxIoDatagram = 24 + kMaxIoData;

struct ConnectionManagerOptions {
  // RPIs (µs) outside [min_rpi, max_rpi] are refused with 0x0111 naming the limit (BEY-2: the floor
  // is what the firmware can really produce at).
  std::uint32_t min_rpi = 1000;
  std::uint32_t max_rpi = 10 * 1000 * 1000;
  std::size_t max_explicit_connections = kMaxExplicitConnections;  // beyond: 0x011A
  std::size_t max_connections_per_point = 4;                       // class 1 per produced point: 0x011A
  // The first O->T packet may take this long (at least; more if the timeout is longer).
  hal::Micros initial_timeout = 10 * hal::kMicrosPerSecond;
};

struct ConnectionCounters {
  std::uint16_t open_requests = 0;
  std::uint16_t open_format_rejects = 0;
  std::uint16_t open_resource_rejects = 0;
  std::uint16_t open_other_rejects = 0;
  std::uint16_t close_requests = 0;
  std::uint16_t close_format_rejects = 0;
  std::uint16_t close_other_rejects = 0;
  std::uint16_t connection_timeouts = 0;
};

class ConnectionManager final : public AttributeHandler,
                                public ConnectedMessageHandler,
                                public ConnectionCountProvider,
                                public ConnectionTable {
 public:
  ConnectionManager(MessageRouter& router, const DeviceInfoProvider& device, hal::RandomSource& random,
                    const ConnectionManagerOptions& options = {});
  ConnectionManager(const ConnectionManager&) = delete;
  ConnectionManager& operator=(const ConnectionManager&) = delete;

  CipObject& object() { return object_; }
  // Without an application every class 1 Forward_Open is refused (0x012A); without a multicast
  // provider every multicast T->O (0x0124).
  void set_io_application(IoApplication* application) { application_ = application; }
  void set_multicast_provider(const MulticastAddressProvider* provider) { multicast_ = provider; }
  void set_events(ConnectionEvents* events) { events_ = events; }

  // ---- UDP 2222 and time ----
  void OnIoDatagram(std::span<const std::uint8_t> bytes, Ipv4Endpoint from, hal::Micros now);
  // Closes every connection whose watchdog ran out at `now` (OnConnectionTimedOut for each).
  void CheckTimeouts(hal::Micros now);
  // Checks timeouts, then builds the most overdue T->O datagram due at `now`; false when none is.
  bool TakeDueProduction(hal::Micros now, IoDatagram& out);
  // The earliest production or watchdog deadline, hal::kNever when there is none.
  hal::Micros NextDeadline() const;

  // ---- State for the rest of the card ----
  // Identity status bits 4-7: 0010 after a class 1 timeout (until a class 1 connection opens again),
  // else 0110 when an I/O connection is in run mode, 0111 when I/O connections are open and all idle,
  // 0011 when there is none.
  ExtendedDeviceStatus IoStatus() const override;
  // Whether an exclusive owner connection consumes `point` (explicit writes to it are refused).
  bool IsOwned(std::uint32_t consumed_point) const override;
  bool OwnedByAnotherOriginator(base::Ipv4Address originator_address) const override;
  // The open connections (at most out.size() of them, in table order); returns how many were written.
  std::size_t ListConnections(std::span<ConnectionInfo> out) const override;
  bool AnyOpen() const override { return ActiveConnections() > 0; }
  const ConnectionCounters& counters() const { return counters_; }
  std::uint32_t missed_productions() const { return missed_productions_; }
  std::uint32_t dropped_datagrams() const { return dropped_datagrams_; }
  // The fixed pools (docs/robustness.md "Exhaustion"): the connection table (refused: 0x0113, table
  // full), class 3 reply stores (refused: 0x011A, options.max_explicit_connections reached) and
  // productions (refused: 0x0113, no multicast group left for a new multicast production).
  base::PoolStats connection_pool() const { return table_marks_.Stats(ActiveConnections(), kMaxCipConnections); }
  base::PoolStats explicit_pool() const;
  base::PoolStats production_pool() const;

  // ConnectionCountProvider (Message Router attribute 3)
  std::uint16_t ActiveConnections() const override;

  // ConnectedMessageHandler (class 3 over SendUnitData)
  std::size_t HandleConnected(std::uint32_t connection_id, std::uint16_t sequence_count,
                              std::span<const std::uint8_t> request, RequestContext& context,
                              std::span<std::uint8_t> reply, std::uint32_t& reply_connection_id) override;
  bool SessionHasConnections(std::uint32_t session_handle) const override;
  void OnSessionClosed(std::uint32_t session_handle) override;

  // AttributeHandler (class 0x06)
  std::uint32_t MaxInstance() const override { return 1; }
  std::span<const AttributeSpec> InstanceAttributes(std::uint32_t instance) const override;
  void GetInstanceAttribute(std::uint32_t instance, std::uint16_t id, base::ByteWriter& out) override;
  ServiceStatus ExecuteOther(const ServiceRequest& request, base::ByteWriter& reply) override;

 private:
  static constexpr int kNone = -1;

  struct Connection {
    bool open = false;
    std::uint8_t transport_class = 0;
    IoConnectionKind kind = IoConnectionKind::kExclusiveOwner;
    IoPoints points;
    ConnectionTriad triad;
    base::Ipv4Address originator_address;
    std::uint32_t session_handle = 0;
    std::uint32_t o_to_t_id = 0;
    std::uint32_t t_to_o_id = 0;
    std::uint32_t o_to_t_api = 0;
    std::uint32_t t_to_o_api = 0;
    hal::Micros timeout = 0;
    hal::Micros deadline = 0;
    std::uint16_t o_to_t_size = 0;  // connection size: sequence count [+ run/idle header] + data
    std::uint16_t t_to_o_size = 0;
    std::uint16_t consumed_size = 0;
    bool has_header = false;
    bool received = false;
    std::uint32_t last_encapsulation_sequence = 0;
    std::uint16_t last_sequence = 0;  // class 1: CIP sequence count; class 3: the cached reply's
    bool run = false;
    int producer = kNone;
    int explicit_slot = kNone;
    bool has_reply = false;
    std::uint16_t reply_size = 0;
  };
  struct Producer {
    bool active = false;
    std::uint32_t point = 0;
    std::uint32_t connection_id = 0;
    Ipv4Endpoint to;
    bool multicast = false;
    ConnectionPriority priority = ConnectionPriority::kLow;  // T->O: the DSCP of the productions
    std::size_t multicast_index = 0;
    std::uint32_t api = 0;
    std::uint16_t size = 0;
    hal::Micros next = 0;
    std::uint32_t encapsulation_sequence = 0;
    std::uint16_t sequence = 0;
  };
  // A validated Forward_Open, ready to be entered into the table.
  struct Opening {
    const ForwardOpenRequest* request = nullptr;
    ConnectionPath path;
    IoConnectionSpec spec;
    IoPoints points;
    int shared_producer = kNone;
    std::uint32_t multicast_group = 0;
    std::size_t multicast_index = 0;
    // Which pool refused it, when CheckCapacity did (for the pool statistics).
    enum class Exhausted : std::uint8_t { kNone, kTable, kExplicit, kMulticastGroups } exhausted = Exhausted::kNone;
  };

  ServiceStatus ForwardOpen(const ServiceRequest& request, base::ByteWriter& reply, bool large);
  ServiceStatus ForwardClose(const ServiceRequest& request, base::ByteWriter& reply);
  ServiceStatus RejectOpen(const ConnectionFailure& failure, const ConnectionTriad& triad, base::ByteWriter& reply);
  std::optional<ConnectionFailure> Validate(const ForwardOpenRequest& request, const RequestContext& context,
                                           Opening& opening) const;
  std::optional<ConnectionFailure> ValidateIo(const ForwardOpenRequest& request, const RequestContext& context,
                                             Opening& opening) const;
  std::optional<ConnectionFailure> CheckCapacity(std::uint8_t transport_class, Opening& opening) const;
  ForwardOpenSuccess Open(const Opening& opening, RequestContext& context);
  void Close(std::size_t index, CloseReason reason);
  void CloseOrphanedListeners();
  void ReleaseUnusedProducers();
  void NotifyChanged();

  void NoteExhausted(const Opening& opening);
  std::size_t ExplicitInUse() const;
  std::size_t ActiveProducers() const;
  int FindFree() const;
  int FindByTriad(const ConnectionTriad& triad) const;
  int FindMulticastProducer(std::uint32_t point) const;
  bool HasProducerOf(std::uint32_t point, bool listen_only_too) const;
  bool IdInUse(std::uint32_t id) const;
  std::uint32_t NewConnectionId();
  ConnectionInfo InfoOf(const Connection& connection) const;
  DeviceKey Key() const;

  MessageRouter& router_;
  const DeviceInfoProvider& device_;
  hal::RandomSource& random_;
  ConnectionManagerOptions options_;
  IoApplication* application_ = nullptr;
  const MulticastAddressProvider* multicast_ = nullptr;
  ConnectionEvents* events_ = nullptr;
  ConnectionCounters counters_;
  bool io_faulted_ = false;
  std::uint32_t missed_productions_ = 0;
  std::uint32_t dropped_datagrams_ = 0;
  std::array<Connection, kMaxCipConnections> connections_{};
  std::array<Producer, kMaxCipConnections> producers_{};
  std::array<bool, kMaxExplicitConnections> explicit_in_use_{};
  std::array<std::array<std::uint8_t, kMaxExplicitReply>, kMaxExplicitConnections> explicit_replies_{};
  std::array<std::uint8_t, kMaxIoDatagram> datagram_{};
  base::PoolWatermark table_marks_;
  base::PoolWatermark explicit_marks_;
  base::PoolWatermark production_marks_;
  AttributeObject object_;
};

// Registers `cm` in the device: class 0x06 in the object registry, the SendUnitData handler of the
// encapsulation server and the Message Router's connection count. kInvalidArgument when class 0x06 is
// already registered.
base::Status AttachConnectionManager(CipDevice& device, ConnectionManager& cm);

}  // namespace cip
