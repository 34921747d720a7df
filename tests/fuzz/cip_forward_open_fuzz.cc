// libFuzzer target for the connection manager (cip/forward_open, cip/io_connection,
// cip/connection_manager*): Forward_Open / Large_Forward_Open / Forward_Close decoding and validation,
// connection paths, class 1 datagrams on UDP 2222, production and timeouts, class 3 requests. A
// CipDevice on the fakes of cip/test/cip_fakes.h with the connection manager attached and the fake
// I/O application of cip/test/cip_connection_fakes.h; an exclusive owner (O->T ID 0x11223344) and a
// class 3 connection (O->T ID 0x12233445) are open before the input runs.
//
// Input: the whole input goes through every decoder once; then it is read as records
//   kind (1 byte), length (1 byte), length bytes
// kind % 4: 0 a message router request (Forward_Open etc. to class 6), 1 a datagram on UDP 2222 from
// the originator, 2 time passes (length × 1 ms, then every due production is taken), 3 a SendUnitData
// request (sequence count = its first two bytes) on the class 3 connection.
// Oracles:
// - decoders stay inside their input; decoded spans lie inside it; framing is consistent with sizes;
// - every router reply fits, decodes, has the reply bit; a refused Forward_Open / Forward_Close carries
//   exactly its 10 bytes of error data (or none, when the request was too short to have a triad);
// - at most kMaxCipConnections connections; datagrams fit kMaxIoDatagram and parse back; production
//   never runs early (NextDeadline is not in the past after taking everything due).
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "cip/connection_manager.h"
#include "cip/forward_open.h"
#include "cip/io_connection.h"
#include "cip/message_router.h"
#include "cip_connection_fakes.h"

namespace {

void Require(bool condition) {
  if (!condition) __builtin_trap();
}

bool Inside(std::span<const std::uint8_t> part, std::span<const std::uint8_t> whole) {
  return part.empty() || (part.data() >= whole.data() && part.data() + part.size() <= whole.data() + whole.size());
}

void CheckDecoders(std::span<const std::uint8_t> input) {
  for (const bool large : {false, true}) {
    const cip::Decoded<cip::ForwardOpenRequest> open = cip::DecodeForwardOpen(input, large);
    const std::size_t fixed = large ? cip::kLargeForwardOpenFixedSize : cip::kForwardOpenFixedSize;
    Require((open.framing == cip::RequestFraming::kFixedPartShort) == (input.size() < fixed));
    if (open.framing == cip::RequestFraming::kOk) {
      Require(Inside(open.request.connection_path, input));
      Require(fixed + open.request.connection_path.size() == input.size());
      // Round trip.
      std::vector<std::uint8_t> again(input.size() + 8);
      base::ByteWriter out(again);
      cip::EncodeForwardOpen(open.request, out);
      Require(out.ok());
      const cip::Decoded<cip::ForwardOpenRequest> reread = cip::DecodeForwardOpen(out.written(), large);
      Require(reread.framing == cip::RequestFraming::kOk && reread.request.triad == open.request.triad);
      Require(reread.request.t_to_o.type == open.request.t_to_o.type);
    }
  }
  const cip::Decoded<cip::ForwardCloseRequest> close = cip::DecodeForwardClose(input);
  if (close.framing == cip::RequestFraming::kOk) Require(Inside(close.request.connection_path, input));
  const cip::ParsedConnectionPath path = cip::ParseConnectionPath(input);
  if (path.extended == 0) {
    Require(path.path.class_id != 0 && path.path.point_count <= 2);
    Require(Inside(path.path.data, input));
  }
  const base::Result<cip::ReceivedIoDatagram> datagram = cip::ParseIoDatagram(input);
  if (datagram.ok()) Require(Inside(datagram->data, input));
}

void CheckRouterReply(std::span<const std::uint8_t> request, std::span<const std::uint8_t> reply) {
  Require(reply.size() >= 4);
  const base::Result<cip::MessageRouterReply> decoded = cip::DecodeMessageRouterReply(reply);
  Require(decoded.ok());
  Require((decoded->service & cip::kReplyServiceBit) != 0);
  const std::uint8_t service = request.empty() ? 0 : request[0];
  const bool connection_service = service == cip::kServiceForwardOpen || service == cip::kServiceLargeForwardOpen ||
                                  service == cip::kServiceForwardClose;
  if (decoded->general == cip::GeneralStatus::kSuccess || !connection_service) return;
  if (decoded->general == cip::GeneralStatus::kConnectionFailure) {
    Require(!decoded->additional_status.empty());
    // A refused Forward_Open / Forward_Close: triad, remaining path size, reserved.
    Require(decoded->data.size() == 10);
  } else {
    Require(decoded->data.empty() || decoded->data.size() == 10);
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::span<const std::uint8_t> input(data, size);
  CheckDecoders(input);

  cip::test::ConnectionCard card;
  (void)card.Open();
  cip::test::OpenParams explicit_params = cip::test::ExplicitParams();
  explicit_params.triad.connection_serial = 0x2000;
  (void)card.Open(explicit_params);

  std::size_t at = 0;
  while (at + 2 <= size) {
    const std::uint8_t kind = data[at] % 4;
    const std::size_t length = data[at + 1];
    at += 2;
    if (length > size - at) break;
    const std::span<const std::uint8_t> record(data + at, length);
    at += length;
    switch (kind) {
      case 0: {
        const cip::test::Bytes request(record.begin(), record.end());
        const cip::test::Bytes reply = card.Ask(request);
        CheckRouterReply(record, reply);
        break;
      }
      case 1:
        card.cm.OnIoDatagram(record, cip::Ipv4Endpoint{cip::test::kOriginator, cip::kIoPort}, card.now);
        break;
      case 2: {
        card.now += static_cast<hal::Micros>(length) * 1000;
        cip::IoDatagram datagram;
        int taken = 0;
        while (card.cm.TakeDueProduction(card.now, datagram)) {
          Require(datagram.bytes.size() <= cip::kMaxIoDatagram);
          Require(cip::ParseIoDatagram(datagram.bytes).ok());
          Require(++taken <= static_cast<int>(cip::kMaxCipConnections));  // one per producer: no burst
        }
        Require(card.cm.NextDeadline() > card.now);
        break;
      }
      default: {
        if (record.size() < 2) break;
        cip::RequestContext context;
        context.now = card.now;
        context.session_handle = cip::test::kSession;
        context.peer = cip::Ipv4Endpoint{cip::test::kOriginator, 50000};
        std::array<std::uint8_t, 600> reply{};
        std::uint32_t reply_id = 0;
        const std::uint16_t sequence = static_cast<std::uint16_t>(record[0] | record[1] << 8);
        const std::size_t reply_size =
            card.cm.HandleConnected(0x12233445, sequence, record.subspan(2), context, reply, reply_id);
        Require(reply_size <= reply.size());
        if (reply_size > 0) Require(reply_size >= 6 && reply_id != 0);
        break;
      }
    }
    Require(card.cm.ActiveConnections() <= cip::kMaxCipConnections);
  }
  return 0;
}
