#include "eip_client.h"

#include <cstdio>

#include "cip/encapsulation.h"
#include "failure.h"

namespace ipe {

EipSession::EipSession(const std::string& host, std::uint16_t port, int timeout_ms) : tcp_(host, port, timeout_ms) {
  const std::vector<std::uint8_t> reply = Exchange(EncodeRegisterSession(), 0x65);
  (void)reply;
}

EipSession::~EipSession() {
  if (session_ == 0) return;
  try {
    tcp_.Send(EncodeUnRegisterSession(session_));  // never answered
  } catch (const Failure&) {
    // The session ends with the connection anyway.
  }
}

std::vector<std::uint8_t> EipSession::Exchange(std::span<const std::uint8_t> message, std::uint16_t command) {
  tcp_.Send(message);
  const std::vector<std::uint8_t> head = tcp_.Receive(cip::kEncapsulationHeaderSize);
  const base::Result<cip::EncapsulationHeader> header = cip::DecodeEncapsulationHeader(head);
  if (!header.ok() || header.value().command != command) {
    Fail(kExitUnreachable, tcp_.name() + ": the reply is not the encapsulation reply expected");
  }
  std::vector<std::uint8_t> body = tcp_.Receive(header.value().length);
  if (header.value().status != 0) {
    char text[96];
    std::snprintf(text, sizeof text, "encapsulation status 0x%04X", static_cast<unsigned>(header.value().status));
    Fail(kExitRefused, tcp_.name() + ": the card refused the request: " + text);
  }
  if (command == 0x65) session_ = header.value().session_handle;
  return body;
}

CipReply EipSession::Request(std::uint8_t service, const CipPath& path, std::span<const std::uint8_t> data) {
  return RequestRaw(EncodeCipRequest(service, path, data));
}

CipReply EipSession::RequestRaw(std::span<const std::uint8_t> cip_request) {
  const std::vector<std::uint8_t> body = Exchange(EncodeSendRRData(session_, cip_request), 0x6F);
  std::optional<CipReply> reply = DecodeSendRRDataReply(body);
  if (!reply) Fail(kExitUnreachable, tcp_.name() + ": the CIP reply does not decode");
  return *reply;
}

}  // namespace ipe
