// Command line of the host-native card (ipe002z-host).
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace host {

enum class NetKind { kLoopback, kTap };

struct HostOptions {
  NetKind net = NetKind::kLoopback;
  std::vector<std::string> tap_interfaces;  // --net tap:IF1[,tap:IF2]: port L, then port R
  std::uint32_t ip = 0;                     // host byte order
  std::uint32_t netmask = 0;
  std::uint32_t gateway = 0;
  bool ip_given = false;
  std::string host_address = "127.0.0.2";  // loopback address the forwards bind (--net loopback)
  std::string state_dir;                    // empty: a fresh temporary directory
  std::vector<std::pair<std::string, std::string>> params;  // --param NAME=VALUE, in order
  std::string model = "vf-mb1";
  std::string pcap_path;
  std::string sim_control_path;
};

enum class ParseOutcome { kRun, kHelp, kError };

// Parses argv[1..]. On kError, `error` says what was wrong in one line.
ParseOutcome ParseHostOptions(int argc, const char* const* argv, HostOptions& options,
                              std::string& error);
const char* HostUsage();

// "10.0.2.15" -> host byte order; false when not a dotted quad.
bool ParseIpv4(const std::string& text, std::uint32_t& out);
std::string FormatIpv4(std::uint32_t host_order);

}  // namespace host
