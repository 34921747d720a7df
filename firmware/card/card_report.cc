#include "card_report.h"

#include <array>

#include "lwip/stats.h"
#include "lwip_internals.h"

namespace firmware {
namespace {

void ReportProto(ReportSink& out, std::string_view name, const stats_proto& p) {
  out.Value({"lwip.", name, ".xmit"}, p.xmit);
  out.Value({"lwip.", name, ".recv"}, p.recv);
  out.Value({"lwip.", name, ".drop"}, p.drop);
  out.Value({"lwip.", name, ".chkerr"}, p.chkerr);
  out.Value({"lwip.", name, ".lenerr"}, p.lenerr);
  out.Value({"lwip.", name, ".memerr"}, p.memerr);
  out.Value({"lwip.", name, ".proterr"}, p.proterr);
  out.Value({"lwip.", name, ".err"}, p.err);
}

void ReportIgmp(ReportSink& out, const stats_igmp& p) {
  out.Value({"lwip.igmp.xmit"}, p.xmit);
  out.Value({"lwip.igmp.recv"}, p.recv);
  out.Value({"lwip.igmp.drop"}, p.drop);
  out.Value({"lwip.igmp.proterr"}, p.proterr);
  out.Value({"lwip.igmp.tx_join"}, p.tx_join);
  out.Value({"lwip.igmp.tx_leave"}, p.tx_leave);
}

void ReportMem(ReportSink& out, std::string_view prefix, std::string_view name, const stats_mem& m) {
  out.Value({prefix, name, ".used"}, m.used);
  out.Value({prefix, name, ".max"}, m.max);
  out.Value({prefix, name, ".avail"}, m.avail);
  out.Value({prefix, name, ".err"}, m.err);
}

void ReportTcpPcbs(ReportSink& out) {
  const LwipTcpPcbCounts pcbs = CountLwipTcpPcbs();
  out.Value({"lwip.tcp_pcbs.active"}, pcbs.active);
  out.Value({"lwip.tcp_pcbs.time_wait"}, pcbs.time_wait);
  out.Value({"lwip.tcp_pcbs.listen"}, pcbs.listen);
}

void ReportPorts(ReportSink& out, const hal::FramePort& port) {
  for (std::size_t i = 0; i < hal::kMaxPorts; ++i) {
    const auto id = static_cast<hal::PortId>(i);
    const char letter[] = {hal::PortLetter(id), '\0'};
    if (i >= port.PortCount()) {
      out.Text({"port.", letter, ".link"}, "absent");
      continue;
    }
    out.Text({"port.", letter, ".link"}, port.Link(id).up ? "up" : "down");
    const hal::PortCounters c = port.Counters(id);
    out.Value({"port.", letter, ".rx_frames"}, c.rx_frames);
    out.Value({"port.", letter, ".rx_octets"}, c.rx_octets);
    out.Value({"port.", letter, ".rx_errors"}, c.rx_errors);
    out.Value({"port.", letter, ".tx_frames"}, c.tx_frames);
    out.Value({"port.", letter, ".tx_octets"}, c.tx_octets);
    out.Value({"port.", letter, ".tx_errors"}, c.tx_errors);
  }
}

void ReportDrive(const Card& card, ReportSink& out) {
  const drive_link::RegisterProxy& proxy = card.proxy();
  const drive_link::LinkClient& link = proxy.link();
  out.Text({"drive.link"}, drive_link::LinkStateName(link.state()));
  const drive_link::LinkCounters& l = link.counters();
  out.Value({"drive.frames_sent"}, l.frames_sent);
  out.Value({"drive.replies"}, l.replies);
  out.Value({"drive.retries"}, l.retries);
  out.Value({"drive.timeouts"}, l.timeouts);
  out.Value({"drive.error_replies"}, l.error_replies);
  out.Value({"drive.garbled_frames"}, l.garbled_frames);
  out.Value({"drive.faults"}, l.faults);
  const drive_link::ProxyCounters& p = proxy.counters();
  out.Value({"proxy.config_loads"}, p.config_loads);
  out.Value({"proxy.config_problems"}, proxy.parsed_config().problems_total);
  out.Value({"proxy.cycles"}, p.cycles);
  out.Value({"proxy.cycle_period_us"}, static_cast<std::uint64_t>(p.cycle_period_last));
  out.Value({"proxy.command_writes"}, p.command_writes);
  out.Value({"proxy.monitor_reads"}, p.monitor_reads);
  out.Value({"proxy.block_reads"}, p.block_reads);
  out.Value({"proxy.owned_writes"}, p.owned_writes);
  out.Value({"proxy.loss_actions"}, p.loss_actions);
  out.Value({"proxy.accesses"}, p.accesses);
  out.Value({"proxy.accesses_ok"}, p.accesses_ok);
  out.Value({"proxy.fd01"}, proxy.drive_status());
  out.Value({"proxy.c536"}, proxy.ethernet_error());
  out.Value({"proxy.loss_action_active"}, proxy.loss_action_active() ? 1 : 0);
}

void ReportModbus(const Card& card, ReportSink& out) {
  const modbus::Server& server = card.modbus_server();
  const modbus::ServerCounters& m = server.counters();
  out.Value({"modbus.listening"}, card.modbus_service().listening() ? 1 : 0);
  out.Value({"modbus.clients"}, server.open_connections());
  out.Value({"modbus.accepted"}, m.accepted);
  out.Value({"modbus.refused"}, m.refused);
  out.Value({"modbus.requests"}, m.requests);
  out.Value({"modbus.exceptions"}, m.exceptions);
  out.Value({"modbus.framing_errors"}, m.framing_errors);
  out.Value({"modbus.idle_closes"}, m.idle_closes);
  out.Value({"modbus.lost"}, card.modbus_service().counters().lost);
  out.Value({"modbus.loss_state"}, static_cast<std::uint64_t>(server.loss_state()));
}

void ReportEip(const EtherNetIpCard& eip, ReportSink& out) {
  const EipCounters& e = eip.eip_service().counters();
  out.Value({"eip.listening"}, eip.eip_service().listening() ? 1 : 0);
  out.Value({"eip.connections"}, eip.encapsulation().connection_count());
  out.Value({"eip.sessions"}, eip.encapsulation().session_count());
  out.Value({"eip.accepted"}, e.accepted);
  out.Value({"eip.refused"}, e.refused);
  out.Value({"eip.closed_by_peer"}, e.closed_by_peer);
  out.Value({"eip.closed_by_card"}, e.closed_by_card);
  out.Value({"eip.lost"}, e.lost);
  out.Value({"eip.write_stalls"}, e.write_stalls);
  out.Value({"eip.udp_received"}, e.udp_received);
  out.Value({"eip.udp_sent"}, e.udp_sent);
  out.Value({"eip.udp_dropped"}, e.udp_dropped);
  out.Value({"eip.deferred_replies"}, e.deferred_replies);
  out.Value({"eip.deferred_retries"}, e.deferred_retries);
}

// The CIP connections, class 1 I/O, connection losses and deferred drive accesses.
void ReportCip(const EtherNetIpCard& eip, ReportSink& out) {
  const cip::ConnectionManager& cm = eip.connections();
  out.Value({"cip.connections"}, cm.ActiveConnections());
  const cip::ConnectionCounters& c = cm.counters();
  out.Value({"cip.open_requests"}, c.open_requests);
  out.Value({"cip.open_format_rejects"}, c.open_format_rejects);
  out.Value({"cip.open_resource_rejects"}, c.open_resource_rejects);
  out.Value({"cip.open_other_rejects"}, c.open_other_rejects);
  out.Value({"cip.close_requests"}, c.close_requests);
  out.Value({"cip.connection_timeouts"}, c.connection_timeouts);
  out.Value({"cip.missed_productions"}, cm.missed_productions());
  out.Value({"cip.dropped_datagrams"}, cm.dropped_datagrams());
  out.Value({"cip.io_status"}, static_cast<std::uint64_t>(cm.IoStatus()));
  const CipLossCounters& l = eip.supervisor().counters();
  out.Value({"cip.lost"}, eip.supervisor().lost() ? 1 : 0);
  out.Value({"cip.loss_timeouts"}, l.timeouts);
  out.Value({"cip.loss_owner_closes"}, l.owner_closes);
  out.Value({"cip.loss_idle"}, l.idle_transitions);
  out.Value({"cip.losses"}, l.losses);
  out.Value({"cip.restores"}, l.restores);
  out.Value({"cip.control_lock_refusals"}, eip.control_lock().refusals());
  out.Value({"cip.journal_accesses"}, eip.journal().accesses_started());
  out.Value({"cip.journal_completions"}, eip.journal().completions());
  const IoCounters& io = eip.io_service().counters();
  out.Value({"io.open"}, eip.io_service().running() ? 1 : 0);
  out.Value({"io.received"}, io.received);
  out.Value({"io.too_long"}, io.too_long);
  out.Value({"io.sent"}, io.sent);
  out.Value({"io.send_failed"}, io.send_failed);
}

void ReportNetwork(const Card& card, ReportSink& out) {
  const AddressingCounters& a = card.addressing().counters();
  out.Value({"addr.restarts"}, a.restarts);
  out.Value({"addr.address_changes"}, a.address_changes);
  out.Value({"addr.bootp_requests"}, a.bootp_requests);
  out.Value({"addr.bootp_replies"}, a.bootp_replies);
  out.Value({"addr.bootp_ignored"}, a.bootp_ignored);
  out.Value({"addr.dhcp_restarts"}, a.dhcp_restarts);
  out.Value({"addr.acd_frames_sent"}, a.acd_frames_sent);
  out.Value({"addr.acd_conflicts"}, a.acd_conflicts);
  out.Value({"addr.duplicate"}, card.addressing().duplicate_detected() ? 1 : 0);
  for (std::size_t i = 0; i < hal::kMaxPorts; ++i) {
    const auto id = static_cast<hal::PortId>(i);
    const char letter[] = {hal::PortLetter(id), '\0'};
    const PortTraffic& t = card.netif().traffic(id);
    out.Value({"switch.", letter, ".forwarded"}, t.forwarded);
    out.Value({"switch.", letter, ".in_ucast"}, t.in_ucast);
    out.Value({"switch.", letter, ".in_nucast"}, t.in_nucast);
    out.Value({"switch.", letter, ".out_ucast"}, t.out_ucast);
    out.Value({"switch.", letter, ".out_nucast"}, t.out_nucast);
    out.Value({"switch.", letter, ".out_discards"}, t.out_discards);
  }
}

// The ring node (docs/network.md "Ring (DLR)"): the DLR object's view plus the node's counters.
void ReportRing(const Card& card, ReportSink& out) {
  const net::DlrRingStatus& s = card.ring().status();
  static constexpr std::string_view kStates[] = {"idle", "fault", "normal"};
  out.Value({"dlr.topology"}, static_cast<std::uint64_t>(s.topology));
  out.Value({"dlr.network_status"}, static_cast<std::uint64_t>(s.network_status));
  out.Text({"dlr.state"}, kStates[static_cast<std::size_t>(s.node_state)]);
  hal::TextLine supervisor;
  supervisor.Mac(s.supervisor.mac).Text(" ").Ipv4(s.supervisor.ip);
  out.Text({"dlr.supervisor"}, s.supervisor_known ? supervisor.view() : "none");
  out.Value({"dlr.supervisor_precedence"}, s.supervisor.precedence);
  out.Value({"dlr.beacon_interval_us"}, s.supervisor.beacon_interval_us);
  out.Value({"dlr.beacon_timeout_us"}, s.supervisor.beacon_timeout_us);
  const net::DlrCounters& c = s.counters;
  out.Value({"dlr.frames_in"}, c.frames_in);
  out.Value({"dlr.malformed"}, c.malformed);
  out.Value({"dlr.neighbor_checks_answered"}, c.neighbor_checks_answered);
  out.Value({"dlr.link_status_sent"}, c.link_status_sent);
  out.Value({"dlr.neighbor_status_sent"}, c.neighbor_status_sent);
  out.Value({"dlr.sign_ons"}, c.sign_ons);
  out.Value({"dlr.flushes"}, c.flushes);
  out.Value({"dlr.ring_faults"}, c.ring_faults);
  out.Value({"dlr.transmit_dropped"}, c.transmit_dropped);
  out.Value({"dlr.frames_sent"}, card.ring().frames_sent());
  out.Value({"dlr.send_failures"}, card.ring().send_failures());
  for (std::size_t i = 0; i < net::kDlrPorts; ++i) {
    const char letter[] = {hal::PortLetter(static_cast<hal::PortId>(i)), '\0'};
    out.Value({"dlr.", letter, ".frames"}, s.ports[i].frames);
    out.Value({"dlr.", letter, ".beacons"}, s.ports[i].beacons);
    out.Value({"dlr.", letter, ".answered"}, s.ports[i].answered);
  }
  out.Value({"switch.learned"}, card.netif().learned_stations());
  out.Value({"switch.learning_flushes"}, card.netif().counters().learning_flushes);
  out.Value({"switch.protocol_frames"}, card.netif().counters().switch_protocol_frames);
}

// lldp.* counters, then one line per neighbour: "lldp.L.0 chassis=... port=... ttl=... name=... mgmt=...".
void ReportLldp(const net::LldpAgent& agent, ReportSink& out) {
  const net::LldpCounters& c = agent.counters();
  out.Value({"lldp.frames_in"}, c.frames_in);
  out.Value({"lldp.frames_out"}, c.frames_out);
  out.Value({"lldp.malformed"}, c.malformed);
  out.Value({"lldp.table_full"}, c.table_full);
  out.Value({"lldp.aged_out"}, c.aged_out);
  out.Value({"lldp.neighbours"}, agent.neighbours().size());
  std::array<std::uint64_t, net::kLldpPorts> per_port{};
  for (const net::LldpNeighbour& n : agent.neighbours()) {
    const char letter[] = {hal::PortLetter(static_cast<hal::PortId>(n.port)), '\0'};
    hal::TextLine line;
    line.Text("lldp.").Text(letter).Text(".").Unsigned(per_port[n.port]++).Text(" chassis=");
    DescribeLldpId(n.info.chassis, true, line);
    line.Text(" port=");
    DescribeLldpId(n.info.port, false, line);
    line.Text(" ttl=").Unsigned(n.info.ttl_seconds).Text(" name=");
    DescribeLldpText(n.info.system_name.view(), line);
    line.Text(" mgmt=");
    if (n.info.management.IsUnspecified()) {
      line.Text("none");
    } else {
      line.Ipv4(n.info.management);
    }
    out.Line(line.view());
  }
}

void ReportPool(ReportSink& out, std::string_view name, const base::PoolStats& pool) {
  out.Value({"pool.", name, ".used"}, pool.used);
  out.Value({"pool.", name, ".capacity"}, pool.capacity);
  out.Value({"pool.", name, ".high_water"}, pool.high_water);
  out.Value({"pool.", name, ".refused"}, pool.refused);
}

void ReportPools(const Card& card, ReportSink& out) {
  const EtherNetIpCard& eip = card.eip();
  // TCP services: the binding's slots (a PCB each) and the protocol core's table behind them; the two
  // move together, so a difference between them is a leak on one side.
  ReportPool(out, "modbus_tcp_slots", card.modbus_service().slot_pool());
  ReportPool(out, "modbus_clients", card.modbus_server().client_pool());
  ReportPool(out, "eip_tcp_slots", eip.eip_service().slot_pool());
  ReportPool(out, "eip_connections", eip.encapsulation().connection_pool());
  ReportPool(out, "eip_sessions", eip.encapsulation().session_pool());
  ReportPool(out, "eip_delayed_replies", eip.encapsulation().delayed_reply_pool());
  ReportPool(out, "eip_deferred_requests", eip.journal().requester_pool());
  ReportPool(out, "cip_connections", eip.connections().connection_pool());
  ReportPool(out, "cip_explicit_connections", eip.connections().explicit_pool());
  ReportPool(out, "cip_productions", eip.connections().production_pool());
  ReportPool(out, "http_tcp_slots", card.web_service().slot_pool());
  ReportPool(out, "http_clients", card.http_server().client_pool());
  ReportPool(out, "http_responses", card.http_server().response_pool());
  ReportPool(out, "web_sessions", card.access().session_pool(card.clock().NowMicros()));
  ReportPool(out, "proxy_accesses", card.proxy().access_pool());
  ReportPool(out, "parameter_writes", card.parameter_writer().queue_pool());
}

const char* ProblemKindName(config::ConfigProblem::Kind kind) {
  switch (kind) {
    case config::ConfigProblem::Kind::kReservedMenu:
      return "reserved-menu";
    case config::ConfigProblem::Kind::kOutOfRange:
      return "out-of-range";
    case config::ConfigProblem::Kind::kUnreadable:
      return "unreadable";
  }
  return "?";
}

template <typename Array>
void List(hal::TextLine& line, const Array& values) {
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (i != 0) line.Text(",");
    line.Unsigned(values[i]);
  }
}

// Four uppercase hex digits, as the parameter numbers are written (0x0C81 -> "0C81").
void Hex4(hal::TextLine& line, std::uint16_t value) {
  static constexpr char kDigits[] = "0123456789ABCDEF";
  const char text[4] = {kDigits[(value >> 12) & 0xF], kDigits[(value >> 8) & 0xF], kDigits[(value >> 4) & 0xF],
                        kDigits[value & 0xF]};
  line.Text(std::string_view(text, sizeof text));
}

}  // namespace

