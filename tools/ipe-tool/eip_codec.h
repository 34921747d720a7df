// The bytes tools/ipe exchanges with a card over EtherNet/IP, encoded and decoded with the project's
// own cores (cip/encapsulation.h, cpf.h, epath.h, message_router.h). Pure functions on spans: no I/O,
// nothing read past a span's end.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "cip/encapsulation.h"

namespace ipe {

using Bytes = std::vector<std::uint8_t>;

// A message router request's target.
struct CipPath {
  std::uint16_t class_id = 0;
  std::uint32_t instance = 0;
  std::optional<std::uint16_t> attribute;
};

// Class 0x64 attribute 3 (instance = number + 0x4000 for 0000-0FFF, number - 0x8000 for F000-FFFF),
// class 0x65 (instance = number) for the rest (the c-parameters Cxxx).
// Where a drive register lives among the card's Parameter objects (docs/drive-objects.md).
struct ParameterAddress {
  std::uint16_t class_id = 0;
  std::uint32_t instance = 0;
};
ParameterAddress ParameterAddressOf(std::uint16_t number);

// The message router request: service, path (logical segments), data.
Bytes EncodeCipRequest(std::uint8_t service, const CipPath& path, std::span<const std::uint8_t> data);

// Whole encapsulation messages (header + command data).
Bytes EncodeRegisterSession();
Bytes EncodeUnRegisterSession(std::uint32_t session);
Bytes EncodeSendRRData(std::uint32_t session, std::span<const std::uint8_t> cip_request);
// ListIdentity asking for an answer within kListIdentityMaxDelayMs.
inline constexpr std::uint16_t kListIdentityMaxDelayMs = 500;
Bytes EncodeListIdentityRequest();

// A decoded message router reply.
struct CipReply {
  std::uint8_t service = 0;  // with the reply bit
  std::uint8_t general = 0;
  std::vector<std::uint16_t> additional;  // additional status words (extended status first)
  Bytes data;

  bool ok() const { return general == 0; }
};

// The SendRRData command data of a reply (after the 24-byte header): interface handle, timeout, the CPF
// items, the message router reply. Nothing when any layer does not decode.
std::optional<CipReply> DecodeSendRRDataReply(std::span<const std::uint8_t> command_data);

// "general status 0x0E (attribute not settable)", "general status 0x01 extended 0x0106 (connection
// failure)": what a refused request is reported with.
std::string FormatCipStatus(const CipReply& reply);

// The command data of a ListIdentity reply: one identity item. Nothing when it does not decode.
std::optional<cip::IdentityItem> DecodeListIdentityReply(std::span<const std::uint8_t> command_data);

// The Identity object's Get_Attributes_All reply data (attributes 1-7).
std::optional<cip::IdentityItem> DecodeIdentityAttributes(std::span<const std::uint8_t> data);

// "1.8", "VF-MB1" etc. as text; the Identity status word as "0x0030".
std::string ProductNameOf(const cip::IdentityItem& item);

}  // namespace ipe
