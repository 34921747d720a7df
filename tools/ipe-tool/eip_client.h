// An EtherNet/IP explicit-messaging session with a card: TCP 44818, RegisterSession, unconnected
// (SendRRData) requests, UnRegisterSession at the end.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string>

#include "eip_codec.h"
#include "socket_io.h"

namespace ipe {

class EipSession {
 public:
  // Fails with kExitUnreachable when the card does not answer, kExitRefused when it refuses the session.
  EipSession(const std::string& host, std::uint16_t port, int timeout_ms);
  ~EipSession();
  EipSession(const EipSession&) = delete;
  EipSession& operator=(const EipSession&) = delete;

  // One request, its reply (which may carry an error status: the caller decides). Fails with
  // kExitUnreachable when no valid reply comes, kExitRefused on an encapsulation error status.
  CipReply Request(std::uint8_t service, const CipPath& path, std::span<const std::uint8_t> data = {});
  // The same with the encoded message router request (Forward_Open, whose data cip/ encodes).
  CipReply RequestRaw(std::span<const std::uint8_t> cip_request);

  in_addr peer() const { return tcp_.peer(); }

 private:
  std::vector<std::uint8_t> Exchange(std::span<const std::uint8_t> message, std::uint16_t command);

  TcpConnection tcp_;
  std::uint32_t session_ = 0;
};

}  // namespace ipe
