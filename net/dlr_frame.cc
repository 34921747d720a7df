#include "net/dlr_frame.h"

#include "base/byte_reader.h"
#include "base/byte_writer.h"

namespace net {
namespace {

constexpr std::uint8_t kStatusPort1 = 0x01;
constexpr std::uint8_t kStatusPort2 = 0x02;
constexpr std::uint8_t kStatusNeighbor = 0x80;
constexpr std::size_t kSignOnListOffset = kDlrCommonHeaderSize + 2;  // after the node count
constexpr std::size_t kSignOnCountOffset = kDlrCommonHeaderSize;

bool KnownFrameType(std::uint8_t type) { return type >= 1 && type <= 10; }

base::Result<DlrRingState> ReadRingState(base::ByteReader& in) {
  const std::uint8_t state = in.U8();
  if (!in.ok()) return base::OutOfRange();
  if (state != 1 && state != 2) return base::InvalidArgument();
  return static_cast<DlrRingState>(state);
}

// The fields after the common header; `in` is positioned at offset 12 of the PDU.
base::Status ReadTypeFields(base::ByteReader& in, DlrFrame& frame) {
  switch (frame.type) {
    case DlrFrameType::kBeacon: {
      const auto state = ReadRingState(in);
      if (!state.ok()) return state.status();
      frame.ring_state = *state;
      frame.precedence = in.U8();
      frame.interval_us = in.U32Be();
      frame.timeout_us = in.U32Be();
      break;
    }
    case DlrFrameType::kAnnounce: {
      const auto state = ReadRingState(in);
      if (!state.ok()) return state.status();
      frame.ring_state = *state;
      break;
    }
    case DlrFrameType::kNeighborCheckResponse:
      frame.request_source_port = in.U8();
      break;
    case DlrFrameType::kLinkStatus:
      frame.link_status = DlrLinkStatus::Decode(in.U8());
      break;
    case DlrFrameType::kSignOn:
      frame.sign_on_nodes = in.U16Be();
      in.Skip(static_cast<std::size_t>(frame.sign_on_nodes) * kDlrSignOnEntrySize);
      break;
    case DlrFrameType::kAdvertise:
      frame.gateway_state = in.U8();
      frame.precedence = in.U8();
      frame.interval_us = in.U32Be();
      frame.timeout_us = in.U32Be();
      frame.learning_update_enable = in.U8() != 0;
      break;
    case DlrFrameType::kFlushTables:
      frame.learning_update_enable = in.U8() != 0;
      break;
    case DlrFrameType::kNeighborCheckRequest:
    case DlrFrameType::kLocateFault:
    case DlrFrameType::kLearningUpdate:
      break;
  }
  return in.ok() ? base::OkStatus() : base::OutOfRange();
}

// Ethernet header (tagged when the PDU has 42 bytes), common header; returns the PDU's offset.
std::size_t WriteHeaders(const DlrOrigin& origin, DlrFrameType type, bool tagged, base::ByteWriter& out) {
  origin.destination.Write(out);
  origin.source.Write(out);
  if (tagged) {
    out.U16Be(kVlanTagType);
    out.U16Be(kDlrTagControl);
  }
  out.U16Be(kDlrEtherType);
  const std::size_t pdu = out.size();
  out.U8(kDlrRingSubtype);
  out.U8(kDlrProtocolVersion);
  out.U8(static_cast<std::uint8_t>(type));
  out.U8(origin.source_port);
  origin.source_ip.Write(out);
  out.U32Be(origin.sequence_id);
  return pdu;
}

// Zero-fills the PDU's reserved tail up to `pdu_size` and the frame up to the Ethernet minimum.
base::Result<std::size_t> Finish(base::ByteWriter& out, std::size_t pdu_offset, std::size_t pdu_size) {
  if (out.size() < pdu_offset + pdu_size) out.Zeros(pdu_offset + pdu_size - out.size());
  if (out.size() < kEthernetMinFrameSize) out.Zeros(kEthernetMinFrameSize - out.size());
  return out.Finish();
}

base::Result<std::size_t> BuildFixed(const DlrOrigin& origin, DlrFrameType type, const std::uint8_t* field,
                                     std::span<std::uint8_t> out) {
  base::ByteWriter writer(out);
  const std::size_t pdu = WriteHeaders(origin, type, true, writer);
  if (field != nullptr) writer.U8(*field);
  return Finish(writer, pdu, kDlrPduSize);
}

}  // namespace

std::uint8_t DlrLinkStatus::Encode() const {
  return static_cast<std::uint8_t>((port1_active ? kStatusPort1 : 0) | (port2_active ? kStatusPort2 : 0) |
                                   (neighbor_status ? kStatusNeighbor : 0));
}

DlrLinkStatus DlrLinkStatus::Decode(std::uint8_t byte) {
  return {(byte & kStatusPort1) != 0, (byte & kStatusPort2) != 0, (byte & kStatusNeighbor) != 0};
}

namespace {

// Reads the addresses, one 802.1Q tag if there is one, and the EtherType; true for a DLR frame.
bool ReadDlrEthernetHeader(base::ByteReader& in, DlrFrame& frame) {
  frame.destination = base::MacAddress::Read(in);
  frame.source = base::MacAddress::Read(in);
  std::uint16_t ether_type = in.U16Be();
  if (ether_type == kVlanTagType) {
    frame.tagged = true;
    frame.tag_control = in.U16Be();
    ether_type = in.U16Be();
  }
  return in.ok() && ether_type == kDlrEtherType;
}

}  // namespace

bool IsDlrFrame(std::span<const std::uint8_t> bytes) {
  base::ByteReader in(bytes);
  DlrFrame header;
  return ReadDlrEthernetHeader(in, header);
}

base::Result<DlrFrame> ParseDlrFrame(std::span<const std::uint8_t> bytes) {
  base::ByteReader in(bytes);
  DlrFrame frame;
  if (!ReadDlrEthernetHeader(in, frame)) return base::NotFound();
  frame.pdu_offset = in.position();

  const std::uint8_t subtype = in.U8();
  const std::uint8_t version = in.U8();
  const std::uint8_t type = in.U8();
  frame.source_port = in.U8();
  frame.source_ip = base::Ipv4Address::Read(in);
  frame.sequence_id = in.U32Be();
  if (!in.ok()) return base::OutOfRange();
  if (subtype != kDlrRingSubtype || version != kDlrProtocolVersion || !KnownFrameType(type)) {
    return base::InvalidArgument();
  }
  frame.type = static_cast<DlrFrameType>(type);
  const base::Status fields = ReadTypeFields(in, frame);
  if (!fields.ok()) return fields;
  return frame;
}

DlrNode SignOnNode(std::span<const std::uint8_t> frame, const DlrFrame& parsed, std::size_t index) {
  base::ByteReader in(frame);
  in.Skip(parsed.pdu_offset + kSignOnListOffset + index * kDlrSignOnEntrySize);
  DlrNode node;
  node.mac = base::MacAddress::Read(in);
  node.ip = base::Ipv4Address::Read(in);
  return node;
}

base::Result<std::size_t> BuildNeighborCheckRequest(const DlrOrigin& origin, std::span<std::uint8_t> out) {
  return BuildFixed(origin, DlrFrameType::kNeighborCheckRequest, nullptr, out);
}

base::Result<std::size_t> BuildNeighborCheckResponse(const DlrOrigin& origin, std::uint8_t request_source_port,
                                                     std::span<std::uint8_t> out) {
  return BuildFixed(origin, DlrFrameType::kNeighborCheckResponse, &request_source_port, out);
}

base::Result<std::size_t> BuildLinkStatus(const DlrOrigin& origin, DlrLinkStatus status,
                                          std::span<std::uint8_t> out) {
  const std::uint8_t byte = status.Encode();
  return BuildFixed(origin, DlrFrameType::kLinkStatus, &byte, out);
}

base::Result<std::size_t> BuildLearningUpdate(const DlrOrigin& origin, std::span<std::uint8_t> out) {
  base::ByteWriter writer(out);
  const std::size_t pdu = WriteHeaders(origin, DlrFrameType::kLearningUpdate, false, writer);
  return Finish(writer, pdu, kDlrLearningUpdatePduSize);
}

base::Result<std::size_t> BuildSignOn(std::span<const std::uint8_t> received, const DlrFrame& parsed,
                                      const base::MacAddress& destination, const DlrNode& self, bool append,
                                      std::span<std::uint8_t> out) {
  const std::size_t list_end =
      parsed.pdu_offset + kSignOnListOffset + static_cast<std::size_t>(parsed.sign_on_nodes) * kDlrSignOnEntrySize;
  if (parsed.type != DlrFrameType::kSignOn || list_end > received.size()) return base::InvalidArgument();
  if (append && !SignOnHasRoom(parsed.sign_on_nodes)) return base::ResourceExhausted();

  base::ByteWriter writer(out);
  destination.Write(writer);
  self.mac.Write(writer);
  // The tag (if any), EtherType, common header, count and list as received.
  writer.Bytes(received.subspan(2 * base::MacAddress::kSize, list_end - 2 * base::MacAddress::kSize));
  if (append) {
    writer.PatchU16Be(parsed.pdu_offset + kSignOnCountOffset, static_cast<std::uint16_t>(parsed.sign_on_nodes + 1));
    self.mac.Write(writer);
    self.ip.Write(writer);
  }
  return Finish(writer, parsed.pdu_offset, kDlrPduSize);
}

}  // namespace net