void ReportSink::Value(std::initializer_list<std::string_view> name, std::uint64_t value) {
  hal::TextLine line;
  for (const std::string_view part : name) line.Text(part);
  line.Text("=").Unsigned(value);
  Line(line.view());
}

void ReportSink::Text(std::initializer_list<std::string_view> name, std::string_view value) {
  hal::TextLine line;
  for (const std::string_view part : name) line.Text(part);
  line.Text("=").Text(value);
  Line(line.view());
}

void ReportLoopStats(const EventLoop& loop, ReportSink& out) {
  const LoopStats& stats = loop.stats();
  out.Value({"loop.passes"}, stats.passes);
  out.Value({"loop.frames_in"}, stats.frames_in);
  out.Value({"loop.bounded_passes"}, stats.bounded_passes);
  out.Value({"loop.link_changes"}, stats.link_changes);
  out.Value({"loop.polls"}, stats.polls);
  out.Value({"loop.event_passes"}, stats.event_passes);
}

void ReportNetifStats(const CardNetif& netif, ReportSink& out) {
  out.Text({"netif.link"}, netif.link_up() ? "up" : "down");
  const NetifCounters& n = netif.counters();
  out.Value({"netif.rx_frames"}, n.rx_frames);
  out.Value({"netif.rx_dropped_no_pbuf"}, n.rx_dropped_no_pbuf);
  out.Value({"netif.rx_port_errors"}, n.rx_port_errors);
  out.Value({"netif.tx_frames"}, n.tx_frames);
  out.Value({"netif.tx_dropped"}, n.tx_dropped);
  out.Value({"netif.arp_answered"}, netif.arp_guard_counters().answered);
  out.Value({"netif.arp_dropped"}, netif.arp_guard_counters().dropped);
  ReportPorts(out, netif.port());
  ReportProto(out, "link", lwip_stats.link);
  ReportProto(out, "etharp", lwip_stats.etharp);
  ReportProto(out, "ip", lwip_stats.ip);
  ReportProto(out, "icmp", lwip_stats.icmp);
  ReportIgmp(out, lwip_stats.igmp);
  ReportProto(out, "udp", lwip_stats.udp);
  ReportProto(out, "tcp", lwip_stats.tcp);
  ReportTcpPcbs(out);
  ReportMem(out, "lwip.mem", "", lwip_stats.mem);
  for (std::size_t i = 0; i < kLwipPoolCount; ++i) {
    const stats_mem* pool = lwip_stats.memp[i];
    if (pool != nullptr) ReportMem(out, "lwip.memp.", LwipPoolName(i), *pool);
  }
}

