// Fakes and a fixture for the connection manager's tests (and its fuzz target): an I/O application
// with a few connection points, a multicast allocation, recorded events, and a CipDevice with the
// connection manager attached.
//
// Connection points of FakeIo (drive-like sizes, not the real assemblies):
//   configuration 1 (no data) and 2 (4 bytes of configuration data)
//   consumed 100 (8 bytes), 102 (any even size 4-16), 198 (heartbeat, input only), 199 (heartbeat,
//   listen only)
//   produced 150 (6 bytes), 151 (4 bytes), 152 (any even size 4-16)
//   connections: 100 -> 150 and 102 -> 152 exclusive owner, 198 -> 150 / 151 / 152 input only,
//   199 -> 150 / 151 / 152 listen only; 100 -> 151 and 102 -> 150 are not connections (0x012F)
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "cip/connection_manager.h"
#include "cip/forward_open.h"
#include "cip/io_connection.h"
#include "cip_fakes.h"
#include "cip_test_support.h"

namespace cip::test {

inline constexpr base::Ipv4Address kOriginator{10, 0, 2, 2};
inline constexpr std::uint32_t kSession = 0x5EE55105;

class FakeIo final : public IoApplication {
 public:
  IoConnectionSpec Describe(const IoPoints& points, const IoRequestedSizes& requested) const override {
    IoConnectionSpec spec;
    if (points.configuration && *points.configuration != 1 && *points.configuration != 2) {
      spec.extended = kExtendedConfigurationPath;
      return spec;
    }
    if (points.consumed != 100 && points.consumed != 102 && points.consumed != 198 && points.consumed != 199) {
      spec.extended = kExtendedConsumingPath;
      return spec;
    }
    if (points.produced != 150 && points.produced != 151 && points.produced != 152) {
      spec.extended = kExtendedProducingPath;
      return spec;
    }
    if ((points.consumed == 100 && points.produced != 150) || (points.consumed == 102 && points.produced != 152)) {
      spec.extended = kExtendedInconsistentPaths;
      return spec;
    }
    last_requested = requested;
    spec.kind = points.consumed == 100 || points.consumed == 102 ? IoConnectionKind::kExclusiveOwner
                : points.consumed == 198                         ? IoConnectionKind::kInputOnly
                                                                 : IoConnectionKind::kListenOnly;
    spec.consumed_size = points.consumed == 100 ? 8 : points.consumed == 102 ? Variable(requested.consumed) : 0;
    spec.produced_size = points.produced == 150 ? 6 : points.produced == 151 ? 4 : Variable(requested.produced);
    if (points.consumed == 102 && scanner_consumed_size != 0) spec.consumed_size = scanner_consumed_size;
    if (points.produced == 152 && scanner_produced_size != 0) spec.produced_size = scanner_produced_size;
    spec.configuration_size = points.configuration == 2U ? 4 : 0;
    spec.owner_conflict = conflicting_point.has_value() && points.consumed == *conflicting_point;
    return spec;
  }
  // 2 to 8 words: the requested size when it is one, else the largest.
  static std::uint16_t Variable(std::uint16_t requested) {
    return requested >= 4 && requested <= 16 && requested % 2 == 0 ? requested : 16;
  }
  std::uint16_t Configure(std::uint32_t point, std::span<const std::uint8_t> data) override {
    configured.emplace_back(point, Of(data));
    return refuse_configuration;
  }
  void Consume(std::uint32_t point, std::span<const std::uint8_t> data, bool run) override {
    consumed.push_back(Consumption{point, Of(data), run});
  }
  void Produce(std::uint32_t point, std::span<std::uint8_t> out) override {
    ++productions;
    for (std::size_t i = 0; i < out.size(); ++i) out[i] = static_cast<std::uint8_t>(point + i);
  }

  // An exclusive owner of this point conflicts with the open ones (IoConnectionSpec::owner_conflict).
  std::optional<std::uint32_t> conflicting_point;

  struct Consumption {
    std::uint32_t point;
    Bytes data;
    bool run;
  };
  std::vector<Consumption> consumed;
  std::vector<std::pair<std::uint32_t, Bytes>> configured;
  std::uint16_t refuse_configuration = 0;
  int productions = 0;
  mutable IoRequestedSizes last_requested;
  // Sizes 102 / 152 claim instead of their 2 to 8 words (0: as usual), for the connection manager's limits.
  std::uint16_t scanner_consumed_size = 0;
  std::uint16_t scanner_produced_size = 0;
};

class FakeMulticastGroups final : public MulticastAddressProvider {
 public:
  std::uint32_t MulticastGroup(std::size_t index) const override {
    return index < count ? 0xEFC00120 + static_cast<std::uint32_t>(index) : 0;  // 239.192.1.32, ...
  }
  std::size_t count = 2;
};

class RecordingEvents final : public ConnectionEvents {
 public:
  void OnConnectionTimedOut(const ConnectionInfo& connection) override { timeouts.push_back(connection); }
  void OnRunIdleChanged(const ConnectionInfo& connection, bool run) override {
    run_idle.emplace_back(connection.o_to_t_connection_id, run);
  }
  void OnConnectionsChanged() override { ++changes; }

