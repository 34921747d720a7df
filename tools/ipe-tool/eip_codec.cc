#include "eip_codec.h"

#include <cstdio>

#include "base/byte_reader.h"
#include "base/byte_writer.h"
#include "cip/cip_status.h"
#include "cip/cpf.h"
#include "cip/drive/parameter_object.h"
#include "cip/epath.h"
#include "cip/message_router.h"

namespace ipe {
namespace {

constexpr std::size_t kScratch = 600;

Bytes Finish(const base::ByteWriter& out) { return Bytes(out.written().begin(), out.written().end()); }

Bytes Encapsulate(cip::EncapCommand command, std::uint32_t session, std::span<const std::uint8_t> data) {
  std::vector<std::uint8_t> buffer(cip::kEncapsulationHeaderSize + data.size());
  base::ByteWriter out(buffer);
  cip::EncapsulationHeader header;
  header.command = static_cast<std::uint16_t>(command);
  header.length = static_cast<std::uint16_t>(data.size());
  header.session_handle = session;
  cip::EncodeEncapsulationHeader(header, out);
  out.Bytes(data);
  return Finish(out);
}

const char* GeneralStatusName(std::uint8_t general) {
  switch (general) {
    case 0x01: return "connection failure";
    case 0x02: return "resource unavailable";
    case 0x04: return "path segment error";
    case 0x05: return "path destination unknown";
    case 0x08: return "service not supported";
    case 0x09: return "invalid attribute value";
    case 0x0C: return "object state conflict";
    case 0x0E: return "attribute not settable";
    case 0x10: return "device state conflict";
    case 0x11: return "reply data too large";
    case 0x13: return "not enough data";
    case 0x14: return "attribute not supported";
    case 0x15: return "too much data";
    case 0x16: return "object does not exist";
    case 0x19: return "store operation failure";
    case 0x1E: return "embedded service error";
    case 0x20: return "invalid parameter";
    default: return "error";
  }
}

void ReadShortString(base::ByteReader& in, cip::FixedString<32>& text) {
  const std::uint8_t length = in.U8();
  const std::span<const std::uint8_t> chars = in.Bytes(length);
  if (!text.Assign(chars)) (void)text.Assign(chars.first(cip::FixedString<32>::kCapacity));
}

// Identity attributes 1-7 in their wire order (Get_Attributes_All and the ListIdentity item alike).
void ReadIdentityFields(base::ByteReader& in, cip::IdentityItem& identity) {
  identity.vendor_id = in.U16Le();
  identity.device_type = in.U16Le();
  identity.product_code = in.U16Le();
  identity.major_revision = in.U8();
  identity.minor_revision = in.U8();
  identity.status = in.U16Le();
  identity.serial_number = in.U32Le();
  ReadShortString(in, identity.product_name);
}

}  // namespace

ParameterAddress ParameterAddressOf(std::uint16_t number) {
  using cip::drive::ParameterClass;
  if (const auto instance = cip::drive::ParameterInstance(ParameterClass::k64, number)) {
    return {cip::drive::kClassParameter64, *instance};
  }
  const auto instance = cip::drive::ParameterInstance(ParameterClass::k65, number);
  return {cip::drive::kClassParameter65, instance.value_or(number)};
}

Bytes EncodeCipRequest(std::uint8_t service, const CipPath& path, std::span<const std::uint8_t> data) {
  std::uint8_t path_bytes[16];
  base::ByteWriter path_out(path_bytes);
  cip::EncodeLogicalSegment(cip::SegmentKind::kClass, path.class_id, path_out);
  cip::EncodeLogicalSegment(cip::SegmentKind::kInstance, path.instance, path_out);
  if (path.attribute) cip::EncodeLogicalSegment(cip::SegmentKind::kAttribute, *path.attribute, path_out);
  std::vector<std::uint8_t> buffer(kScratch + data.size());
  base::ByteWriter out(buffer);
  cip::EncodeMessageRouterRequest({service, path_out.written(), data}, out);
  return Finish(out);
}

Bytes EncodeRegisterSession() {
  std::uint8_t data[4];
  base::ByteWriter out(data);
  out.U16Le(cip::kEncapsulationProtocolVersion);
  out.U16Le(0);  // options
  return Encapsulate(cip::EncapCommand::kRegisterSession, 0, out.written());
}

Bytes EncodeUnRegisterSession(std::uint32_t session) {
  return Encapsulate(cip::EncapCommand::kUnRegisterSession, session, {});
}

Bytes EncodeListIdentityRequest() {
  // Bytes 0-1 of the sender context: the longest a target may delay its answer to a broadcast, in ms
  // (0 means 2000). 500 ms, the shortest the card accepts, keeps discover quick.
  Bytes message = Encapsulate(cip::EncapCommand::kListIdentity, 0, {});
  message[12] = static_cast<std::uint8_t>(kListIdentityMaxDelayMs & 0xFF);
  message[13] = static_cast<std::uint8_t>(kListIdentityMaxDelayMs >> 8);
  return message;
}

Bytes EncodeSendRRData(std::uint32_t session, std::span<const std::uint8_t> cip_request) {
  std::vector<std::uint8_t> buffer(kScratch + cip_request.size());
  base::ByteWriter out(buffer);
  out.U32Le(0);  // interface handle: CIP
  out.U16Le(0);  // timeout: the target ignores it
  out.U16Le(2);  // item count
  cip::FinishCpfItem(out, cip::BeginCpfItem(out, cip::CpfItemType::kNullAddress));
  const std::size_t at = cip::BeginCpfItem(out, cip::CpfItemType::kUnconnectedData);
  out.Bytes(cip_request);
  cip::FinishCpfItem(out, at);
  return Encapsulate(cip::EncapCommand::kSendRRData, session, out.written());
}

std::optional<CipReply> DecodeSendRRDataReply(std::span<const std::uint8_t> command_data) {
  const base::Result<cip::SendDataCommand> command = cip::DecodeSendDataCommand(command_data);
  if (!command.ok()) return std::nullopt;
  const base::Result<cip::UnconnectedMessage> message = cip::ParseUnconnectedMessage(command.value().packet);
  if (!message.ok()) return std::nullopt;
  const base::Result<cip::MessageRouterReply> reply = cip::DecodeMessageRouterReply(message.value().request);
  if (!reply.ok()) return std::nullopt;
  CipReply out;
  out.service = reply.value().service;
  out.general = static_cast<std::uint8_t>(reply.value().general);
  base::ByteReader words(reply.value().additional_status);
  while (words.remaining() >= 2) out.additional.push_back(words.U16Le());
  out.data.assign(reply.value().data.begin(), reply.value().data.end());
  return out;
}

std::string FormatCipStatus(const CipReply& reply) {
  char text[96];
  if (reply.additional.empty()) {
    std::snprintf(text, sizeof text, "general status 0x%02X (%s)", reply.general, GeneralStatusName(reply.general));
  } else {
    std::snprintf(text, sizeof text, "general status 0x%02X extended 0x%04X (%s)", reply.general,
                  reply.additional.front(), GeneralStatusName(reply.general));
  }
  return text;
}

std::optional<cip::IdentityItem> DecodeListIdentityReply(std::span<const std::uint8_t> command_data) {
  base::ByteReader in(command_data);
  if (in.U16Le() < 1) return std::nullopt;  // item count
  if (in.U16Le() != cip::kItemListIdentity) return std::nullopt;
  const std::uint16_t length = in.U16Le();
  base::ByteReader item = in.Take(length);
  cip::IdentityItem identity;
  (void)item.U16Le();  // encapsulation protocol version
  identity.socket_address = cip::DecodeSocketAddress(item);
  ReadIdentityFields(item, identity);
  identity.state = item.U8();
  if (!in.ok() || !item.ok()) return std::nullopt;
  return identity;
}

std::optional<cip::IdentityItem> DecodeIdentityAttributes(std::span<const std::uint8_t> data) {
  base::ByteReader in(data);
  cip::IdentityItem identity;
  ReadIdentityFields(in, identity);
  if (!in.ok()) return std::nullopt;
  return identity;
}

std::string ProductNameOf(const cip::IdentityItem& item) {
  const std::span<const std::uint8_t> bytes = item.product_name.bytes();
  return std::string(bytes.begin(), bytes.end());
}

}  // namespace ipe
