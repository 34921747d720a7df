#include "card_report.h"

#include <span>
#include <string>

#include "lwip/memp.h"
#include "lwip/priv/tcp_priv.h"
#include "control_server.h"
#include "lwip/stats.h"
#include "sim_control.h"

namespace host {
namespace {

// lwIP keeps pool names only in debug builds; take them from its own pool list instead.
constexpr const char* kPoolNames[] = {
#define LWIP_MEMPOOL(name, num, size, desc) #name,
#include "lwip/priv/memp_std.h"
};
static_assert(sizeof(kPoolNames) / sizeof(kPoolNames[0]) == MEMP_MAX);

void Line(std::string& out, const std::string& name, std::uint64_t value) { AppendLine(out, name, value); }

void AppendProto(std::string& out, const char* name, const stats_proto& p) {
  const std::string prefix = std::string("lwip.") + name + ".";
  Line(out, prefix + "xmit", p.xmit);
  Line(out, prefix + "recv", p.recv);
  Line(out, prefix + "drop", p.drop);
  Line(out, prefix + "chkerr", p.chkerr);
  Line(out, prefix + "lenerr", p.lenerr);
  Line(out, prefix + "memerr", p.memerr);
  Line(out, prefix + "proterr", p.proterr);
  Line(out, prefix + "err", p.err);
}

void AppendIgmp(std::string& out, const stats_igmp& p) {
  Line(out, "lwip.igmp.xmit", p.xmit);
  Line(out, "lwip.igmp.recv", p.recv);
  Line(out, "lwip.igmp.drop", p.drop);
  Line(out, "lwip.igmp.proterr", p.proterr);
  Line(out, "lwip.igmp.tx_join", p.tx_join);
  Line(out, "lwip.igmp.tx_leave", p.tx_leave);
}

void AppendMem(std::string& out, const std::string& prefix, const stats_mem& m) {
  Line(out, prefix + ".used", m.used);
  Line(out, prefix + ".max", m.max);
  Line(out, prefix + ".avail", m.avail);
  Line(out, prefix + ".err", m.err);
}

std::uint64_t CountPcbs(const tcp_pcb* list) {
  std::uint64_t count = 0;
  for (const tcp_pcb* pcb = list; pcb != nullptr; pcb = pcb->next) ++count;
  return count;
}

// lwIP's TCP PCB lists. A connection the card closed first stays in TIME_WAIT for 2 x TCP_MSL and keeps
// its TCP_PCB (docs/robustness.md "Exhaustion"); these lines tell those apart from a leak.
void AppendTcpPcbs(std::string& out) {
  Line(out, "lwip.tcp_pcbs.active", CountPcbs(tcp_active_pcbs));
  Line(out, "lwip.tcp_pcbs.time_wait", CountPcbs(tcp_tw_pcbs));
  std::uint64_t listening = 0;
  for (const tcp_pcb_listen* pcb = tcp_listen_pcbs.listen_pcbs; pcb != nullptr; pcb = pcb->next) ++listening;
  Line(out, "lwip.tcp_pcbs.listen", listening);
}

void AppendPorts(std::string& out, const hal::FramePort& port) {
  for (std::size_t i = 0; i < hal::kMaxPorts; ++i) {
    const auto id = static_cast<hal::PortId>(i);
    const std::string prefix = std::string("port.") + hal::PortLetter(id) + ".";
    if (i >= port.PortCount()) {
      out += prefix + "link=absent\n";
      continue;
    }
    const hal::LinkState link = port.Link(id);
    out += prefix + "link=" + (link.up ? "up" : "down") + "\n";
    const hal::PortCounters c = port.Counters(id);
    Line(out, prefix + "rx_frames", c.rx_frames);
    Line(out, prefix + "rx_octets", c.rx_octets);
    Line(out, prefix + "rx_errors", c.rx_errors);
    Line(out, prefix + "tx_frames", c.tx_frames);
    Line(out, prefix + "tx_octets", c.tx_octets);
    Line(out, prefix + "tx_errors", c.tx_errors);
  }
}

bool ParsePort(std::string_view letter, hal::PortId& port) {
  if (letter == "L" || letter == "l") {
    port = hal::PortId::kLeft;
    return true;
  }
  if (letter == "R" || letter == "r") {
    port = hal::PortId::kRight;
    return true;
  }
  return false;
}

constexpr char kHelp[] =
    "help                   this list\n"
    "stats                  counters: event loop, netif, ports, lwIP protocols and pools, the card's pools\n"
    "config                 the configuration read from the inverter and its problems\n"
    "leds                   current LED colours\n"
    "address                IP mode, phase, address in use, ACD duplicate flag, attribute 11 (hex)\n"
    "led-inputs             what the MS/NS model is given now\n"
    "link L|R up|down       plug or unplug the cable of port L or R\n"
    "power-cycle            power-cycle the inverter and restart the card (state dir kept)\n";

}  // namespace

void AppendLine(std::string& out, const std::string& name, std::uint64_t value) {
  out += name;
  out += '=';
  out += std::to_string(value);
  out += '\n';
}

void AppendStats(const CardReport& report, std::string& out) {
  const firmware::LoopStats& loop = report.loop.stats();
  Line(out, "loop.passes", loop.passes);
  Line(out, "loop.waits", report.waiter.wait_count());
  Line(out, "loop.frames_in", loop.frames_in);
  Line(out, "loop.bounded_passes", loop.bounded_passes);
  Line(out, "loop.link_changes", loop.link_changes);
  out += std::string("netif.link=") + (report.netif.link_up() ? "up" : "down") + "\n";
  const firmware::NetifCounters& n = report.netif.counters();
  Line(out, "netif.rx_frames", n.rx_frames);
  Line(out, "netif.rx_dropped_no_pbuf", n.rx_dropped_no_pbuf);
  Line(out, "netif.rx_port_errors", n.rx_port_errors);
  Line(out, "netif.tx_frames", n.tx_frames);
  Line(out, "netif.tx_dropped", n.tx_dropped);
  Line(out, "netif.arp_answered", report.netif.arp_guard_counters().answered);
  Line(out, "netif.arp_dropped", report.netif.arp_guard_counters().dropped);
  AppendPorts(out, report.netif.port());
  AppendProto(out, "link", lwip_stats.link);
  AppendProto(out, "etharp", lwip_stats.etharp);
  AppendProto(out, "ip", lwip_stats.ip);
  AppendProto(out, "icmp", lwip_stats.icmp);
  AppendIgmp(out, lwip_stats.igmp);
  AppendProto(out, "udp", lwip_stats.udp);
  AppendProto(out, "tcp", lwip_stats.tcp);
  AppendTcpPcbs(out);
  AppendMem(out, "lwip.mem", lwip_stats.mem);
  for (int i = 0; i < MEMP_MAX; ++i) {
    const stats_mem* pool = lwip_stats.memp[i];
    if (pool != nullptr) AppendMem(out, std::string("lwip.memp.") + kPoolNames[i], *pool);
  }
}

void HandleControlCommand(std::string_view command, std::string& reply, const CardReport& report,
                          const SetPlugged& set_plugged, hal::ResetControl& reset,
                          sim::SimulatedInverter& inverter) {
  // "link L down" -> words. More than kMaxCommandWords words is no command of ours: the count says so.
  std::string_view words[hal::host::kMaxCommandWords];
  const std::size_t count = hal::host::SplitCommand(command, words);
  const std::string_view verb = count > 0 ? words[0] : std::string_view();
  if (count <= hal::host::kMaxCommandWords && sim::HandleSimCommand(std::span(words, count), reply, inverter)) {
    return;
  }
  if (verb == "help" && count == 1) {
    reply += kHelp;
    reply += sim::kSimControlHelp;
  } else if (verb == "stats" && count == 1) {
    AppendStats(report, reply);
    if (report.drive != nullptr) AppendDriveStats(*report.drive, reply);
    if (report.network != nullptr) AppendNetworkStats(*report.network, reply);
    if (report.pools != nullptr) AppendPoolStats(*report.pools, reply);
  } else if (verb == "config" && count == 1 && report.drive != nullptr) {
    AppendDriveConfig(*report.drive, reply);
  } else if (verb == "leds" && count == 1) {
    reply += report.leds.Describe() + "\n";
  } else if (verb == "address" && count == 1 && report.network != nullptr) {
    reply += DescribeAddress(*report.network) + "\n";
  } else if (verb == "led-inputs" && count == 1 && report.network != nullptr) {
    reply += DescribeLedInputs(*report.network) + "\n";
  } else if (verb == "power-cycle" && count == 1) {
    // The card and the drive lose power together: the inverter's image is stored before the card
    // restarts (re-exec), and the new process starts the inverter from it.
    inverter.PowerCycle();
    reset.RequestReset(hal::ResetKind::kRestart);
  } else if (verb == "link" && count == 3) {
    hal::PortId port{};
    if (!ParsePort(words[1], port) || (words[2] != "up" && words[2] != "down")) {
      reply += "error usage: link L|R up|down\n";
      return;
    }
    const base::Status status = set_plugged(port, words[2] == "up");
    if (!status.ok()) {
      reply += std::string("error port ") + hal::PortLetter(port) + " " + base::StatusName(status) +
               (status.code() == base::StatusCode::kNotFound ? " (not present)" : "") + "\n";
      return;
    }
  } else {
    reply += "error unknown command (try 'help')\n";
    return;
  }
  reply += "ok\n";
}

}  // namespace host
