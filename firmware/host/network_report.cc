#include "network_report.h"

#include <cstdio>

#include "card_lines.h"
#include "card_report.h"
#include "host_options.h"

namespace host {

void AppendNetworkStats(const NetworkReport& report, std::string& out) {
  const firmware::AddressingCounters& a = report.addressing.counters();
  AppendLine(out, "addr.restarts", a.restarts);
  AppendLine(out, "addr.address_changes", a.address_changes);
  AppendLine(out, "addr.bootp_requests", a.bootp_requests);
  AppendLine(out, "addr.bootp_replies", a.bootp_replies);
  AppendLine(out, "addr.bootp_ignored", a.bootp_ignored);
  AppendLine(out, "addr.dhcp_restarts", a.dhcp_restarts);
  AppendLine(out, "addr.acd_frames_sent", a.acd_frames_sent);
  AppendLine(out, "addr.acd_conflicts", a.acd_conflicts);
  AppendLine(out, "addr.duplicate", report.addressing.duplicate_detected() ? 1 : 0);
  for (std::size_t i = 0; i < hal::kMaxPorts; ++i) {
    const auto id = static_cast<hal::PortId>(i);
    const firmware::PortTraffic& t = report.netif.traffic(id);
    const std::string prefix = std::string("switch.") + hal::PortLetter(id) + ".";
    AppendLine(out, prefix + "forwarded", t.forwarded);
    AppendLine(out, prefix + "in_ucast", t.in_ucast);
    AppendLine(out, prefix + "in_nucast", t.in_nucast);
    AppendLine(out, prefix + "out_ucast", t.out_ucast);
    AppendLine(out, prefix + "out_nucast", t.out_nucast);
    AppendLine(out, prefix + "out_discards", t.out_discards);
  }
}

std::string DescribeAddress(const NetworkReport& report) {
  firmware::TextLine line;
  firmware::DescribeAddress(report.addressing, line);
  return std::string(line.view());
}

std::string DescribeLedInputs(const NetworkReport& report) {
  const net::LedInputs in = report.indicators.Gather();
  static constexpr const char* kConnections[] = {"none", "established", "timed-out"};
  static constexpr const char* kFaults[] = {"none", "minor", "major"};
  return std::string("protocol=") + (in.protocol == net::Protocol::kEtherNetIp ? "eip" : "modbus") +
         " configured=" + (in.configured ? "1" : "0") + " fault=" + kFaults[static_cast<int>(in.fault)] +
         " address=" + (in.has_address ? "1" : "0") + " acquiring=" + (in.acquiring_address ? "1" : "0") +
         " duplicate=" + (in.duplicate_address ? "1" : "0") + " link=" + (in.any_link_up ? "1" : "0") +
         " connections=" + kConnections[static_cast<int>(in.connections)];
}

}  // namespace host
