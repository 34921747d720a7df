#include "host_options.h"

#include <cctype>
#include <string>
#include <string_view>

namespace host {
namespace {

// The default address plan of the loopback port: libslirp's virtual 10.0.2.0/24 with its gateway.
constexpr std::uint32_t kLoopbackIp = 0x0A00020F;       // 10.0.2.15
constexpr std::uint32_t kLoopbackGateway = 0x0A000202;  // 10.0.2.2
constexpr std::uint32_t kLoopbackMask = 0xFFFFFF00;

bool ParseNet(std::string_view text, HostOptions& options) {
  if (text == "loopback") {
    options.net = NetKind::kLoopback;
    return true;
  }
  options.net = NetKind::kTap;
  options.tap_interfaces.clear();
  while (!text.empty()) {
    const std::size_t comma = text.find(',');
    const std::string_view item = text.substr(0, comma);
    if (item.substr(0, 4) != "tap:" || item.size() == 4 || item.size() > 4 + 15) return false;
    options.tap_interfaces.emplace_back(item.substr(4));
    if (comma == std::string_view::npos) break;
    text.remove_prefix(comma + 1);
    if (text.empty()) return false;
  }
  return !options.tap_interfaces.empty() && options.tap_interfaces.size() <= 2;
}

// An unsigned decimal of at most `digits` digits within [low, high].
bool ParseBounded(std::string_view text, std::size_t digits, std::uint32_t low, std::uint32_t high,
                  std::uint32_t& out) {
  if (text.empty() || text.size() > digits) return false;
  std::uint32_t value = 0;
  for (char c : text) {
    if (std::isdigit(static_cast<unsigned char>(c)) == 0) return false;
    value = value * 10 + static_cast<std::uint32_t>(c - '0');
  }
  if (value < low || value > high) return false;
  out = value;
  return true;
}

// IDLE_MS,INTERVAL_MS,COUNT: idle and interval 100 ms .. 2 h, count 1..20.
bool ParseKeepalive(std::string_view text, firmware::TcpKeepalive& out) {
  constexpr std::uint32_t kMinMs = 100;
  constexpr std::uint32_t kMaxMs = 7200000;
  const std::size_t first = text.find(',');
  if (first == std::string_view::npos) return false;
  const std::size_t second = text.find(',', first + 1);
  if (second == std::string_view::npos) return false;
  std::uint32_t idle = 0, interval = 0, count = 0;
  if (!ParseBounded(text.substr(0, first), 7, kMinMs, kMaxMs, idle) ||
      !ParseBounded(text.substr(first + 1, second - first - 1), 7, kMinMs, kMaxMs, interval) ||
      !ParseBounded(text.substr(second + 1), 2, 1, 20, count)) {
    return false;
  }
  out = {idle, interval, static_cast<std::uint8_t>(count)};
  return true;
}

}  // namespace

const char* HostUsage() {
  static const std::string usage =
      std::string(
          "usage: ipe002z-host [options]\n"
          "  --net loopback | tap:IF[,tap:IF2]  network port (default loopback: libslirp, no root)\n"
          "  --ip A.B.C.D/N                     card address: sets c504 = 0 (manual) and c505-c516 in the\n"
          "                                     inverter at every start (loopback: always, default\n"
          "                                     10.0.2.15/24); without it (tap) c504-c516 decide: manual,\n"
          "                                     BOOTP or DHCP\n"
          "  --gateway A.B.C.D                  default gateway with --ip (loopback default 10.0.2.2)\n"
          "  --host-addr A.B.C.D                loopback address the forwards bind (default 127.0.0.2)\n"
          "  --state-dir DIR                    persistent state (default: a fresh temporary dir)\n"
          "  --pcap FILE                        capture every frame in and out\n"
          "  --sim-control PATH                 UNIX control socket (line protocol; 'help' lists it)\n"
          "  --drive unix:PATH                  the inverter is another process listening there\n"
          "                                     (ipe002z-inverter --serial unix:PATH); default: the\n"
          "                                     simulated inverter in this process (the flags below)\n"
          "  --tcp-keepalive IDLE_MS,INTERVAL_MS,COUNT\n"
          "                                     TCP keepalive of the card's connections (for tests): first\n"
          "                                     probe after IDLE_MS idle, then every INTERVAL_MS, dropped\n"
          "                                     after COUNT unanswered (IDLE_MS and INTERVAL_MS 100-7200000,\n"
          "                                     COUNT 1-20; default 60000,10000,6)\n"
          "  --eds PATH                         serve the file at PATH as the card's EDS (File object\n"
          "                                     0x37, GET /api/eds) instead of the card's own\n"
          "simulated inverter (its EEPROM is kept in DIR/inverter/MODEL.eeprom):\n") +
      sim::kInverterOptionsUsage + "  --help                             this text\n";
  return usage.c_str();
}

ParseOutcome ParseHostOptions(int argc, const char* const* argv, HostOptions& options,
                              std::string& error) {
  bool gateway_given = false;
  for (int i = 1; i < argc; ++i) {
    const std::string flag = argv[i];
    if (flag == "--help" || flag == "-h") return ParseOutcome::kHelp;
    if (sim::TakeInverterSwitch(flag, options)) continue;
    if (i + 1 >= argc) {
      error = flag.rfind("--", 0) == 0 ? "missing value for " + flag : "unexpected argument " + flag;
      return ParseOutcome::kError;
    }
    const std::string value = argv[++i];
    bool ok = true;
    if (flag == "--net") {
      ok = ParseNet(value, options);
    } else if (flag == "--ip") {
      ok = sim::ParseCidr(value, options.ip, options.netmask);
      options.ip_given = ok;
    } else if (flag == "--gateway") {
      ok = ParseIpv4(value, options.gateway);
      gateway_given = ok;
    } else if (flag == "--host-addr") {
      std::uint32_t address = 0;
      ok = ParseIpv4(value, address) && (address >> 24) == 127;
      options.host_address = value;
    } else if (flag == "--state-dir") {
      options.state_dir = value;
    } else if (flag == "--tcp-keepalive") {
      ok = ParseKeepalive(value, options.tcp_keepalive);
    } else if (flag == "--eds") {
      options.eds_path = value;
    } else if (flag == "--pcap") {
      options.pcap_path = value;
    } else if (flag == "--sim-control") {
      options.sim_control_path = value;
    } else if (flag == "--drive") {
      ok = value.rfind("unix:", 0) == 0 && value.size() > 5;
      options.drive_socket = ok ? value.substr(5) : std::string();
    } else if (const sim::FlagOutcome taken = sim::TakeInverterFlag(flag, value, options);
               taken != sim::FlagOutcome::kNotOurs) {
      ok = taken == sim::FlagOutcome::kTaken;
    } else {
      error = "unknown option " + flag;
      return ParseOutcome::kError;
    }
    if (!ok || value.empty()) {
      error = "invalid value for " + flag + ": '" + value + "'";
      return ParseOutcome::kError;
    }
  }
  if (options.net == NetKind::kLoopback && !options.ip_given) {
    options.ip = kLoopbackIp;
    options.netmask = kLoopbackMask;
    options.ip_given = true;
  }
  if (options.net == NetKind::kLoopback && !gateway_given) options.gateway = kLoopbackGateway;
  if (!sim::CheckPresets(options, error)) return ParseOutcome::kError;
  return ParseOutcome::kRun;
}

}  // namespace host
