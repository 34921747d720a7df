// libFuzzer target for the EtherNet/IP encapsulation layer and the Common Packet Format (cip/), with the
// whole CipDevice behind it (fakes of cip/test/cip_fakes.h).
//
// The first input byte picks what is exercised:
//   0 TCP: the rest is a stream cut into chunks; each chunk is a length byte and that many bytes. A
//     length byte of 0 lets 61 s pass (inactivity timeouts, delayed replies fire); 0xFF closes the
//     connection and opens a new one.
//   1 UDP: byte 1 bit 0 = broadcast; the rest is one datagram. Then time passes and due replies go.
//   2 CPF: the rest is decoded as a Common Packet Format packet (and as SendRRData/SendUnitData data).
// Oracles: every reply is a well-formed encapsulation message no longer than kMaxReplyMessage; the
// stream always makes progress; the session table never exceeds kMaxSessions; a CPF packet that decodes
// re-encodes to exactly the same bytes (round trip), and the layout parsers never disagree with it.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "cip/cpf.h"
#include "cip_fakes.h"

namespace {

using cip::kEncapsulationHeaderSize;

void Require(bool condition) {
  if (!condition) __builtin_trap();
}

void CheckReply(std::span<const std::uint8_t> reply) {
  if (reply.empty()) return;
  Require(reply.size() >= kEncapsulationHeaderSize && reply.size() <= cip::kMaxReplyMessage);
  const base::Result<cip::EncapsulationHeader> header = cip::DecodeEncapsulationHeader(reply);
  Require(header.ok());
  Require(header->length == reply.size() - kEncapsulationHeaderSize);
  Require(header->options == 0);
}

void FuzzTcp(std::span<const std::uint8_t> input) {
  cip::test::FakeCard card;
  cip::EncapsulationServer& server = card.cip.encapsulation();
  hal::Micros now = 1;
  cip::TcpConnectionId id = server.OpenTcpConnection(cip::Ipv4Endpoint{base::Ipv4Address(0x0A000202), 50000}, now).value();
  while (!input.empty()) {
    const std::size_t length = input[0];
    input = input.subspan(1);
    if (length == 0) {
      now += 61 * hal::kMicrosPerSecond;
      cip::TcpConnectionId expired;
      while (server.TakeExpiredConnection(now, expired)) server.CloseTcpConnection(expired);
      cip::DueDatagram due;
      while (server.TakeDueDatagram(now, due)) CheckReply(due.bytes);
      if (server.connection_count() == 0) id = server.OpenTcpConnection(cip::Ipv4Endpoint{base::Ipv4Address(1), 2}, now).value();
      continue;
    }
    if (length == 0xFF) {
      server.CloseTcpConnection(id);
      id = server.OpenTcpConnection(cip::Ipv4Endpoint{base::Ipv4Address(0x0A000203), 50001}, now).value();
      continue;
    }
    std::span<const std::uint8_t> chunk = input.first(length < input.size() ? length : input.size());
    input = input.subspan(chunk.size());
    while (!chunk.empty()) {
      const cip::TcpStep step = server.OnTcpData(id, chunk, now);
      Require(step.consumed > 0 && step.consumed <= chunk.size());
      CheckReply(step.reply);
      chunk = chunk.subspan(step.consumed);
      Require(server.session_count() <= cip::kMaxSessions);
      if (step.close) {
        server.CloseTcpConnection(id);
        id = server.OpenTcpConnection(cip::Ipv4Endpoint{base::Ipv4Address(0x0A000204), 50002}, now).value();
        break;
      }
    }
  }
}

void FuzzUdp(std::span<const std::uint8_t> input) {
  if (input.empty()) return;
  cip::test::FakeCard card;
  cip::EncapsulationServer& server = card.cip.encapsulation();
  const cip::UdpSource source{cip::Ipv4Endpoint{base::Ipv4Address(0x0A000202), 44818}, (input[0] & 1) != 0};
  const cip::UdpDecision decision = server.OnUdpDatagram(input.subspan(1), source, 1);
  CheckReply(decision.reply);
  Require(decision.action != cip::UdpDecision::Action::kSendNow || !decision.reply.empty());
  if (decision.action == cip::UdpDecision::Action::kSendLater) {
    // Within the largest delay a sender can ask for: 65535 ms.
    Require(decision.send_at >= 1 && decision.send_at <= 1 + 65535 * hal::kMicrosPerMilli);
    cip::DueDatagram due;
    Require(server.TakeDueDatagram(decision.send_at, due));
    CheckReply(due.bytes);
  }
}

void FuzzCpf(std::span<const std::uint8_t> input) {
  const base::Result<cip::CpfPacket> packet = cip::DecodeCpf(input);
  if (packet.ok()) {
    std::vector<std::uint8_t> buffer(input.size() + 8);
    base::ByteWriter out(buffer);
    out.U16Le(static_cast<std::uint16_t>(packet->count));
    for (std::size_t i = 0; i < packet->count; ++i) {
      out.U16Le(packet->items[i].type);
      out.U16Le(static_cast<std::uint16_t>(packet->items[i].data.size()));
      out.Bytes(packet->items[i].data);
    }
    Require(out.ok() && out.size() == input.size());
    Require(std::equal(input.begin(), input.end(), out.written().begin()));
    const base::Result<cip::UnconnectedMessage> unconnected = cip::ParseUnconnectedMessage(*packet);
    if (unconnected.ok()) Require(packet->count >= 2 && unconnected->request.size() <= input.size());
    const base::Result<cip::ConnectedMessage> connected = cip::ParseConnectedMessage(*packet);
    if (connected.ok()) Require(packet->count == 2);
  }
  const base::Result<cip::SendDataCommand> command = cip::DecodeSendDataCommand(input);
  if (command.ok()) Require(input.size() >= 8);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::span<const std::uint8_t> rest(data + 1, size - 1);
  switch (data[0] % 3) {
    case 0:
      FuzzTcp(rest);
      break;
    case 1:
      FuzzUdp(rest);
      break;
    default:
      FuzzCpf(rest);
      break;
  }
  return 0;
}
