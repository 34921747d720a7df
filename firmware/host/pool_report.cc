#include "pool_report.h"

#include "card_report.h"

namespace host {
namespace {

void AppendPool(std::string& out, const char* name, const base::PoolStats& pool) {
  const std::string prefix = std::string("pool.") + name + ".";
  AppendLine(out, prefix + "used", pool.used);
  AppendLine(out, prefix + "capacity", pool.capacity);
  AppendLine(out, prefix + "high_water", pool.high_water);
  AppendLine(out, prefix + "refused", pool.refused);
}

}  // namespace

void AppendPoolStats(const PoolReport& report, std::string& out) {
  const firmware::EtherNetIpCard& eip = report.eip_card;
  // TCP services: the binding's slots (a PCB each) and the protocol core's table behind them; the two
  // move together, so a difference between them is a leak on one side.
  AppendPool(out, "modbus_tcp_slots", report.modbus_service.slot_pool());
  AppendPool(out, "modbus_clients", report.modbus_server.client_pool());
  AppendPool(out, "eip_tcp_slots", eip.eip_service().slot_pool());
  AppendPool(out, "eip_connections", eip.encapsulation().connection_pool());
  AppendPool(out, "eip_sessions", eip.encapsulation().session_pool());
  AppendPool(out, "eip_delayed_replies", eip.encapsulation().delayed_reply_pool());
  AppendPool(out, "eip_deferred_requests", eip.journal().requester_pool());
  AppendPool(out, "cip_connections", eip.connections().connection_pool());
  AppendPool(out, "cip_explicit_connections", eip.connections().explicit_pool());
  AppendPool(out, "cip_productions", eip.connections().production_pool());
  AppendPool(out, "http_tcp_slots", report.web_service.slot_pool());
  AppendPool(out, "http_clients", report.http_server.client_pool());
  AppendPool(out, "web_sessions", report.access.session_pool(report.clock.NowMicros()));
  AppendPool(out, "proxy_accesses", report.proxy.access_pool());
  AppendPool(out, "parameter_writes", report.parameter_writer.queue_pool());
}

}  // namespace host
