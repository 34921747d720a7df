#include "cip/encapsulation.h"

#include <string_view>

namespace cip {

base::Result<EncapsulationHeader> DecodeEncapsulationHeader(std::span<const std::uint8_t> bytes) {
  if (bytes.size() < kEncapsulationHeaderSize) return base::OutOfRange();
  ByteReader in(bytes.first(kEncapsulationHeaderSize));
  EncapsulationHeader header;
  header.command = in.U16();
  header.length = in.U16();
  header.session_handle = in.U32();
  header.status = in.U32();
  const std::span<const std::uint8_t> context = in.Bytes(header.sender_context.size());
  for (std::size_t i = 0; i < context.size(); ++i) header.sender_context[i] = context[i];
  header.options = in.U32();
  if (!in.ok()) return base::Internal();  // cannot happen: 24 bytes were checked above
  return header;
}

void EncodeEncapsulationHeader(const EncapsulationHeader& header, ByteWriter& out) {
  out.U16(header.command);
  out.U16(header.length);
  out.U32(header.session_handle);
  out.U32(header.status);
  out.Bytes(header.sender_context);
  out.U32(header.options);
}

EncapsulationHeader ReplyHeaderFor(const EncapsulationHeader& request, EncapStatus status) {
  EncapsulationHeader reply;
  reply.command = request.command;
  reply.length = 0;
  reply.session_handle = request.session_handle;
  reply.status = static_cast<std::uint32_t>(status);
  reply.sender_context = request.sender_context;
  reply.options = 0;
  return reply;
}

void EncodeListIdentityData(const IdentityItem& identity, ByteWriter& out) {
  out.U16(1);  // item count
  out.U16(kItemListIdentity);
  const std::size_t length_at = out.size();
  out.U16(0);  // item length, patched below
  const std::size_t item_start = out.size();
  out.U16(kEncapsulationProtocolVersion);
  EncodeSocketAddress(identity.socket_address, out);
  out.U16(identity.vendor_id);
  out.U16(identity.device_type);
  out.U16(identity.product_code);
  out.U8(identity.major_revision);
  out.U8(identity.minor_revision);
  out.U16(identity.status);
  out.U32(identity.serial_number);
  out.U8(static_cast<std::uint8_t>(identity.product_name.size()));
  out.Bytes(identity.product_name.bytes());
  out.U8(identity.state);
  out.PatchU16(length_at, static_cast<std::uint16_t>(out.size() - item_start));
}

void EncodeListServicesData(ByteWriter& out) {
  // One service, "Communications": 16 bytes of name, NUL-padded.
  static constexpr std::string_view kName = "Communications";
  static constexpr std::size_t kNameField = 16;
  out.U16(1);  // item count
  out.U16(kItemListServices);
  out.U16(static_cast<std::uint16_t>(2 + 2 + kNameField));
  out.U16(kEncapsulationProtocolVersion);
  out.U16(kCapabilityCipOverTcp | kCapabilityCipClass0And1OverUdp);
  for (char c : kName) out.U8(static_cast<std::uint8_t>(c));
  out.Zeros(kNameField - kName.size());
}

void EncodeListInterfacesData(ByteWriter& out) {
  out.U16(0);  // no non-CIP interfaces: the item count is 0
}

}  // namespace cip
