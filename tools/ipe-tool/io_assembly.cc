#include "io_assembly.h"

#include <cstdio>

#include "base/byte_reader.h"
#include "base/byte_writer.h"
#include "cip/io_connection.h"

namespace ipe {
namespace {

const char* StateName(std::uint8_t state) {
  switch (state) {
    case 1: return "startup";
    case 2: return "not-ready";
    case 3: return "ready";
    case 4: return "enabled";
    case 5: return "stopping";
    case 6: return "fault-stop";
    case 7: return "faulted";
    default: return "unknown";
  }
}

}  // namespace

std::array<std::uint8_t, 4> EncodeAssembly21(const SpeedCommand& command) {
  std::uint8_t bits = 0;
  if (command.run_forward) bits |= 0x01;
  if (command.run_reverse) bits |= 0x02;
  if (command.fault_reset) bits |= 0x04;
  if (command.net_ctrl) bits |= 0x20;
  if (command.net_ref) bits |= 0x40;
  const auto speed = static_cast<std::uint16_t>(command.speed_rpm);
  return {bits, 0, static_cast<std::uint8_t>(speed), static_cast<std::uint8_t>(speed >> 8)};
}

std::optional<SpeedStatus> DecodeAssembly71(std::span<const std::uint8_t> data) {
  if (data.size() != 4) return std::nullopt;
  SpeedStatus status;
  const std::uint8_t bits = data[0];
  status.faulted = (bits & 0x01) != 0;
  status.warning = (bits & 0x02) != 0;
  status.running_forward = (bits & 0x04) != 0;
  status.running_reverse = (bits & 0x08) != 0;
  status.ready = (bits & 0x10) != 0;
  status.ctrl_from_net = (bits & 0x20) != 0;
  status.ref_from_net = (bits & 0x40) != 0;
  status.at_reference = (bits & 0x80) != 0;
  status.state = data[1];
  status.speed_rpm = static_cast<std::int16_t>(data[2] | data[3] << 8);
  return status;
}

std::string FormatSpeedStatus(const SpeedStatus& s, std::uint16_t centi_hz) {
  std::string text;
  auto flag = [&text](bool on, const char* name) {
    if (on) text += std::string(text.empty() ? "" : " ") + name;
  };
  flag(s.faulted, "faulted");
  flag(s.warning, "warning");
  flag(s.running_forward, "running-fwd");
  flag(s.running_reverse, "running-rev");
  flag(s.ready, "ready");
  flag(s.ctrl_from_net, "ctrl-from-net");
  flag(s.ref_from_net, "ref-from-net");
  flag(s.at_reference, "at-reference");
  if (!s.running_forward && !s.running_reverse) flag(true, "stopped");
  char tail[96];
  std::snprintf(tail, sizeof tail, " state=%u (%s) speed=%d rpm (%u.%02u Hz)", s.state, StateName(s.state),
                s.speed_rpm, centi_hz / 100u, centi_hz % 100u);
  return text + tail;
}

std::vector<std::uint8_t> EncodeOutputDatagram(std::uint32_t connection_id, std::uint32_t encapsulation_sequence,
                                               std::uint16_t cip_sequence, bool run,
                                               std::span<const std::uint8_t> assembly) {
  std::vector<std::uint8_t> data(4 + assembly.size());
  data[0] = run ? 1 : 0;  // run/idle header: bit 0 run
  for (std::size_t i = 0; i < assembly.size(); ++i) data[4 + i] = assembly[i];
  std::vector<std::uint8_t> buffer(64 + data.size());
  base::ByteWriter out(buffer);
  cip::EncodeIoDatagram(connection_id, encapsulation_sequence, cip_sequence, data, out);
  return std::vector<std::uint8_t>(out.written().begin(), out.written().end());
}

std::optional<std::vector<std::uint8_t>> DecodeInputDatagram(std::span<const std::uint8_t> datagram,
                                                             std::uint32_t connection_id) {
  const base::Result<cip::ReceivedIoDatagram> parsed = cip::ParseIoDatagram(datagram);
  if (!parsed.ok() || parsed.value().connection_id != connection_id || parsed.value().data.size() < 2) {
    return std::nullopt;
  }
  const std::span<const std::uint8_t> data = parsed.value().data.subspan(2);
  return std::vector<std::uint8_t>(data.begin(), data.end());
}

}  // namespace ipe
