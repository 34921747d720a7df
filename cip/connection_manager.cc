// Connection Manager object, Forward_Open validation and the connection table. The class 1 datagrams,
// production, watchdogs and class 3 traffic are in connection_manager_io.cc.
#include "cip/connection_manager.h"

#include <algorithm>

#include "cip/identity_object.h"

namespace cip {
namespace {

constexpr std::array<std::uint16_t, 6> kClassAttributes = {1, 2, 3, 4, 6, 7};
constexpr std::array<std::uint16_t, 8> kOptionalAttributes = {1, 2, 3, 4, 5, 6, 7, 8};
constexpr std::array<std::uint8_t, 1> kClassServices = {kServiceGetAttributeSingle};
constexpr std::array<std::uint8_t, 4> kInstanceServices = {kServiceGetAttributeSingle, kServiceForwardClose,
                                                           kServiceForwardOpen, kServiceLargeForwardOpen};
constexpr ClassSpec kConnectionManagerClass = {
    kClassConnectionManager, 1, kClassAttributes, kOptionalAttributes, {}, 7, 8, kClassServices, kInstanceServices,
};
constexpr std::array<AttributeSpec, 8> kAttributes = GettableAttributes<8>();

constexpr std::uint8_t kMaxTimeoutMultiplier = 7;
constexpr std::uint16_t kSequenceCountSize = 2;
constexpr std::uint16_t kRunIdleHeaderSize = 4;

bool IsFormatReject(const ConnectionFailure& failure) {
  if (failure.extended == 0) return true;  // 0x13 / 0x15: the request's framing
  return failure.extended == kExtendedInvalidRouteSegment || failure.extended == kExtendedInvalidRoutePort ||
         failure.extended == kExtendedInvalidRouteNode;
}

bool IsResourceReject(const ConnectionFailure& failure) {
  return failure.extended == kExtendedOutOfConnections || failure.extended == kExtendedTargetOutOfConnections;
}

ConnectionFailure PathFailure(std::uint16_t extended, const ForwardOpenRequest& request) {
  ConnectionFailure failure = ConnectionFailure::Extended(extended);
  // A segment the card cannot follow: none of the path was used.
  failure.remaining_path_words = static_cast<std::uint8_t>(request.connection_path.size() / 2);
  return failure;
}

// The O->T connection size a consumed point of `size` data bytes needs: sequence count, run/idle
// header and data; a heartbeat point (size 0) has no header.
std::uint16_t ConsumedConnectionSize(std::uint16_t size) {
  return size == 0 ? kSequenceCountSize : static_cast<std::uint16_t>(kSequenceCountSize + kRunIdleHeaderSize + size);
}

std::optional<ConnectionFailure> CheckRpi(const ForwardOpenRequest& request, std::uint32_t min, std::uint32_t max) {
  std::uint8_t o_type = kRpiAcceptable;
  std::uint8_t t_type = kRpiAcceptable;
  std::uint32_t o_rpi = request.o_to_t_rpi;
  std::uint32_t t_rpi = request.t_to_o_rpi;
  if (o_rpi < min) {
    o_type = kRpiMinimumAcceptable;
    o_rpi = min;
  } else if (o_rpi > max) {
    o_type = kRpiMaximumAcceptable;
    o_rpi = max;
  }
  if (t_rpi < min) {
    t_type = kRpiMinimumAcceptable;
    t_rpi = min;
  } else if (t_rpi > max) {
    t_type = kRpiMaximumAcceptable;
    t_rpi = max;
  }
  if (o_type == kRpiAcceptable && t_type == kRpiAcceptable) return std::nullopt;
  return ConnectionFailure::WithRpi(kExtendedRpiNotSupported, o_type, o_rpi, t_type, t_rpi);
}

}  // namespace

ConnectionManager::ConnectionManager(MessageRouter& router, const DeviceInfoProvider& device, hal::RandomSource& random,
                                     const ConnectionManagerOptions& options)
    : router_(router), device_(device), random_(random), options_(options), object_(kConnectionManagerClass, *this) {
  options_.max_explicit_connections = std::min(options_.max_explicit_connections, kMaxExplicitConnections);
}

std::span<const AttributeSpec> ConnectionManager::InstanceAttributes(std::uint32_t) const { return kAttributes; }

void ConnectionManager::GetInstanceAttribute(std::uint32_t, std::uint16_t id, base::ByteWriter& out) {
  const std::array<std::uint16_t, 8> values = {
      counters_.open_requests,       counters_.open_format_rejects, counters_.open_resource_rejects,
      counters_.open_other_rejects,  counters_.close_requests,      counters_.close_format_rejects,
      counters_.close_other_rejects, counters_.connection_timeouts,
  };
  if (id >= 1 && id <= values.size()) out.U16Le(values[id - 1]);
}

ServiceStatus ConnectionManager::ExecuteOther(const ServiceRequest& request, base::ByteWriter& reply) {
  switch (request.service) {
    case kServiceForwardOpen:
      return ForwardOpen(request, reply, false);
    case kServiceLargeForwardOpen:
      return ForwardOpen(request, reply, true);
    case kServiceForwardClose:
      return ForwardClose(request, reply);
    default:
      return Error(GeneralStatus::kServiceNotSupported);
  }
}

std::uint16_t ConnectionManager::ActiveConnections() const {
  return static_cast<std::uint16_t>(
      std::count_if(connections_.begin(), connections_.end(), [](const Connection& c) { return c.open; }));
}

DeviceKey ConnectionManager::Key() const {
  const std::uint16_t product = device_.Model() == DriveModel::kVfS15 ? kProductCodeVfS15 : kProductCodeVfMb1;
  return DeviceKey{kVendorIdToshiba, kDeviceTypeAcDrive, product, kMajorRevision, kMinorRevision};
}

// ---- Forward_Open ------------------------------------------------------------------------------------

ServiceStatus ConnectionManager::RejectOpen(const ConnectionFailure& failure, const ConnectionTriad& triad,
                                            base::ByteWriter& reply) {
  if (IsFormatReject(failure)) {
    ++counters_.open_format_rejects;
  } else if (IsResourceReject(failure)) {
    ++counters_.open_resource_rejects;
  } else {
    ++counters_.open_other_rejects;
  }
  return EncodeConnectionFailure(failure, triad, reply);
}

ServiceStatus ConnectionManager::ForwardOpen(const ServiceRequest& service, base::ByteWriter& reply, bool large) {
  ++counters_.open_requests;
  const Decoded<ForwardOpenRequest> decoded = DecodeForwardOpen(service.data, large);
  const ForwardOpenRequest& request = decoded.request;
  switch (decoded.framing) {
    case RequestFraming::kFixedPartShort:
      ++counters_.open_format_rejects;
      return Error(GeneralStatus::kNotEnoughData);
    case RequestFraming::kPathShort:
      return RejectOpen(ConnectionFailure::General(GeneralStatus::kNotEnoughData), request.triad, reply);
    case RequestFraming::kExtraData:
      return RejectOpen(ConnectionFailure::General(GeneralStatus::kTooMuchData), request.triad, reply);
    case RequestFraming::kOk:
      break;
  }
  RequestContext local_context;
  RequestContext& context = service.context != nullptr ? *service.context : local_context;
  Opening opening;
  opening.request = &request;
  if (const std::optional<ConnectionFailure> failure = Validate(request, context, opening)) {
    NoteExhausted(opening);
    return RejectOpen(*failure, request.triad, reply);
  }
  if (opening.path.has_data && application_ != nullptr && request.transport.transport_class == 1) {
    const std::uint16_t refused = application_->Configure(*opening.points.configuration, opening.path.data);
    if (refused != 0) return RejectOpen(ConnectionFailure::Extended(refused), request.triad, reply);
  }
  EncodeForwardOpenSuccess(Open(opening, context), reply);
  return Success();
}

std::optional<ConnectionFailure> ConnectionManager::Validate(const ForwardOpenRequest& request,
                                                             const RequestContext& context, Opening& opening) const {
  using F = ConnectionFailure;
  if (request.o_to_t.type == ConnectionType::kNull && request.t_to_o.type == ConnectionType::kNull) {
    return F::Extended(kExtendedNullForwardOpen);
  }
  if (FindByTriad(request.triad) != kNone) return F::Extended(kExtendedDuplicateForwardOpen);
  const TransportClassTrigger& transport = request.transport;
  const bool class1 = transport.transport_class == 1 && transport.trigger == kTriggerCyclic;
  const bool class3 = transport.transport_class == 3 && transport.trigger <= kTriggerApplicationObject;
  if (!class1 && !class3) return F::Extended(kExtendedTransportTrigger);
  if (request.o_to_t.type != ConnectionType::kPointToPoint) return F::Extended(kExtendedOtoTConnectionType);
  const bool multicast = request.t_to_o.type == ConnectionType::kMulticast;
  if (request.t_to_o.type != ConnectionType::kPointToPoint && (!multicast || class3 || multicast_ == nullptr)) {
    return F::Extended(kExtendedTtoOConnectionType);
  }
  if (request.o_to_t.redundant_owner) return F::Extended(kExtendedRedundantOwner);
  if (request.timeout_multiplier > kMaxTimeoutMultiplier) return F::Extended(kExtendedTimeoutMultiplier);

  const ParsedConnectionPath parsed = ParseConnectionPath(request.connection_path);
  if (parsed.extended != 0) return PathFailure(parsed.extended, request);
  opening.path = parsed.path;
  const ConnectionPath& path = opening.path;
  if (path.key) {
    if (const std::uint16_t mismatch = CheckElectronicKey(*path.key, Key()); mismatch != 0) {
      return F::Extended(mismatch);
    }
  }
  if (path.class_id == kClassMessageRouter) {
    if (!class3) return F::Extended(kExtendedTransportTrigger);
    if (path.instance != 1U || path.point_count != 0 || path.has_data) {
      return PathFailure(kExtendedInvalidRouteSegment, request);
    }
  } else if (path.class_id == kClassAssembly) {
    if (!class1) return F::Extended(kExtendedTransportTrigger);
  } else {
    return PathFailure(kExtendedInvalidRouteSegment, request);
  }
  if (const std::optional<F> rpi = CheckRpi(request, options_.min_rpi, options_.max_rpi)) return rpi;
  if (class1) {
    if (const std::optional<F> io = ValidateIo(request, context, opening)) return io;
  }
  return CheckCapacity(transport.transport_class, opening);
}

std::optional<ConnectionFailure> ConnectionManager::ValidateIo(const ForwardOpenRequest& request,
                                                               const RequestContext& context,
                                                               Opening& opening) const {
  using F = ConnectionFailure;
  const ConnectionPath& path = opening.path;
  if (path.point_count == 0 || application_ == nullptr) return F::Extended(kExtendedConsumingPath);
  if (path.point_count == 1) return F::Extended(kExtendedProducingPath);
  opening.points = IoPoints{path.instance, path.points[0], path.points[1]};
  const std::uint16_t o_to_t_overhead = kSequenceCountSize + kRunIdleHeaderSize;
  const IoRequestedSizes requested{
      static_cast<std::uint16_t>(request.o_to_t.size > o_to_t_overhead ? request.o_to_t.size - o_to_t_overhead : 0),
      static_cast<std::uint16_t>(request.t_to_o.size > kSequenceCountSize ? request.t_to_o.size - kSequenceCountSize
                                                                          : 0)};
  const IoConnectionSpec spec = application_->Describe(opening.points, requested);
  if (spec.extended != 0) return F::Extended(spec.extended);
  if (spec.consumed_size > kMaxIoData) return F::Extended(kExtendedConsumingPath);
  if (spec.produced_size > kMaxIoData) return F::Extended(kExtendedProducingPath);
  opening.spec = spec;

  const std::uint16_t o_to_t_size = ConsumedConnectionSize(spec.consumed_size);
  const bool heartbeat_with_header =
      spec.consumed_size == 0 && request.o_to_t.size == kSequenceCountSize + kRunIdleHeaderSize;
  if (request.o_to_t.size != o_to_t_size && !heartbeat_with_header) return F::WithSize(kExtendedOtoTSize, o_to_t_size);
  const std::uint16_t t_to_o_size = static_cast<std::uint16_t>(kSequenceCountSize + spec.produced_size);
  if (request.t_to_o.size != t_to_o_size) return F::WithSize(kExtendedTtoOSize, t_to_o_size);
  if (path.has_data) {
    if (!path.instance) return F::Extended(kExtendedConfigurationPath);
    if (path.data.size() != spec.configuration_size) {
      return F::WithSize(kExtendedConfigurationSize, spec.configuration_size);
    }
  }

  const IoPoints& points = opening.points;
  // One originator owns the drive: an exclusive owner of another output from another IP address would
  // be a second master of the same motor (docs/security.md "Exclusive-owner write lock").
  // Nor may two exclusive owners of different points command the same thing (spec.owner_conflict).
  if (spec.kind == IoConnectionKind::kExclusiveOwner &&
      (IsOwned(points.consumed) || spec.owner_conflict || OwnedByAnotherOriginator(context.peer.address))) {
    return F::Extended(kExtendedOwnershipConflict);
  }
  if (spec.kind == IoConnectionKind::kListenOnly && !HasProducerOf(points.produced, false)) {
    return F::Extended(kExtendedNoNonListenOnly);
  }
  if (request.t_to_o.type == ConnectionType::kMulticast) {
    opening.shared_producer = FindMulticastProducer(points.produced);
    if (opening.shared_producer != kNone) {
      const Producer& shared = producers_[static_cast<std::size_t>(opening.shared_producer)];
      if (shared.size != spec.produced_size) {
        return F::WithSize(kExtendedTtoOSize, static_cast<std::uint16_t>(kSequenceCountSize + shared.size));
      }
      if (shared.api != request.t_to_o_rpi) {
        return F::WithRpi(kExtendedRpiNotAcceptable, kRpiAcceptable, request.o_to_t_rpi, kRpiRequiredForMismatch,
                          shared.api);
      }
    }
  }
  const std::size_t users =
      static_cast<std::size_t>(std::count_if(connections_.begin(), connections_.end(), [&](const Connection& c) {
        return c.open && c.transport_class == 1 && c.points.produced == points.produced;
      }));
  if (users >= options_.max_connections_per_point) return F::Extended(kExtendedTargetOutOfConnections);
  return std::nullopt;
}

std::optional<ConnectionFailure> ConnectionManager::CheckCapacity(std::uint8_t transport_class,
                                                                  Opening& opening) const {
  using F = ConnectionFailure;
  if (transport_class == 3) {
    if (ExplicitInUse() >= options_.max_explicit_connections) {
      opening.exhausted = Opening::Exhausted::kExplicit;
      return F::Extended(kExtendedTargetOutOfConnections);
    }
  }
  if (FindFree() == kNone) {
    opening.exhausted = Opening::Exhausted::kTable;
    return F::Extended(kExtendedOutOfConnections);
  }
  const ForwardOpenRequest& request = *opening.request;
  if (transport_class == 1 && request.t_to_o.type == ConnectionType::kMulticast && opening.shared_producer == kNone) {
    // A new multicast production needs a group of its own: the lowest index no producer uses.
    for (std::size_t index = 0; index < producers_.size(); ++index) {
      const bool used = std::any_of(producers_.begin(), producers_.end(), [&](const Producer& p) {
        return p.active && p.multicast && p.multicast_index == index;
      });
      if (used) continue;
      opening.multicast_index = index;
      opening.multicast_group = multicast_->MulticastGroup(index);
      break;
    }
    if (opening.multicast_group == 0) {
      opening.exhausted = Opening::Exhausted::kMulticastGroups;
      return F::Extended(kExtendedOutOfConnections);
    }
  }
  return std::nullopt;
}

ForwardOpenSuccess ConnectionManager::Open(const Opening& opening, RequestContext& context) {
  const ForwardOpenRequest& request = *opening.request;
  const std::size_t index = static_cast<std::size_t>(FindFree());
  Connection& connection = connections_[index];
  connection = Connection{};
  connection.transport_class = request.transport.transport_class;
  connection.triad = request.triad;
  connection.originator_address = context.peer.address;
  connection.session_handle = context.session_handle;
  connection.o_to_t_id = NewConnectionId();
  connection.o_to_t_api = request.o_to_t_rpi;
  connection.t_to_o_api = request.t_to_o_rpi;
  connection.o_to_t_size = request.o_to_t.size;
  connection.t_to_o_size = request.t_to_o.size;
  connection.timeout = ConnectionTimeout(request.o_to_t_rpi, request.timeout_multiplier);
  connection.deadline = context.now + std::max(connection.timeout, options_.initial_timeout);

  if (connection.transport_class == 3) {
    connection.t_to_o_id = request.t_to_o_connection_id;
    for (std::size_t slot = 0; slot < explicit_in_use_.size(); ++slot) {
      if (explicit_in_use_[slot]) continue;
      explicit_in_use_[slot] = true;
      connection.explicit_slot = static_cast<int>(slot);
      break;
    }
  } else {
    connection.kind = opening.spec.kind;
    connection.points = opening.points;
    connection.consumed_size = opening.spec.consumed_size;
    connection.has_header = request.o_to_t.size != kSequenceCountSize;
    io_faulted_ = false;
    if (opening.shared_producer != kNone) {
      connection.producer = opening.shared_producer;
    } else {
      const auto free = std::find_if(producers_.begin(), producers_.end(), [](const Producer& p) { return !p.active; });
      Producer& producer = *free;  // a free producer exists: there are as many as connections
      producer = Producer{};
      producer.active = true;
      producer.point = opening.points.produced;
      producer.api = request.t_to_o_rpi;
      producer.priority = request.t_to_o.priority;
      producer.size = opening.spec.produced_size;
      producer.next = context.now;
      if (request.t_to_o.type == ConnectionType::kMulticast) {
        producer.multicast = true;
        producer.multicast_index = opening.multicast_index;
        producer.connection_id = NewConnectionId();
        producer.to = Ipv4Endpoint{base::Ipv4Address(opening.multicast_group), kIoPort};
      } else {
        producer.connection_id = request.t_to_o_connection_id;
        const bool port_given = context.request_t_to_o && context.request_t_to_o->port != 0;
        producer.to = Ipv4Endpoint{context.peer.address, port_given ? context.request_t_to_o->port : kIoPort};
      }
      connection.producer = static_cast<int>(free - producers_.begin());
    }
    const Producer& producer = producers_[static_cast<std::size_t>(connection.producer)];
    connection.t_to_o_id = producer.connection_id;
    connection.t_to_o_api = producer.api;
    if (producer.multicast) {
      context.reply_t_to_o = SocketAddress{SocketAddress::kAfInet, kIoPort, producer.to.address.HostOrder()};
    }
  }
  connection.open = true;
  table_marks_.NoteTaken(ActiveConnections());
  if (connection.explicit_slot != kNone) explicit_marks_.NoteTaken(ExplicitInUse());
  if (connection.producer != kNone) production_marks_.NoteTaken(ActiveProducers());
  NotifyChanged();
  return ForwardOpenSuccess{connection.o_to_t_id, connection.t_to_o_id, connection.triad, connection.o_to_t_api,
                            connection.t_to_o_api};
}

// ---- Forward_Close and closing -----------------------------------------------------------------------

ServiceStatus ConnectionManager::ForwardClose(const ServiceRequest& service, base::ByteWriter& reply) {
  ++counters_.close_requests;
  const Decoded<ForwardCloseRequest> decoded = DecodeForwardClose(service.data);
  const ConnectionTriad& triad = decoded.request.triad;
  switch (decoded.framing) {
    case RequestFraming::kFixedPartShort:
      ++counters_.close_format_rejects;
      return Error(GeneralStatus::kNotEnoughData);
    case RequestFraming::kPathShort:
      ++counters_.close_format_rejects;
      return EncodeConnectionFailure(ConnectionFailure::General(GeneralStatus::kNotEnoughData), triad, reply);
    case RequestFraming::kExtraData:
      ++counters_.close_format_rejects;
      return EncodeConnectionFailure(ConnectionFailure::General(GeneralStatus::kTooMuchData), triad, reply);
    case RequestFraming::kOk:
      break;
  }
  const int index = FindByTriad(triad);
  const bool same_originator =
      service.context == nullptr || index == kNone ||
      connections_[static_cast<std::size_t>(index)].originator_address == service.context->peer.address;
  if (index == kNone || !same_originator) {
    ++counters_.close_other_rejects;
    return EncodeConnectionFailure(ConnectionFailure::Extended(kExtendedConnectionNotFound), triad, reply);
  }
  Close(static_cast<std::size_t>(index), CloseReason::kForwardClose);
  EncodeForwardCloseSuccess(triad, reply);
  return Success();
}

void ConnectionManager::Close(std::size_t index, CloseReason reason) {
  Connection& connection = connections_[index];
  if (!connection.open) return;
  connection.open = false;
  if (connection.explicit_slot != kNone) explicit_in_use_[static_cast<std::size_t>(connection.explicit_slot)] = false;
  if (events_ != nullptr) events_->OnConnectionClosed(InfoOf(connection), reason);
  CloseOrphanedListeners();
  ReleaseUnusedProducers();
  NotifyChanged();
}

void ConnectionManager::CloseOrphanedListeners() {
  for (Connection& connection : connections_) {
    if (connection.open && connection.transport_class == 1 && connection.kind == IoConnectionKind::kListenOnly &&
        !HasProducerOf(connection.points.produced, false)) {
      connection.open = false;
      if (events_ != nullptr) events_->OnConnectionClosed(InfoOf(connection), CloseReason::kProducerGone);
    }
  }
}

void ConnectionManager::ReleaseUnusedProducers() {
  for (std::size_t i = 0; i < producers_.size(); ++i) {
    if (!producers_[i].active) continue;
    const bool used = std::any_of(connections_.begin(), connections_.end(),
                                  [&](const Connection& c) { return c.open && c.producer == static_cast<int>(i); });
    if (!used) producers_[i].active = false;
  }
}

void ConnectionManager::NotifyChanged() {
  if (events_ != nullptr) events_->OnConnectionsChanged();
}

// ---- Pools -------------------------------------------------------------------------------------------

void ConnectionManager::NoteExhausted(const Opening& opening) {
  switch (opening.exhausted) {
    case Opening::Exhausted::kNone:
      break;
    case Opening::Exhausted::kTable:
      table_marks_.NoteRefused();
      break;
    case Opening::Exhausted::kExplicit:
      explicit_marks_.NoteRefused();
      break;
    case Opening::Exhausted::kMulticastGroups:
      production_marks_.NoteRefused();
      break;
  }
}

std::size_t ConnectionManager::ExplicitInUse() const {
  return static_cast<std::size_t>(std::count(explicit_in_use_.begin(), explicit_in_use_.end(), true));
}

std::size_t ConnectionManager::ActiveProducers() const {
  return static_cast<std::size_t>(
      std::count_if(producers_.begin(), producers_.end(), [](const Producer& p) { return p.active; }));
}

base::PoolStats ConnectionManager::explicit_pool() const {
  return explicit_marks_.Stats(ExplicitInUse(), options_.max_explicit_connections);
}

base::PoolStats ConnectionManager::production_pool() const {
  return production_marks_.Stats(ActiveProducers(), producers_.size());
}

// ---- Lookups -----------------------------------------------------------------------------------------

int ConnectionManager::FindFree() const {
  for (std::size_t i = 0; i < connections_.size(); ++i) {
    if (!connections_[i].open) return static_cast<int>(i);
  }
  return kNone;
}

int ConnectionManager::FindByTriad(const ConnectionTriad& triad) const {
  for (std::size_t i = 0; i < connections_.size(); ++i) {
    if (connections_[i].open && connections_[i].triad == triad) return static_cast<int>(i);
  }
  return kNone;
}

int ConnectionManager::FindMulticastProducer(std::uint32_t point) const {
  for (std::size_t i = 0; i < producers_.size(); ++i) {
    if (producers_[i].active && producers_[i].multicast && producers_[i].point == point) return static_cast<int>(i);
  }
  return kNone;
}

bool ConnectionManager::HasProducerOf(std::uint32_t point, bool listen_only_too) const {
  return std::any_of(connections_.begin(), connections_.end(), [&](const Connection& c) {
    return c.open && c.transport_class == 1 && c.points.produced == point &&
           (listen_only_too || c.kind != IoConnectionKind::kListenOnly);
  });
}

bool ConnectionManager::IsOwned(std::uint32_t consumed_point) const {
  return std::any_of(connections_.begin(), connections_.end(), [&](const Connection& c) {
    return c.open && c.transport_class == 1 && c.kind == IoConnectionKind::kExclusiveOwner &&
           c.points.consumed == consumed_point;
  });
}

bool ConnectionManager::OwnedByAnotherOriginator(base::Ipv4Address originator_address) const {
  return std::any_of(connections_.begin(), connections_.end(), [&](const Connection& c) {
    return c.open && c.transport_class == 1 && c.kind == IoConnectionKind::kExclusiveOwner &&
           c.originator_address != originator_address;
  });
}

bool ConnectionManager::IdInUse(std::uint32_t id) const {
  const bool by_connection = std::any_of(connections_.begin(), connections_.end(), [&](const Connection& c) {
    return c.open && (c.o_to_t_id == id || c.t_to_o_id == id);
  });
  const bool by_producer = std::any_of(producers_.begin(), producers_.end(),
                                       [&](const Producer& p) { return p.active && p.connection_id == id; });
  return by_connection || by_producer;
}

std::uint32_t ConnectionManager::NewConnectionId() {
  // Random IDs, so that a stranger cannot guess where to inject I/O data; a collision with a live ID
  // (or 0) is drawn again, and the loop stays bounded by falling back to counting up.
  std::uint32_t id = random_.NextU32();
  for (int attempt = 0; attempt < 4 && (id == 0 || IdInUse(id)); ++attempt) id = random_.NextU32();
  while (id == 0 || IdInUse(id)) ++id;
  return id;
}

ConnectionInfo ConnectionManager::InfoOf(const Connection& connection) const {
  ConnectionInfo info{connection.transport_class,    connection.kind,      connection.points,   connection.triad,
                      connection.originator_address, connection.o_to_t_id, connection.t_to_o_id};
  info.o_to_t_api = connection.o_to_t_api;
  info.t_to_o_api = connection.t_to_o_api;
  info.timeout = connection.timeout;
  info.run = connection.run;
  info.multicast = connection.producer != kNone && producers_[static_cast<std::size_t>(connection.producer)].multicast;
  return info;
}

std::size_t ConnectionManager::ListConnections(std::span<ConnectionInfo> out) const {
  std::size_t count = 0;
  for (const Connection& connection : connections_) {
    if (!connection.open || count == out.size()) continue;
    out[count++] = InfoOf(connection);
  }
  return count;
}

base::Status AttachConnectionManager(CipDevice& device, ConnectionManager& cm) {
  const base::Status registered = device.objects().Register(cm.object());
  if (!registered.ok()) return registered;
  device.encapsulation().set_connected_handler(&cm);
  device.message_router_object().set_connection_counter(&cm);
  return base::OkStatus();
}

}  // namespace cip
