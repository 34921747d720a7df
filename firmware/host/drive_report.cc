#include "drive_report.h"

#include <cstdio>

#include "card_report.h"

namespace host {
namespace {

void Line(std::string& out, const std::string& name, std::uint64_t value) { AppendLine(out, name, value); }

std::string Hex4(std::uint16_t value) {
  char text[8];
  std::snprintf(text, sizeof text, "%04X", value);
  return text;
}

std::string Dotted(const std::array<std::uint8_t, 4>& a) {
  return std::to_string(a[0]) + "." + std::to_string(a[1]) + "." + std::to_string(a[2]) + "." +
         std::to_string(a[3]);
}

const char* ProblemKindName(drive_link::ConfigProblem::Kind kind) {
  switch (kind) {
    case drive_link::ConfigProblem::Kind::kReservedMenu:
      return "reserved-menu";
    case drive_link::ConfigProblem::Kind::kOutOfRange:
      return "out-of-range";
    case drive_link::ConfigProblem::Kind::kUnreadable:
      return "unreadable";
  }
  return "?";
}

template <typename Array>
std::string List(const Array& values) {
  std::string text;
  for (std::size_t i = 0; i < values.size(); ++i) text += (i ? "," : "") + std::to_string(values[i]);
  return text;
}

// The CIP connections, class 1 I/O, connection losses and deferred drive accesses.
void AppendCipStats(const firmware::EtherNetIpCard& card, std::string& out) {
  const cip::ConnectionManager& cm = card.connections();
  Line(out, "cip.connections", cm.ActiveConnections());
  const cip::ConnectionCounters& c = cm.counters();
  Line(out, "cip.open_requests", c.open_requests);
  Line(out, "cip.open_format_rejects", c.open_format_rejects);
  Line(out, "cip.open_resource_rejects", c.open_resource_rejects);
  Line(out, "cip.open_other_rejects", c.open_other_rejects);
  Line(out, "cip.close_requests", c.close_requests);
  Line(out, "cip.connection_timeouts", c.connection_timeouts);
  Line(out, "cip.missed_productions", cm.missed_productions());
  Line(out, "cip.dropped_datagrams", cm.dropped_datagrams());
  Line(out, "cip.io_status", static_cast<std::uint64_t>(cm.IoStatus()));
  const firmware::CipLossCounters& l = card.supervisor().counters();
  Line(out, "cip.lost", card.supervisor().lost() ? 1 : 0);
  Line(out, "cip.loss_timeouts", l.timeouts);
  Line(out, "cip.loss_owner_closes", l.owner_closes);
  Line(out, "cip.loss_idle", l.idle_transitions);
  Line(out, "cip.losses", l.losses);
  Line(out, "cip.restores", l.restores);
  Line(out, "cip.control_lock_refusals", card.control_lock().refusals());
  Line(out, "cip.journal_accesses", card.journal().accesses_started());
  Line(out, "cip.journal_completions", card.journal().completions());
  const firmware::IoCounters& io = card.io_service().counters();
  Line(out, "io.open", card.io_service().running() ? 1 : 0);
  Line(out, "io.received", io.received);
  Line(out, "io.too_long", io.too_long);
  Line(out, "io.sent", io.sent);
  Line(out, "io.send_failed", io.send_failed);
}

}  // namespace

void AppendDriveStats(const DriveReport& report, std::string& out) {
  const drive_link::LinkClient& link = report.proxy.link();
  out += std::string("drive.link=") + drive_link::LinkStateName(link.state()) + "\n";
  const drive_link::LinkCounters& l = link.counters();
  Line(out, "drive.frames_sent", l.frames_sent);
  Line(out, "drive.replies", l.replies);
  Line(out, "drive.retries", l.retries);
  Line(out, "drive.timeouts", l.timeouts);
  Line(out, "drive.error_replies", l.error_replies);
  Line(out, "drive.garbled_frames", l.garbled_frames);
  Line(out, "drive.faults", l.faults);
  const drive_link::ProxyCounters& p = report.proxy.counters();
  Line(out, "proxy.config_loads", p.config_loads);
  Line(out, "proxy.config_problems", report.proxy.parsed_config().problems_total);
  Line(out, "proxy.cycles", p.cycles);
  Line(out, "proxy.cycle_period_us", static_cast<std::uint64_t>(p.cycle_period_last));
  Line(out, "proxy.command_writes", p.command_writes);
  Line(out, "proxy.monitor_reads", p.monitor_reads);
  Line(out, "proxy.block_reads", p.block_reads);
  Line(out, "proxy.owned_writes", p.owned_writes);
  Line(out, "proxy.loss_actions", p.loss_actions);
  Line(out, "proxy.accesses", p.accesses);
  Line(out, "proxy.accesses_ok", p.accesses_ok);
  Line(out, "proxy.fd01", report.proxy.drive_status());
  Line(out, "proxy.c536", report.proxy.ethernet_error());
  Line(out, "proxy.loss_action_active", report.proxy.loss_action_active() ? 1 : 0);
  const modbus::ServerCounters& m = report.modbus_server.counters();
  Line(out, "modbus.listening", report.modbus_service.listening() ? 1 : 0);
  Line(out, "modbus.clients", report.modbus_server.open_connections());
  Line(out, "modbus.accepted", m.accepted);
  Line(out, "modbus.refused", m.refused);
  Line(out, "modbus.requests", m.requests);
  Line(out, "modbus.exceptions", m.exceptions);
  Line(out, "modbus.framing_errors", m.framing_errors);
  Line(out, "modbus.idle_closes", m.idle_closes);
  Line(out, "modbus.lost", report.modbus_service.counters().lost);
  Line(out, "modbus.loss_state", static_cast<std::uint64_t>(report.modbus_server.loss_state()));
  const firmware::EipCounters& e = report.eip_card.eip_service().counters();
  Line(out, "eip.listening", report.eip_card.eip_service().listening() ? 1 : 0);
  Line(out, "eip.connections", report.eip_card.encapsulation().connection_count());
  Line(out, "eip.sessions", report.eip_card.encapsulation().session_count());
  Line(out, "eip.accepted", e.accepted);
  Line(out, "eip.refused", e.refused);
  Line(out, "eip.closed_by_peer", e.closed_by_peer);
  Line(out, "eip.closed_by_card", e.closed_by_card);
  Line(out, "eip.lost", e.lost);
  Line(out, "eip.write_stalls", e.write_stalls);
  Line(out, "eip.udp_received", e.udp_received);
  Line(out, "eip.udp_sent", e.udp_sent);
  Line(out, "eip.udp_dropped", e.udp_dropped);
  Line(out, "eip.deferred_replies", e.deferred_replies);
  Line(out, "eip.deferred_retries", e.deferred_retries);
  AppendCipStats(report.eip_card, out);
  const firmware::ParameterWriterCounters& w = report.parameter_writer.counters();
  Line(out, "params.pending", report.parameter_writer.pending());
  Line(out, "params.written", w.written);
  Line(out, "params.failed", w.failed);
}

void AppendDriveConfig(const DriveReport& report, std::string& out) {
  const drive_link::ParsedConfig& parsed = report.proxy.parsed_config();
  const drive_link::CardConfig& c = parsed.config;
  Line(out, "loaded", report.proxy.config_loaded() ? 1 : 0);
  out += "command_menus=" + List(c.command_menus) + "\n";
  out += "monitor_menus=" + List(c.monitor_menus) + "\n";
  out += std::string("device_name=") + c.device_name.data() + "\n";
  Line(out, "c100", c.loss_delay_tenths);
  Line(out, "c101", c.loss_action);
  Line(out, "c102", c.loss_preset_speed);
  Line(out, "c103", c.loss_condition);
  Line(out, "c500", static_cast<std::uint64_t>(c.protocol));
  Line(out, "c501", c.rate_setting);
  Line(out, "c504", static_cast<std::uint64_t>(c.ip_mode));
  out += "ip=" + Dotted(c.ip) + " netmask=" + Dotted(c.netmask) + " gateway=" + Dotted(c.gateway) + "\n";
  Line(out, "c523", c.timeout_tenths);
  Line(out, "c554", c.web_server ? 1 : 0);
  out += "modbus_master=" + Dotted(c.modbus_master) + "\n";
  Line(out, "c604", c.io_scanning ? 1 : 0);
  Line(out, "cmod", c.cmod);
  Line(out, "fmod", c.fmod);
  for (std::size_t i = 0; i < parsed.problem_count; ++i) {
    const drive_link::ConfigProblem& problem = parsed.problems[i];
    out += "problem=" + Hex4(problem.number) + " " + std::to_string(problem.value) + " " +
           ProblemKindName(problem.kind) + "\n";
  }
}

}  // namespace host
