// discover (ListIdentity over UDP) and identity (the Identity object over TCP).
#include <arpa/inet.h>

#include <chrono>
#include <cstdio>
#include <set>

#include "cip/cip_status.h"
#include "cip/encapsulation.h"
#include "commands.h"
#include "failure.h"
#include "socket_io.h"

namespace ipe {
namespace {

std::string Hex(std::uint32_t value, int digits) {
  char text[16];
  std::snprintf(text, sizeof text, "0x%0*X", digits, value);
  return text;
}

std::string IdentityFields(const cip::IdentityItem& id) {
  return "vendor=" + std::to_string(id.vendor_id) + " product_code=" + std::to_string(id.product_code) +
         " product_name=\"" + ProductNameOf(id) + "\" serial=" + Hex(id.serial_number, 8) +
         " revision=" + std::to_string(id.major_revision) + "." + std::to_string(id.minor_revision) +
         " status=" + Hex(id.status, 4);
}

}  // namespace

int RunDiscover(const Options& options) {
  in_addr target{};
  target.s_addr = htonl(INADDR_BROADCAST);
  if (!options.broadcast.empty()) target = ResolveHost(options.broadcast);
  if (!options.interface_name.empty()) target = InterfaceBroadcast(options.interface_name);
  UdpSocket socket(in_addr{htonl(INADDR_ANY)}, 0);
  if (!options.interface_name.empty()) socket.BindToDevice(options.interface_name);
  const std::uint16_t port = options.port.value_or(cip::kEncapsulationPort);
  socket.SendTo(EncodeListIdentityRequest(), target, port);

  // Cards answer a broadcast after a random delay of up to 2 s (the request's context asks for none):
  // collect answers until the timeout.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::milliseconds(options.timeout_ms);
  std::set<std::uint32_t> seen;
  int found = 0;
  for (;;) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) break;
    std::vector<std::uint8_t> bytes;
    sockaddr_in from{};
    if (!socket.ReceiveFrom(bytes, from, static_cast<int>(left.count()))) continue;
    const base::Result<cip::EncapsulationHeader> header = cip::DecodeEncapsulationHeader(bytes);
    if (!header.ok() || header.value().command != static_cast<std::uint16_t>(cip::EncapCommand::kListIdentity) ||
        header.value().status != 0 || bytes.size() != cip::kEncapsulationHeaderSize + header.value().length) {
      continue;
    }
    const std::optional<cip::IdentityItem> identity =
        DecodeListIdentityReply(std::span<const std::uint8_t>(bytes).subspan(cip::kEncapsulationHeaderSize));
    if (!identity || !seen.insert(from.sin_addr.s_addr).second) continue;
    // The answer's own socket address is the card's address as it knows it (behind NAT, e.g. the
    // loopback port, it differs from where the answer came from): both are shown.
    in_addr own{};
    own.s_addr = htonl(identity->socket_address.address);
    std::printf("%s card_ip=%s %s\n", FormatAddress(from.sin_addr).c_str(), FormatAddress(own).c_str(),
                IdentityFields(*identity).c_str());
    std::fflush(stdout);
    ++found;
  }
  if (found == 0) {
    std::fprintf(stderr, "ipe: discover: no card answered within %u ms\n", options.timeout_ms);
    return kExitUnreachable;
  }
  return kExitOk;
}

int RunIdentity(const Options& options) {
  EipSession session(options.args[0], DefaultPort(options), static_cast<int>(options.timeout_ms));
  const CipReply reply = session.Request(cip::kServiceGetAttributesAll, {cip::kClassIdentity, 1, std::nullopt});
  if (!reply.ok()) Fail(kExitRefused, "identity: refused by the card: " + FormatCipStatus(reply));
  const std::optional<cip::IdentityItem> id = DecodeIdentityAttributes(reply.data);
  if (!id) Fail(kExitUnreachable, "identity: the reply does not decode");
  const std::optional<Model> model = ModelFromProductCode(id->product_code);
  std::printf("vendor_id = %u\n", id->vendor_id);
  std::printf("device_type = %u\n", id->device_type);
  std::printf("product_code = %u (%s)\n", id->product_code, model ? ModelName(*model) : "unknown model");
  std::printf("revision = %u.%u\n", id->major_revision, id->minor_revision);
  std::printf("status = %s\n", Hex(id->status, 4).c_str());
  std::printf("serial_number = %s\n", Hex(id->serial_number, 8).c_str());
  std::printf("product_name = %s\n", ProductNameOf(*id).c_str());
  return kExitOk;
}

}  // namespace ipe