  std::vector<ConnectionInfo> timeouts;
  std::vector<std::pair<std::uint32_t, bool>> run_idle;
  int changes = 0;
};

// A Forward_Open with the defaults of an exclusive owner 1 / 100 / 150 at 10 ms, point-to-point.
struct OpenParams {
  bool large = false;
  std::uint32_t t_to_o_id = 0x20000001;
  ConnectionTriad triad{0x1337, 0x3333, 0x12345678};
  std::uint8_t multiplier = 1;
  std::uint32_t o_to_t_rpi = 10000;
  std::uint32_t t_to_o_rpi = 10000;
  NetworkConnectionParameters o_to_t{14, false, ConnectionPriority::kScheduled, ConnectionType::kPointToPoint, false};
  NetworkConnectionParameters t_to_o{8, false, ConnectionPriority::kScheduled, ConnectionType::kPointToPoint, false};
  std::uint8_t transport = 0x01;
  Bytes path = Hex("20 04 24 01 2C 64 2C 96");
};

inline Bytes ForwardOpenRequestBytes(const OpenParams& params) {
  ForwardOpenRequest request;
  request.large = params.large;
  request.priority_tick = 0x0A;
  request.timeout_ticks = 0x0E;
  request.t_to_o_connection_id = params.t_to_o_id;
  request.triad = params.triad;
  request.timeout_multiplier = params.multiplier;
  request.o_to_t_rpi = params.o_to_t_rpi;
  request.o_to_t = params.o_to_t;
  request.t_to_o_rpi = params.t_to_o_rpi;
  request.t_to_o = params.t_to_o;
  request.transport = DecodeTransportClassTrigger(params.transport);
  request.connection_path = params.path;
  Bytes out(64 + params.path.size());
  base::ByteWriter writer(out);
  writer.U8(params.large ? kServiceLargeForwardOpen : kServiceForwardOpen);
  writer.U8(2);
  writer.Bytes(Hex("20 06 24 01"));
  EncodeForwardOpen(request, writer);
  out.resize(writer.size());
  return out;
}

// An input only connection (heartbeat 198) to input 151 (6 bytes), with its own serial number.
inline OpenParams InputOnly151(std::uint16_t serial) {
  OpenParams params;
  params.triad.connection_serial = serial;
  params.o_to_t.size = 2;
  params.t_to_o.size = 6;
  params.path = Hex("20 04 24 01 2C C6 2C 97");
  return params;
}

// A class 3 connection to the Message Router at 2 s.
inline OpenParams ExplicitParams() {
  OpenParams params;
  params.transport = 0xA3;
  params.o_to_t_rpi = 2000000;
  params.t_to_o_rpi = 2000000;
  params.o_to_t.size = 500;
  params.t_to_o.size = 500;
  params.o_to_t.variable = true;
  params.t_to_o.variable = true;
  params.path = Hex("20 02 24 01");
  return params;
}

inline Bytes ForwardCloseRequestBytes(const ConnectionTriad& triad,
                                      const Bytes& path = Hex("20 04 24 01 2C 64 2C 96")) {
  ForwardCloseRequest request;
  request.priority_tick = 0x0A;
  request.timeout_ticks = 0x0E;
  request.triad = triad;
  request.connection_path = path;
  Bytes out(32 + path.size());
  base::ByteWriter writer(out);
  writer.U8(kServiceForwardClose);
  writer.U8(2);
  writer.Bytes(Hex("20 06 24 01"));
  EncodeForwardClose(request, writer);
  out.resize(writer.size());
  return out;
}

// An O->T datagram: sequenced address item, connected data item with sequence count, run/idle header
// (unless `header` is false) and data.
inline Bytes IoDatagramBytes(std::uint32_t connection_id, std::uint32_t encapsulation_sequence, std::uint16_t sequence,
                             bool run, const Bytes& data, bool header = true) {
  Bytes payload;
  if (header) payload = {static_cast<std::uint8_t>(run ? 1 : 0), 0, 0, 0};
  for (std::uint8_t byte : data) payload.push_back(byte);
  Bytes out(64 + payload.size());
  base::ByteWriter writer(out);
  EncodeIoDatagram(connection_id, encapsulation_sequence, sequence, payload, writer);
  out.resize(writer.size());
  return out;
}

// A CipDevice on fakes with the connection manager attached.
struct ConnectionCard {
  explicit ConnectionCard(const ConnectionManagerOptions& options = {})
      : cm(card.cip.router(), card.device, ids, options) {
    (void)AttachConnectionManager(card.cip, cm);
    cm.set_io_application(&io);
    cm.set_multicast_provider(&groups);
    cm.set_events(&events);
  }

  // Asks the message router as the encapsulation layer would for a request from `originator`.
  Bytes Ask(const Bytes& request) {
    Bytes reply(kMaxEncapsulationData);
    context = RequestContext{};
    context.now = now;
    context.session_handle = kSession;
    context.peer = Ipv4Endpoint{originator, 50000};
    reply.resize(card.cip.router().HandleUnconnected(request, context, reply));
    return reply;
  }
  Bytes Open(const OpenParams& params = {}) { return Ask(ForwardOpenRequestBytes(params)); }
  // The O->T connection ID of a successful Forward_Open reply.
  static std::uint32_t OtoTId(const Bytes& reply) {
    return reply.size() < 8 ? 0
                            : static_cast<std::uint32_t>(reply[4] | reply[5] << 8 | reply[6] << 16 | reply[7] << 24);
  }
  Bytes Take() {
    IoDatagram datagram;
    if (!cm.TakeDueProduction(now, datagram)) return {};
    last_to = datagram.to;
    last_priority = datagram.priority;
    return Of(datagram.bytes);
  }

  FakeCard card;
  ScriptedRandom ids;
  FakeIo io;
  FakeMulticastGroups groups;
  RecordingEvents events;
  ConnectionManager cm;
  RequestContext context;
  base::Ipv4Address originator = kOriginator;  // the IP address requests come from
  hal::Micros now = 1000000;
  Ipv4Endpoint last_to;
  ConnectionPriority last_priority = ConnectionPriority::kLow;
};

}  // namespace cip::test
