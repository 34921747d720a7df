#include "host_options.h"

#include <cctype>
#include <cstdio>
#include <cstring>
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

bool ParseCidr(const std::string& text, HostOptions& options) {
  const std::size_t slash = text.find('/');
  if (slash == std::string::npos) return false;
  const std::string prefix_text = text.substr(slash + 1);
  if (prefix_text.empty() || prefix_text.size() > 2) return false;
  for (char c : prefix_text) {
    if (std::isdigit(static_cast<unsigned char>(c)) == 0) return false;
  }
  const int prefix = std::stoi(prefix_text);
  if (prefix < 1 || prefix > 30) return false;
  if (!ParseIpv4(text.substr(0, slash), options.ip)) return false;
  options.netmask = ~std::uint32_t{0} << (32 - prefix);
  return true;
}

// NAME: a parameter name of the inverter (c500, f856, cmod, acc); VALUE: a decimal or 0x-hex number.
bool ParseParam(const std::string& text, HostOptions& options) {
  const std::size_t eq = text.find('=');
  if (eq == std::string::npos || eq == 0 || eq > 8 || eq + 1 == text.size()) return false;
  const std::string name = text.substr(0, eq);
  const std::string value = text.substr(eq + 1);
  if (std::isalpha(static_cast<unsigned char>(name[0])) == 0) return false;
  for (char c : name) {
    if (std::isalnum(static_cast<unsigned char>(c)) == 0) return false;
  }
  std::size_t i = (value[0] == '-' || value[0] == '+') ? 1 : 0;
  const bool hex = value.compare(i, 2, "0x") == 0 || value.compare(i, 2, "0X") == 0;
  if (hex) i += 2;
  if (i == value.size() || value.size() > 16) return false;
  for (; i < value.size(); ++i) {
    const auto c = static_cast<unsigned char>(value[i]);
    if (!(hex ? std::isxdigit(c) != 0 : (std::isdigit(c) != 0 || c == '.'))) return false;
  }
  options.params.emplace_back(name, value);
  return true;
}

}  // namespace

bool ParseIpv4(const std::string& text, std::uint32_t& out) {
  unsigned a = 0, b = 0, c = 0, d = 0;
  char tail = 0;
  if (std::sscanf(text.c_str(), "%3u.%3u.%3u.%3u%c", &a, &b, &c, &d, &tail) != 4) return false;
  if (a > 255 || b > 255 || c > 255 || d > 255) return false;
  for (char ch : text) {
    if (std::isdigit(static_cast<unsigned char>(ch)) == 0 && ch != '.') return false;
  }
  out = (a << 24) | (b << 16) | (c << 8) | d;
  return true;
}

std::string FormatIpv4(std::uint32_t v) {
  char text[16];
  std::snprintf(text, sizeof text, "%u.%u.%u.%u", (v >> 24) & 0xFFu, (v >> 16) & 0xFFu,
                (v >> 8) & 0xFFu, v & 0xFFu);
  return text;
}

const char* HostUsage() {
  return "usage: ipe002z-host [options]\n"
         "  --net loopback | tap:IF[,tap:IF2]  network port (default loopback: libslirp, no root)\n"
         "  --ip A.B.C.D/N                     card address (loopback default 10.0.2.15/24)\n"
         "  --gateway A.B.C.D                  default gateway (loopback default 10.0.2.2)\n"
         "  --host-addr A.B.C.D                loopback address the forwards bind (default 127.0.0.2)\n"
         "  --state-dir DIR                    persistent state (default: a fresh temporary dir)\n"
         "  --param NAME=VALUE                 preset an inverter parameter on a fresh state dir\n"
         "  --model vf-mb1|vf-s15              inverter model (default vf-mb1)\n"
         "  --pcap FILE                        capture every frame in and out\n"
         "  --sim-control PATH                 UNIX control socket (line protocol; 'help' lists it)\n"
         "  --help                             this text\n";
}

ParseOutcome ParseHostOptions(int argc, const char* const* argv, HostOptions& options,
                              std::string& error) {
  bool gateway_given = false;
  for (int i = 1; i < argc; ++i) {
    const std::string flag = argv[i];
    if (flag == "--help" || flag == "-h") return ParseOutcome::kHelp;
    if (i + 1 >= argc) {
      error = flag.rfind("--", 0) == 0 ? "missing value for " + flag : "unexpected argument " + flag;
      return ParseOutcome::kError;
    }
    const std::string value = argv[++i];
    bool ok = true;
    if (flag == "--net") {
      ok = ParseNet(value, options);
    } else if (flag == "--ip") {
      ok = ParseCidr(value, options);
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
    } else if (flag == "--param") {
      ok = ParseParam(value, options);
    } else if (flag == "--model") {
      ok = value == "vf-mb1" || value == "vf-s15";
      options.model = value;
    } else if (flag == "--pcap") {
      options.pcap_path = value;
    } else if (flag == "--sim-control") {
      options.sim_control_path = value;
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
  if (!options.ip_given) {
    error = "--ip is required with --net tap";
    return ParseOutcome::kError;
  }
  return ParseOutcome::kRun;
}

}  // namespace host
