#include "cip/message_router.h"

namespace cip {
namespace {

constexpr std::size_t kReplyHeaderSize = 4;
constexpr std::uint8_t kRoutePort = 1;          // the port a Logix-style route names for "this chassis"
constexpr std::uint8_t kRouteLocalSlot = 0;     // ... and the slot that is this device
constexpr std::uint8_t kEthernetIpPort = 2;     // the card's one CIP port (Port object instance 1)

bool Is(const ApplicationPath& path, std::uint16_t class_id, std::uint32_t instance) {
  return path.class_id == class_id && path.instance == instance && !path.attribute && !path.member;
}

// Checks an Unconnected_Send route path: empty, or port 1 / link 0 segments only. Returns the
// extended status of the first segment that leads elsewhere, 0 when the route is local.
std::uint16_t CheckRoute(std::span<const std::uint8_t> route) {
  EpathReader reader(route);
  PathSegment segment;
  while (reader.Next(segment)) {
    if (segment.kind != SegmentKind::kPort) return kExtendedInvalidRouteSegment;
    const bool local_slot = segment.bytes.size() == 1 && segment.bytes[0] == kRouteLocalSlot;
    if (segment.value == kRoutePort && local_slot) continue;
    if (segment.value == kRoutePort || segment.value == kEthernetIpPort) return kExtendedInvalidRouteNode;
    return kExtendedInvalidRoutePort;
  }
  return reader.status().ok() ? 0 : kExtendedInvalidRouteSegment;
}

// Writes the reply header in front of the data already in `out` (which starts with 4 placeholder
// bytes), or replaces everything with an error reply.
std::size_t FinishReply(std::uint8_t request_service, ServiceStatus status, base::ByteWriter& out) {
  if (!out.ok()) status = Error(GeneralStatus::kReplyDataTooLarge);
  if (status.ok() || (status.keep_reply_data && !status.has_extended)) {
    out.PatchU8(0, static_cast<std::uint8_t>(request_service | kReplyServiceBit));
    out.PatchU8(1, 0);
    out.PatchU8(2, static_cast<std::uint8_t>(status.general));
    out.PatchU8(3, status.ok() ? 0 : status.additional_words_in_data);
  } else {
    out.Truncate(0);
    EncodeErrorReply(request_service, status, out);
  }
  return out.ok() ? out.size() : 0;
}

}  // namespace

base::Result<MessageRouterRequest> DecodeMessageRouterRequest(std::span<const std::uint8_t> bytes) {
  base::ByteReader in(bytes);
  MessageRouterRequest request;
  request.service = in.U8();
  const std::uint8_t path_words = in.U8();
  request.path = in.Bytes(2U * path_words);
  if (!in.ok()) return base::OutOfRange();
  request.data = in.Rest();
  return request;
}

void EncodeMessageRouterRequest(const MessageRouterRequest& request, base::ByteWriter& out) {
  out.U8(request.service);
  out.U8(static_cast<std::uint8_t>(request.path.size() / 2));
  out.Bytes(request.path);
  out.Bytes(request.data);
}

base::Result<MessageRouterReply> DecodeMessageRouterReply(std::span<const std::uint8_t> bytes) {
  base::ByteReader in(bytes);
  MessageRouterReply reply;
  reply.service = in.U8();
  in.Skip(1);  // reserved
  reply.general = static_cast<GeneralStatus>(in.U8());
  const std::uint8_t words = in.U8();
  reply.additional_status = in.Bytes(2U * words);
  if (!in.ok()) return base::OutOfRange();
  reply.data = in.Rest();
  return reply;
}

void EncodeErrorReply(std::uint8_t request_service, const ServiceStatus& status, base::ByteWriter& out) {
  out.U8(static_cast<std::uint8_t>(request_service | kReplyServiceBit));
  out.U8(0);
  out.U8(static_cast<std::uint8_t>(status.general));
  out.U8(status.has_extended ? 1 : 0);
  if (status.has_extended) out.U16Le(status.extended);
}

std::size_t MessageRouter::Handle(std::span<const std::uint8_t> request_bytes, RequestContext& context,
                                  std::span<std::uint8_t> reply, int depth) {
  base::ByteWriter out(reply);
  const base::Result<MessageRouterRequest> request = DecodeMessageRouterRequest(request_bytes);
  const std::uint8_t service = request_bytes.empty() ? 0 : request_bytes[0];
  if (!request.ok()) {
    EncodeErrorReply(service, Error(GeneralStatus::kPathSegmentError), out);
    return out.ok() ? out.size() : 0;
  }
  if ((service & kReplyServiceBit) != 0) {
    EncodeErrorReply(service, Error(GeneralStatus::kServiceNotSupported), out);
    return out.ok() ? out.size() : 0;
  }
  const base::Result<ApplicationPath> path = DecodeApplicationPath(request->path);
  if (!path.ok()) {
    EncodeErrorReply(service, Error(GeneralStatus::kPathSegmentError), out);
    return out.ok() ? out.size() : 0;
  }
  const bool unconnected_send =
      service == kServiceUnconnectedSend && Is(*path, kClassConnectionManager, 1);
  const bool multiple_service_packet =
      service == kServiceMultipleServicePacket && Is(*path, kClassMessageRouter, 1);
  if ((unconnected_send || multiple_service_packet) && depth >= kMaxNesting) {
    EncodeErrorReply(service, Error(GeneralStatus::kResourceUnavailable), out);
    return out.ok() ? out.size() : 0;
  }
  if (unconnected_send) return UnconnectedSend(*request, context, reply, depth);

  out.Zeros(kReplyHeaderSize);
  if (!out.ok()) return 0;
  const ServiceStatus status = multiple_service_packet
                                   ? MultipleServicePacket(request->data, context, out, depth)
                                   : Dispatch(*request, *path, context, out);
  return FinishReply(service, status, out);
}

ServiceStatus MessageRouter::Dispatch(const MessageRouterRequest& request, const ApplicationPath& path,
                                      RequestContext& context, base::ByteWriter& reply) {
  CipObject* object = objects_.Find(path.class_id);
  if (object == nullptr) return Error(GeneralStatus::kPathDestinationUnknown);
  if (!object->HasInstance(path.instance)) return Error(GeneralStatus::kObjectDoesNotExist);
  // Service support is decided before the attribute, member or data are looked at (CT finding, see
  // docs/ethernetip.md): an unimplemented service is 0x08 whatever else the request holds.
  if (!object->SupportsService(path.instance, request.service)) return Error(GeneralStatus::kServiceNotSupported);
  if (path.member) return Error(GeneralStatus::kPathDestinationUnknown);
  ServiceRequest service_request;
  service_request.service = request.service;
  service_request.path = path;
  service_request.data = request.data;
  service_request.context = &context;
  if (guard_ != nullptr) {
    const ServiceStatus admitted = guard_->Admit(service_request);
    if (!admitted.ok()) return admitted;
  }
  return object->Execute(service_request, reply);
}

ServiceStatus MessageRouter::MultipleServicePacket(std::span<const std::uint8_t> data, RequestContext& context,
                                                   base::ByteWriter& reply, int depth) {
  base::ByteReader in(data);
  const std::uint16_t count = in.U16Le();
  if (!in.ok() || in.remaining() < 2U * count) return Error(GeneralStatus::kNotEnoughData);
  const std::size_t table_end = 2 + 2U * count;

  // Offsets count from the start of the service count; each embedded request runs to the next offset
  // (the last one to the end). They must lie inside the data and go strictly up.
  std::size_t previous = 0;
  for (std::size_t i = 0; i < count; ++i) {
    const std::size_t offset = in.U16Le();
    if (offset < table_end || offset >= data.size()) return Error(GeneralStatus::kNotEnoughData);
    if (offset <= previous) return Error(GeneralStatus::kInvalidParameter);
    previous = offset;
  }

  const std::size_t base = reply.size();
  reply.U16Le(count);
  reply.Zeros(2U * count);
  bool any_failed = false;
  for (std::size_t i = 0; i < count && reply.ok(); ++i) {
    base::ByteReader offsets(data.subspan(2 + 2 * i));
    const std::size_t start = offsets.U16Le();
    const std::size_t end = i + 1 < count ? offsets.U16Le() : data.size();
    reply.PatchU16Le(base + 2 + 2 * i, static_cast<std::uint16_t>(reply.size() - base));
    const std::size_t size = Handle(data.subspan(start, end - start), context, reply.Tail(), depth + 1);
    // A deferred member defers the whole packet: the retry runs every member again from the first.
    if (context.pending) return Success();
    if (size == 0) return Error(GeneralStatus::kReplyDataTooLarge);
    const std::span<const std::uint8_t> member_reply = reply.Tail().first(size);
    if (member_reply[2] != static_cast<std::uint8_t>(GeneralStatus::kSuccess)) any_failed = true;
    reply.Advance(size);
  }
  if (!any_failed) return Success();
  ServiceStatus status = Error(GeneralStatus::kEmbeddedServiceError);
  status.keep_reply_data = true;
  return status;
}

std::size_t MessageRouter::UnconnectedSend(const MessageRouterRequest& request, RequestContext& context,
                                           std::span<std::uint8_t> reply, int depth) {
  base::ByteWriter out(reply);
  base::ByteReader in(request.data);
  in.Skip(2);  // priority/time tick and timeout ticks: the card answers at once
  const std::uint16_t embedded_size = in.U16Le();
  const std::span<const std::uint8_t> embedded = in.Bytes(embedded_size);
  if (embedded_size % 2 != 0) in.Skip(1);  // pad byte
  const std::uint8_t route_words = in.U8();
  in.Skip(1);  // reserved
  const std::span<const std::uint8_t> route = in.Bytes(2U * route_words);
  ServiceStatus status;
  if (!in.ok() || embedded_size == 0) {
    status = Error(GeneralStatus::kNotEnoughData);
  } else if (!in.empty()) {
    status = Error(GeneralStatus::kTooMuchData);
  } else if (const std::uint16_t routing_error = CheckRoute(route); routing_error != 0) {
    EncodeErrorReply(request.service, ErrorWithExtended(GeneralStatus::kConnectionFailure, routing_error), out);
    out.U8(route_words);  // remaining path size: no hop of the route was taken
    out.U8(0);            // reserved (what Wireshark's CIP dissector reads after it)
    return out.ok() ? out.size() : 0;
  } else {
    return Handle(embedded, context, reply, depth + 1);
  }
  EncodeErrorReply(request.service, status, out);
  return out.ok() ? out.size() : 0;
}

}  // namespace cip
