// libFuzzer target for LLDP (net/lldp_frame.h, net/lldp_agent.h). The input is a script of records:
// one byte kind, two bytes of time step in ms, then for a frame one port byte, one length byte and that
// many bytes. Kinds: 0 frame, 1 link up, 2 link down, 3 system name (the frame bytes as text),
// 4 management address (the first four frame bytes); the rest: poll.
// Oracles: nothing is read outside a frame (ASan); a parsed LLDPDU keeps its IDs and texts within their
// fixed sizes and its mandatory IDs non-empty; every frame the agent sends parses back with its own MAC,
// the port's ID and TTL 120 and goes out of a port with link only; the table never holds more than
// kLldpMaxNeighbours entries, two entries never share a key, an entry never outlives its TTL past a
// poll, and a deadline never lies before the poll that set it.
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>

#include "net/lldp_agent.h"
#include "net/lldp_frame.h"

namespace {

void Require(bool condition) {
  if (!condition) __builtin_trap();
}

constexpr base::MacAddress kOwnMac = {0x00, 0x00, 0x5E, 0x00, 0x53, 0x01};

class CheckingSink final : public net::LldpSink {
 public:
  explicit CheckingSink(const std::array<bool, net::kLldpPorts>& up) : up_(up) {}
  void SendLldp(std::size_t port, std::span<const std::uint8_t> frame) override {
    Require(port < net::kLldpPorts && up_[port]);
    const base::Result<net::LldpNeighbourInfo> info = net::ParseLldpFrame(frame);
    Require(info.ok());
    Require(info->chassis.subtype == net::kLldpChassisMac && info->chassis.id.size == 6);
    for (std::size_t i = 0; i < 6; ++i) Require(info->chassis.id.bytes[i] == kOwnMac.octets()[i]);
    Require(info->port.subtype == net::kLldpPortLocal && info->port.id.size == 1 &&
            info->port.id.bytes[0] == '1' + port);
    Require(info->ttl_seconds == net::kLldpTtlSeconds);
  }

 private:
  const std::array<bool, net::kLldpPorts>& up_;
};

void CheckParse(std::span<const std::uint8_t> frame) {
  const base::Result<net::LldpNeighbourInfo> info = net::ParseLldpFrame(frame);
  if (!info.ok()) return;
  Require(info->chassis.id.size >= 1 && info->chassis.id.size <= net::kLldpIdMax);
  Require(info->port.id.size >= 1 && info->port.id.size <= net::kLldpIdMax);
  Require(info->system_name.size <= net::kLldpTextMax && info->port_description.size <= net::kLldpTextMax);
}

void CheckTable(const net::LldpAgent& agent, hal::Micros polled_at) {
  const std::span<const net::LldpNeighbour> table = agent.neighbours();
  Require(table.size() <= net::kLldpMaxNeighbours);
  for (std::size_t i = 0; i < table.size(); ++i) {
    Require(table[i].port < net::kLldpPorts && table[i].expires > polled_at);
    for (std::size_t j = i + 1; j < table.size(); ++j) {
      Require(!(table[i].port == table[j].port && table[i].info.chassis == table[j].info.chassis &&
                table[i].info.port == table[j].info.port));
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::span<const std::uint8_t> rest(data, size);
  CheckParse(rest);
  std::array<bool, net::kLldpPorts> up{};
  CheckingSink sink(up);
  net::LldpAgent agent({.mac = kOwnMac, .product = "IPE002Z", .system_description = "fuzz"}, sink);
  hal::Micros now = 0;
  hal::Micros polled_at = 0;
  while (rest.size() >= 3) {
    const std::uint8_t kind = rest[0];
    now += static_cast<hal::Micros>(rest[1] << 8 | rest[2]) * hal::kMicrosPerMilli;
    rest = rest.subspan(3);
    if (kind <= 4) {
      if (rest.size() < 2) return 0;
      const std::size_t port = rest[0] % (net::kLldpPorts + 1);  // kLldpPorts: a port that does not exist
      const std::size_t length = rest[1] < rest.size() - 2 ? rest[1] : rest.size() - 2;
      const std::span<const std::uint8_t> bytes = rest.subspan(2, length);
      rest = rest.subspan(2 + length);
      switch (kind) {
        case 0:
          CheckParse(bytes);
          agent.OnFrame(port, bytes, now);
          break;
        case 1:
          agent.LinkUp(port, now);
          if (port < net::kLldpPorts) up[port] = true;
          break;
        case 2:
          agent.LinkDown(port);
          if (port < net::kLldpPorts) up[port] = false;
          break;
        case 3:
          agent.SetSystemName(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
          Require(!agent.system_name().empty() && agent.system_name().size() <= net::kLldpSystemNameMax);
          break;
        default:
          if (bytes.size() >= 4) agent.SetManagementAddress(base::Ipv4Address(bytes[0], bytes[1], bytes[2], bytes[3]));
          break;
      }
    } else {
      agent.Poll(now);
      polled_at = now;
      Require(agent.NextDeadline() > now);
      CheckTable(agent, polled_at);
    }
  }
  return 0;
}
