#include "cip/encapsulation.h"

#include <string_view>

namespace cip {

base::Result<EncapsulationHeader> DecodeEncapsulationHeader(std::span<const std::uint8_t> bytes) {
  if (bytes.size() < kEncapsulationHeaderSize) return base::OutOfRange();
  base::ByteReader in(bytes.first(kEncapsulationHeaderSize));
  EncapsulationHeader header;
  header.command = in.U16Le();
  header.length = in.U16Le();
  header.session_handle = in.U32Le();
  header.status = in.U32Le();
  const std::span<const std::uint8_t> context = in.Bytes(header.sender_context.size());
  for (std::size_t i = 0; i < context.size(); ++i) header.sender_context[i] = context[i];
  header.options = in.U32Le();
  if (!in.ok()) return base::Internal();  // cannot happen: 24 bytes were checked above
  return header;
}

void EncodeEncapsulationHeader(const EncapsulationHeader& header, base::ByteWriter& out) {
  out.U16Le(header.command);
  out.U16Le(header.length);
  out.U32Le(header.session_handle);
  out.U32Le(header.status);
  out.Bytes(header.sender_context);
  out.U32Le(header.options);
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

void EncodeListIdentityData(const IdentityItem& identity, base::ByteWriter& out) {
  out.U16Le(1);  // item count
  out.U16Le(kItemListIdentity);
  const std::size_t length_at = out.size();
  out.U16Le(0);  // item length, patched below
  const std::size_t item_start = out.size();
  out.U16Le(kEncapsulationProtocolVersion);
  EncodeSocketAddress(identity.socket_address, out);
  out.U16Le(identity.vendor_id);
  out.U16Le(identity.device_type);
  out.U16Le(identity.product_code);
  out.U8(identity.major_revision);
  out.U8(identity.minor_revision);
  out.U16Le(identity.status);
  out.U32Le(identity.serial_number);
  out.U8(static_cast<std::uint8_t>(identity.product_name.size()));
  out.Bytes(identity.product_name.bytes());
  out.U8(identity.state);
  out.PatchU16Le(length_at, static_cast<std::uint16_t>(out.size() - item_start));
}

void EncodeListServicesData(base::ByteWriter& out) {
  // One service, "Communications": 16 bytes of name, NUL-padded.
  static constexpr std::string_view kName = "Communications";
  static constexpr std::size_t kNameField = 16;
  out.U16Le(1);  // item count
  out.U16Le(kItemListServices);
  out.U16Le(static_cast<std::uint16_t>(2 + 2 + kNameField));
  out.U16Le(kEncapsulationProtocolVersion);
  out.U16Le(kCapabilityCipOverTcp | kCapabilityCipClass0And1OverUdp);
  for (char c : kName) out.U8(static_cast<std::uint8_t>(c));
  out.Zeros(kNameField - kName.size());
}

void EncodeListInterfacesData(base::ByteWriter& out) {
  out.U16Le(0);  // no non-CIP interfaces: the item count is 0
}

}  // namespace cip