void ReportCardStats(const Card& card, ReportSink& out) {
  ReportDrive(card, out);
  ReportModbus(card, out);
  ReportEip(card.eip(), out);
  ReportCip(card.eip(), out);
  const ParameterWriterCounters& w = card.parameter_writer().counters();
  out.Value({"params.pending"}, card.parameter_writer().pending());
  out.Value({"params.written"}, w.written);
  out.Value({"params.failed"}, w.failed);
  ReportNetwork(card, out);
  ReportRing(card, out);
  ReportLldp(card.lldp().agent(), out);
  ReportPools(card, out);
}

void ReportCardConfig(const Card& card, ReportSink& out) {
  const config::ParsedConfig& parsed = card.proxy().parsed_config();
  const config::CardConfig& c = parsed.config;
  out.Value({"loaded"}, card.proxy().config_loaded() ? 1 : 0);
  hal::TextLine line;
  line.Text("command_menus=");
  List(line, c.command_menus);
  out.Line(line.view());
  line.Clear();
  line.Text("monitor_menus=");
  List(line, c.monitor_menus);
  out.Line(line.view());
  out.Text({"device_name"}, std::string_view(c.device_name.data()));
  out.Value({"c100"}, c.loss_delay_tenths);
  out.Value({"c101"}, c.loss_action);
  out.Value({"c102"}, c.loss_preset_speed);
  out.Value({"c103"}, c.loss_condition);
  out.Value({"c500"}, static_cast<std::uint64_t>(c.protocol));
  out.Value({"c501"}, c.rate_setting);
  out.Value({"c504"}, static_cast<std::uint64_t>(c.ip_mode));
  line.Clear();
  line.Text("ip=");
  line.Ipv4(c.ip);
  line.Text(" netmask=");
  line.Ipv4(c.netmask);
  line.Text(" gateway=");
  line.Ipv4(c.gateway);
  out.Line(line.view());
  out.Value({"c523"}, c.timeout_tenths);
  out.Value({"c554"}, c.web_server ? 1 : 0);
  line.Clear();
  line.Text("modbus_master=");
  line.Ipv4(c.modbus_master);
  out.Line(line.view());
  out.Value({"c604"}, c.io_scanning ? 1 : 0);
  out.Value({"cmod"}, c.cmod);
  out.Value({"fmod"}, c.fmod);
  for (std::size_t i = 0; i < parsed.problem_count; ++i) {
    const config::ConfigProblem& problem = parsed.problems[i];
    line.Clear();
    line.Text("problem=");
    Hex4(line, problem.number);
    line.Text(" ").Unsigned(problem.value).Text(" ").Text(ProblemKindName(problem.kind));
    out.Line(line.view());
  }
}

void DescribeLedInputs(const Card& card, hal::TextLine& line) {
  const net::LedInputs in = card.indicators().Gather();
  static constexpr const char* kConnections[] = {"none", "established", "timed-out"};
  static constexpr const char* kFaults[] = {"none", "minor", "major"};
  line.Text("protocol=").Text(in.protocol == net::Protocol::kEtherNetIp ? "eip" : "modbus");
  line.Text(" configured=").Text(in.configured ? "1" : "0");
  line.Text(" fault=").Text(kFaults[static_cast<int>(in.fault)]);
  line.Text(" address=").Text(in.has_address ? "1" : "0");
  line.Text(" acquiring=").Text(in.acquiring_address ? "1" : "0");
  line.Text(" duplicate=").Text(in.duplicate_address ? "1" : "0");
  line.Text(" link=").Text(in.any_link_up ? "1" : "0");
  line.Text(" connections=").Text(kConnections[static_cast<int>(in.connections)]);
}

}  // namespace firmware
