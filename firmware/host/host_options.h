// Command line of the host-native card (ipe002z-host).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "sim/register_table.h"
#include "tcp_keepalive.h"

namespace host {

enum class NetKind { kLoopback, kTap };

// --param NAME|COMMNO=VALUE: a parameter preset for the simulated inverter, checked against the
// register table of the chosen model (an EEPROM parameter hosts may write, within its static limits).
struct ParamPreset {
  std::string text;          // as given ("acc=50"), for messages
  std::uint16_t number = 0;  // communication number
  std::int32_t value = 0;    // in the register's unit step
};

struct HostOptions {
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
  // The simulated inverter.
  sim::Model model = sim::Model::kVfMb1;
  std::vector<ParamPreset> params;  // in order; applied only to a new inverter (no EEPROM file yet)
  bool rs485_profile = false;       // 19200 baud 8E1, 20 ms processing (sim::Rs485Profile())
  int sim_processing_ms = -1;       // the inverter's processing delay; -1: the profile's (2 ms or 20 ms)
  // --tcp-keepalive IDLE_MS,INTERVAL_MS,COUNT: keepalive timing of the card's TCP connections (tests
  // shorten it to see a vanished peer dropped); default lwipopts.h's 60 s, 10 s, 6.
  firmware::TcpKeepalive tcp_keepalive;
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
