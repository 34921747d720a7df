// io: a class 1 exclusive-owner connection 21/71, run/speed out, the input assembly decoded in.
#include <arpa/inet.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <random>

#include "base/byte_reader.h"
#include "base/byte_writer.h"
#include "cip/cip_status.h"
#include "cip/drive/drive_units.h"
#include "cip/epath.h"
#include "cip/forward_open.h"
#include "commands.h"
#include "drive_link/drive_registers.h"
#include "failure.h"
#include "io_assembly.h"
#include "values.h"

namespace ipe {
namespace {

using Clock = std::chrono::steady_clock;

constexpr std::uint16_t kIoPort = 2222;
constexpr std::uint16_t kOriginatorVendor = 0xFFFE;  // no ODVA vendor id of its own: a test value
constexpr std::uint8_t kTimeoutMultiplier = 2;       // connection timeout = 16 RPIs
constexpr std::uint32_t kStopMillis = 1000;          // how long a stop is sent before Forward_Close

std::vector<std::uint8_t> ConnectionPath(const Options& options) {
  std::uint8_t bytes[16];
  base::ByteWriter out(bytes);
  cip::EncodeLogicalSegment(cip::SegmentKind::kClass, cip::kClassAssembly, out);
  cip::EncodeLogicalSegment(cip::SegmentKind::kInstance, 1, out);  // configuration instance 1, size 0
  cip::EncodeLogicalSegment(cip::SegmentKind::kConnectionPoint, options.output_instance, out);
  cip::EncodeLogicalSegment(cip::SegmentKind::kConnectionPoint, options.input_instance, out);
  return std::vector<std::uint8_t>(out.written().begin(), out.written().end());
}

// A Forward_Open/Forward_Close to the Connection Manager (class 6 instance 1); a refusal ends the command.
template <typename Request, typename Encoder>
CipReply ConnectionManagerRequest(EipSession& session, std::uint8_t service, const char* name,
                                  const Request& request, Encoder encode) {
  std::vector<std::uint8_t> data(128);
  base::ByteWriter out(data);
  encode(request, out);
  const CipReply reply = session.Request(service, {cip::kClassConnectionManager, 1, std::nullopt}, out.written());
  if (!reply.ok()) Fail(kExitRefused, std::string("io: ") + name + " refused by the card: " + FormatCipStatus(reply));
  return reply;
}

struct OpenConnection {
  std::uint32_t o_to_t_id = 0;
  std::uint32_t t_to_o_id = 0;
  cip::ConnectionTriad triad;
};

OpenConnection ForwardOpen(EipSession& session, const Options& options, const std::vector<std::uint8_t>& path,
                           std::uint32_t proposed_t_to_o, const cip::ConnectionTriad& triad) {
  cip::ForwardOpenRequest request;
  request.priority_tick = 0x0A;
  request.timeout_ticks = 0x0E;
  request.t_to_o_connection_id = proposed_t_to_o;
  request.triad = triad;
  request.timeout_multiplier = kTimeoutMultiplier;
  request.o_to_t_rpi = options.rpi_ms * 1000;
  request.o_to_t = {static_cast<std::uint16_t>(2 + 4 + 4), false, cip::ConnectionPriority::kScheduled,
                    cip::ConnectionType::kPointToPoint, false};  // sequence count + run/idle header + 21
  request.t_to_o_rpi = options.rpi_ms * 1000;
  request.t_to_o = {static_cast<std::uint16_t>(2 + 4), false, cip::ConnectionPriority::kScheduled,
                    cip::ConnectionType::kPointToPoint, false};  // sequence count + 71
  request.transport = {false, cip::kTriggerCyclic, 1};
  request.connection_path = path;
  const CipReply reply =
      ConnectionManagerRequest(session, cip::kServiceForwardOpen, "Forward_Open", request, cip::EncodeForwardOpen);
  base::ByteReader in(reply.data);
  OpenConnection open;
  open.o_to_t_id = in.U32Le();
  open.t_to_o_id = in.U32Le();
  open.triad = triad;
  if (!in.ok()) Fail(kExitUnreachable, "io: the Forward_Open reply does not decode");
  return open;
}

void ForwardClose(EipSession& session, const std::vector<std::uint8_t>& path, const cip::ConnectionTriad& triad) {
  cip::ForwardCloseRequest request;
  request.priority_tick = 0x0A;
  request.timeout_ticks = 0x0E;
  request.triad = triad;
  request.connection_path = path;
  ConnectionManagerRequest(session, cip::kServiceForwardClose, "Forward_Close", request, cip::EncodeForwardClose);
  std::fprintf(stderr, "io: connection closed (Forward_Close)\n");
}

}  // namespace

int RunIo(const Options& options) {
  const std::string& host = options.args[0];
  Card card = ConnectCard(options, host);
  // The speed in Hz becomes rpm with the drive's pole pairs (f856), as the card converts it back.
  const AccessResult poles = card.access->Read(drive_link::reg::kF856);
  if (!poles.ok) Fail(kExitRefused, "io: reading f856 refused by the card: " + poles.refusal);
  // The owner's Forward_Close is a communication loss for the card (docs/drive-control.md): with the
  // factory c101 = 4 the drive trips err8 when this connection closes, however stopped it is.
  const AccessResult loss_action = card.access->Read(drive_link::reg::kC101);
  if (loss_action.ok && loss_action.word == 4) {
    std::fprintf(stderr, "io: warning: c101 = 4: the drive trips err8 when this connection closes (set c101 first)\n");
  }
  std::uint16_t centi_hz = 0;
  if (!options.speed.empty()) {
    const std::optional<ParameterInfo> fa07 = FindParameter("fa07", card.model);
    if (!fa07) Fail(kExitUsage, "io: no frequency command register in the table");
    const ParsedValue speed = ParseValue(options.speed, *fa07);
    if (!speed.ok) Fail(kExitUsage, "io: --speed " + speed.error);
    if (const std::string range = CheckRange(speed.raw, *fa07, card.model); !range.empty()) Fail(kExitUsage, "io: --speed " + range);
    centi_hz = static_cast<std::uint16_t>(speed.raw);
  }
  SpeedCommand command;
  command.net_ctrl = options.run || !options.speed.empty();
  command.net_ref = !options.speed.empty();
  command.run_forward = options.run;
  command.speed_rpm = static_cast<std::int16_t>(cip::drive::FrequencyToRpm(centi_hz, poles.word));

  in_addr bind_address{};
  if (!options.io_bind.empty()) {
    bind_address = ResolveHost(options.io_bind);
  } else {
    // A card on the loopback port sends T->O to 127.0.0.1 (it sees the host as 10.0.2.2) and holds
    // 127.0.0.x:2222 itself: bind beside it on 127.0.0.1.
    const in_addr peer = card.eip->peer();
    bind_address.s_addr = (ntohl(peer.s_addr) >> 24) == 127 ? htonl(INADDR_LOOPBACK) : htonl(INADDR_ANY);
  }
  UdpSocket io(bind_address, kIoPort);

  std::random_device random;
  const cip::ConnectionTriad triad{static_cast<std::uint16_t>(random()), kOriginatorVendor,
                                   static_cast<std::uint32_t>(random())};
  const std::vector<std::uint8_t> path = ConnectionPath(options);
  const OpenConnection open = ForwardOpen(*card.eip, options, path, static_cast<std::uint32_t>(random()), triad);
  std::fprintf(stderr, "io: connection open: O->T 0x%08X T->O 0x%08X, RPI %u ms, %u/%u\n", open.o_to_t_id,
               open.t_to_o_id, options.rpi_ms, options.output_instance, options.input_instance);

  InstallInterruptHandler();
  const bool tty = isatty(STDOUT_FILENO) != 0;
  const auto rpi = std::chrono::milliseconds(options.rpi_ms);
  const Clock::time_point start = Clock::now();
  std::optional<Clock::time_point> stop_at;
  if (options.duration_ms) stop_at = start + std::chrono::milliseconds(*options.duration_ms);
  std::optional<Clock::time_point> stopping_since;
  Clock::time_point last_input = start;
  Clock::time_point next_send = start;
  std::uint32_t encapsulation_sequence = 0;
  std::uint16_t cip_sequence = 0;
  std::string last_line;
  bool received = false;
  for (;;) {
    const Clock::time_point now = Clock::now();
    if (!stopping_since && (Interrupted() || (stop_at && now >= *stop_at))) {
      stopping_since = now;
      command.run_forward = false;  // a stop first, so that Forward_Close finds the drive stopped
    }
    if (stopping_since && (!options.run || now - *stopping_since >= std::chrono::milliseconds(kStopMillis))) break;
    if (now - last_input > std::chrono::milliseconds(options.timeout_ms) + rpi * 16) {
      if (tty) std::printf("\n");
      ForwardClose(*card.eip, path, triad);
      Fail(kExitUnreachable, received ? "io: the card stopped producing" : "io: no T->O data from the card on UDP 2222");
    }
    if (now >= next_send) {
      const std::array<std::uint8_t, 4> assembly = EncodeAssembly21(command);
      io.SendTo(EncodeOutputDatagram(open.o_to_t_id, ++encapsulation_sequence, ++cip_sequence, true, assembly),
                card.eip->peer(), kIoPort);
      next_send += rpi;
      if (next_send < now) next_send = now + rpi;  // late: no burst
    }
    std::vector<std::uint8_t> bytes;
    sockaddr_in from{};
    const auto wait = std::chrono::duration_cast<std::chrono::milliseconds>(next_send - Clock::now()).count();
    if (!io.ReceiveFrom(bytes, from, static_cast<int>(wait < 0 ? 0 : wait))) continue;
    const auto input = DecodeInputDatagram(bytes, open.t_to_o_id);
    if (!input) continue;
    const std::optional<SpeedStatus> status = DecodeAssembly71(*input);
    if (!status) continue;
    received = true;
    last_input = Clock::now();
    const std::uint16_t actual = cip::drive::RpmToFrequency(status->speed_rpm, poles.word);
    const std::string line = FormatSpeedStatus(*status, actual);
    if (line != last_line) {
      if (tty) std::printf("\r\033[K%s", line.c_str());
      else std::printf("%s\n", line.c_str());
      std::fflush(stdout);
      last_line = line;
    }
  }
  if (tty) std::printf("\n");
  ForwardClose(*card.eip, path, triad);
  return kExitOk;
}

}  // namespace ipe
