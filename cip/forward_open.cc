#include "cip/forward_open.h"

namespace cip {
namespace {

constexpr std::uint8_t kRoutePort = 1;       // "backplane" port of a Logix-style route: this device ...
constexpr std::uint8_t kRouteLocalSlot = 0;  // ... when the slot is 0 (as Unconnected_Send accepts)
constexpr std::uint8_t kEthernetIpPort = 2;  // the card's one CIP port
constexpr std::uint8_t kCompatibilityBit = 0x80;

template <typename Request>
Decoded<Request> Frame(base::ByteReader& in, std::size_t path_words, Decoded<Request> decoded) {
  decoded.request.connection_path = in.Bytes(2 * path_words);
  if (!in.ok()) {
    decoded.framing = RequestFraming::kPathShort;
  } else if (!in.empty()) {
    decoded.framing = RequestFraming::kExtraData;
  } else {
    decoded.framing = RequestFraming::kOk;
  }
  return decoded;
}

ConnectionTriad ReadTriad(base::ByteReader& in) {
  ConnectionTriad triad;
  triad.connection_serial = in.U16Le();
  triad.originator_vendor = in.U16Le();
  triad.originator_serial = in.U32Le();
  return triad;
}

void WriteTriad(const ConnectionTriad& triad, base::ByteWriter& out) {
  out.U16Le(triad.connection_serial);
  out.U16Le(triad.originator_vendor);
  out.U32Le(triad.originator_serial);
}

}  // namespace

NetworkConnectionParameters DecodeNetworkParameters16(std::uint16_t word) {
  NetworkConnectionParameters parameters;
  parameters.redundant_owner = (word & 0x8000) != 0;
  parameters.type = static_cast<ConnectionType>((word >> 13) & 0x3);
  parameters.priority = static_cast<ConnectionPriority>((word >> 10) & 0x3);
  parameters.variable = (word & 0x0200) != 0;
  parameters.size = word & 0x01FF;
  return parameters;
}

NetworkConnectionParameters DecodeNetworkParameters32(std::uint32_t word) {
  NetworkConnectionParameters parameters;
  parameters.redundant_owner = (word & 0x80000000U) != 0;
  parameters.type = static_cast<ConnectionType>((word >> 29) & 0x3);
  parameters.priority = static_cast<ConnectionPriority>((word >> 26) & 0x3);
  parameters.variable = (word & 0x02000000U) != 0;
  parameters.size = static_cast<std::uint16_t>(word & 0xFFFF);
  return parameters;
}

std::uint16_t EncodeNetworkParameters16(const NetworkConnectionParameters& parameters) {
  std::uint16_t word = parameters.size & 0x01FF;
  if (parameters.redundant_owner) word |= 0x8000;
  word = static_cast<std::uint16_t>(word | static_cast<std::uint16_t>(parameters.type) << 13);
  word = static_cast<std::uint16_t>(word | static_cast<std::uint16_t>(parameters.priority) << 10);
  if (parameters.variable) word |= 0x0200;
  return word;
}

std::uint32_t EncodeNetworkParameters32(const NetworkConnectionParameters& parameters) {
  std::uint32_t word = parameters.size;
  if (parameters.redundant_owner) word |= 0x80000000U;
  word |= static_cast<std::uint32_t>(parameters.type) << 29;
  word |= static_cast<std::uint32_t>(parameters.priority) << 26;
  if (parameters.variable) word |= 0x02000000U;
  return word;
}

TransportClassTrigger DecodeTransportClassTrigger(std::uint8_t byte) {
  return TransportClassTrigger{(byte & 0x80) != 0, static_cast<std::uint8_t>((byte >> 4) & 0x07),
                               static_cast<std::uint8_t>(byte & 0x0F)};
}

std::uint8_t EncodeTransportClassTrigger(const TransportClassTrigger& transport) {
  return static_cast<std::uint8_t>((transport.server ? 0x80 : 0) | (transport.trigger & 0x07) << 4 |
                                   (transport.transport_class & 0x0F));
}

Decoded<ForwardOpenRequest> DecodeForwardOpen(std::span<const std::uint8_t> data, bool large) {
  Decoded<ForwardOpenRequest> decoded;
  ForwardOpenRequest& request = decoded.request;
  request.large = large;
  if (data.size() < (large ? kLargeForwardOpenFixedSize : kForwardOpenFixedSize)) return decoded;
  base::ByteReader in(data);
  request.priority_tick = in.U8();
  request.timeout_ticks = in.U8();
  request.o_to_t_connection_id = in.U32Le();
  request.t_to_o_connection_id = in.U32Le();
  request.triad = ReadTriad(in);
  request.timeout_multiplier = in.U8();
  in.Skip(3);
  request.o_to_t_rpi = in.U32Le();
  request.o_to_t = large ? DecodeNetworkParameters32(in.U32Le()) : DecodeNetworkParameters16(in.U16Le());
  request.t_to_o_rpi = in.U32Le();
  request.t_to_o = large ? DecodeNetworkParameters32(in.U32Le()) : DecodeNetworkParameters16(in.U16Le());
  request.transport = DecodeTransportClassTrigger(in.U8());
  const std::size_t path_words = in.U8();
  return Frame(in, path_words, decoded);
}

Decoded<ForwardCloseRequest> DecodeForwardClose(std::span<const std::uint8_t> data) {
  Decoded<ForwardCloseRequest> decoded;
  if (data.size() < kForwardCloseFixedSize) return decoded;
  base::ByteReader in(data);
  decoded.request.priority_tick = in.U8();
  decoded.request.timeout_ticks = in.U8();
  decoded.request.triad = ReadTriad(in);
  const std::size_t path_words = in.U8();
  in.Skip(1);  // reserved
  return Frame(in, path_words, decoded);
}

void EncodeForwardOpen(const ForwardOpenRequest& request, base::ByteWriter& out) {
  out.U8(request.priority_tick);
  out.U8(request.timeout_ticks);
  out.U32Le(request.o_to_t_connection_id);
  out.U32Le(request.t_to_o_connection_id);
  WriteTriad(request.triad, out);
  out.U8(request.timeout_multiplier);
  out.Zeros(3);
  out.U32Le(request.o_to_t_rpi);
  if (request.large) {
    out.U32Le(EncodeNetworkParameters32(request.o_to_t));
  } else {
    out.U16Le(EncodeNetworkParameters16(request.o_to_t));
  }
  out.U32Le(request.t_to_o_rpi);
  if (request.large) {
    out.U32Le(EncodeNetworkParameters32(request.t_to_o));
  } else {
    out.U16Le(EncodeNetworkParameters16(request.t_to_o));
  }
  out.U8(EncodeTransportClassTrigger(request.transport));
  out.U8(static_cast<std::uint8_t>(request.connection_path.size() / 2));
  out.Bytes(request.connection_path);
}

void EncodeForwardClose(const ForwardCloseRequest& request, base::ByteWriter& out) {
  out.U8(request.priority_tick);
  out.U8(request.timeout_ticks);
  WriteTriad(request.triad, out);
  out.U8(static_cast<std::uint8_t>(request.connection_path.size() / 2));
  out.U8(0);
  out.Bytes(request.connection_path);
}

ParsedConnectionPath ParseConnectionPath(std::span<const std::uint8_t> padded_path) {
  ParsedConnectionPath parsed;
  ConnectionPath& path = parsed.path;
  EpathReader reader(padded_path);
  PathSegment segment;
  bool routing_allowed = true;  // port segments only before everything else
  while (reader.Next(segment)) {
    if (path.has_data) return {kExtendedInvalidRouteSegment, {}};  // the data segment comes last
    switch (segment.kind) {
      case SegmentKind::kPort: {
        if (!routing_allowed) return {kExtendedInvalidRouteSegment, {}};
        const bool local =
            segment.value == kRoutePort && segment.bytes.size() == 1 && segment.bytes[0] == kRouteLocalSlot;
        if (local) break;
        if (segment.value == kRoutePort || segment.value == kEthernetIpPort) return {kExtendedInvalidRouteNode, {}};
        return {kExtendedInvalidRoutePort, {}};
      }
      case SegmentKind::kElectronicKey:
        if (path.key || path.class_id != 0) return {kExtendedInvalidRouteSegment, {}};
        path.key = segment.key;
        break;
      case SegmentKind::kClass:
        if (path.class_id != 0 && segment.value != path.class_id) return {kExtendedInvalidRouteSegment, {}};
        path.class_id = segment.value;
        break;
      case SegmentKind::kInstance:
      case SegmentKind::kConnectionPoint:
        if (path.class_id == 0) return {kExtendedInvalidRouteSegment, {}};
        if (segment.kind == SegmentKind::kInstance && !path.instance && path.point_count == 0) {
          path.instance = segment.value;
          break;
        }
        if (path.point_count == path.points.size()) return {kExtendedInvalidRouteSegment, {}};
        path.points[path.point_count++] = segment.value;
        break;
      case SegmentKind::kSimpleData:
        if (path.class_id == 0) return {kExtendedInvalidRouteSegment, {}};
        path.has_data = true;
        path.data = segment.bytes;
        break;
      default:
        return {kExtendedInvalidRouteSegment, {}};
    }
    routing_allowed = segment.kind == SegmentKind::kPort;
  }
  if (!reader.status().ok() || path.class_id == 0) return {kExtendedInvalidRouteSegment, {}};
  return parsed;
}

std::uint16_t CheckElectronicKey(const ElectronicKey& key, const DeviceKey& device) {
  const bool vendor_ok = key.vendor_id == 0 || key.vendor_id == device.vendor_id;
  const bool product_ok = key.product_code == 0 || key.product_code == device.product_code;
  if (!vendor_ok || !product_ok) return kExtendedVendorOrProductCode;
  if (key.device_type != 0 && key.device_type != device.device_type) return kExtendedDeviceType;
  const std::uint8_t major = key.major_revision & static_cast<std::uint8_t>(~kCompatibilityBit);
  const std::uint8_t minor = key.minor_revision;
  if ((key.major_revision & kCompatibilityBit) != 0) {
    if (major != device.major_revision || minor == 0 || minor > device.minor_revision) return kExtendedRevision;
    return 0;
  }
  if (major == 0) return 0;
  if (major != device.major_revision || (minor != 0 && minor != device.minor_revision)) return kExtendedRevision;
  return 0;
}

ConnectionFailure ConnectionFailure::Extended(std::uint16_t extended) {
  ConnectionFailure failure;
  failure.extended = extended;
  return failure;
}

ConnectionFailure ConnectionFailure::WithSize(std::uint16_t extended, std::uint16_t size) {
  ConnectionFailure failure = Extended(extended);
  failure.extra[0] = size;
  failure.extra_count = 1;
  return failure;
}

ConnectionFailure ConnectionFailure::WithRpi(std::uint16_t extended, std::uint8_t o_to_t_type, std::uint32_t o_to_t_rpi,
                                             std::uint8_t t_to_o_type, std::uint32_t t_to_o_rpi) {
  ConnectionFailure failure = Extended(extended);
  failure.extra = {static_cast<std::uint16_t>(o_to_t_type | t_to_o_type << 8), static_cast<std::uint16_t>(o_to_t_rpi),
                   static_cast<std::uint16_t>(o_to_t_rpi >> 16), static_cast<std::uint16_t>(t_to_o_rpi),
                   static_cast<std::uint16_t>(t_to_o_rpi >> 16)};
  failure.extra_count = 5;
  return failure;
}

ConnectionFailure ConnectionFailure::General(GeneralStatus general) {
  ConnectionFailure failure;
  failure.general = general;
  return failure;
}

ServiceStatus EncodeConnectionFailure(const ConnectionFailure& failure, const ConnectionTriad& triad,
                                      base::ByteWriter& reply) {
  ServiceStatus status = Error(failure.general);
  status.keep_reply_data = true;
  if (failure.extended != 0) {
    reply.U16Le(failure.extended);
    for (std::size_t i = 0; i < failure.extra_count && i < failure.extra.size(); ++i) reply.U16Le(failure.extra[i]);
    status.additional_words_in_data = static_cast<std::uint8_t>(1 + failure.extra_count);
  }
  WriteTriad(triad, reply);
  reply.U8(failure.remaining_path_words);
  reply.U8(0);  // reserved
  return status;
}

void EncodeForwardOpenSuccess(const ForwardOpenSuccess& success, base::ByteWriter& reply) {
  reply.U32Le(success.o_to_t_connection_id);
  reply.U32Le(success.t_to_o_connection_id);
  WriteTriad(success.triad, reply);
  reply.U32Le(success.o_to_t_api);
  reply.U32Le(success.t_to_o_api);
  reply.U8(0);  // application reply size (words)
  reply.U8(0);  // reserved
}

void EncodeForwardCloseSuccess(const ConnectionTriad& triad, base::ByteWriter& reply) {
  WriteTriad(triad, reply);
  reply.U8(0);  // application reply size (words)
  reply.U8(0);  // reserved
}

}  // namespace cip
