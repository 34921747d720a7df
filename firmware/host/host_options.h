// Command line of the host-native card (ipe002z-host).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "address_plan.h"
#include "inverter_options.h"
#include "tcp_keepalive.h"

namespace host {

enum class NetKind { kLoopback, kTap };

// The simulated inverter's flags (--model, --param, --rs485-profile, --sim-processing-ms) are the
// base's: ipe002z-inverter takes the same ones (sim/host/inverter_options.h).
struct HostOptions : sim::InverterOptions {
  NetKind net = NetKind::kLoopback;
  std::vector<std::string> tap_interfaces;  // --net tap:IF1[,tap:IF2]: port L, then port R
  std::uint32_t ip = 0;                     // host byte order
  std::uint32_t netmask = 0;
  std::uint32_t gateway = 0;
  bool ip_given = false;                    // --ip: forces c504 = 0 and c505-c516 at every start
  std::string host_address = "127.0.0.2";  // loopback address the forwards bind (--net loopback)
  std::string state_dir;                    // empty: a fresh temporary directory
  std::string pcap_path;
  std::string sim_control_path;
  // --drive unix:PATH: the drive link talks to an inverter listening there (ipe002z-inverter --serial
  // unix:PATH) instead of the simulator in this process; empty: the in-process simulator. Lets a
  // profiler count the card's own work without the simulator's (tools/bench/instructions).
  std::string drive_socket;
  // --tcp-keepalive IDLE_MS,INTERVAL_MS,COUNT: keepalive timing of the card's TCP connections (tests
  // shorten it to see a vanished peer dropped); default lwipopts.h's 60 s, 10 s, 6.
  firmware::TcpKeepalive tcp_keepalive;
  // --eds PATH: the file the card serves as its EDS (File object 0x37, GET /api/eds) instead of its own
  // (firmware/card/card.cc), read once at start; for tests of large files.
  std::string eds_path;
};

enum class ParseOutcome { kRun, kHelp, kError };

// Parses argv[1..]. On kError, `error` says what was wrong in one line.
ParseOutcome ParseHostOptions(int argc, const char* const* argv, HostOptions& options,
                              std::string& error);
const char* HostUsage();

// "10.0.2.15" -> host byte order; false when not a dotted quad. Shared with the simulated inverter's
// --ip (sim/host/address_plan.h).
using sim::FormatIpv4;
using sim::ParseIpv4;

}  // namespace host
