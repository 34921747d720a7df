// The control socket's `stats` lines for the card's own fixed pools: pool.<name>.used/capacity/
// high_water/refused, one block per pool (docs/robustness.md "Exhaustion" lists them and what counts
// as refused). The pools expose base::PoolStats; only this file knows their names and the format.
#pragma once

#include <string>

#include "drive_link/register_proxy.h"
#include "ethernet_ip_card.h"
#include "hal/clock.h"
#include "modbus/server.h"
#include "modbus_tcp_service.h"
#include "parameter_writer.h"
#include "web/access_control.h"
#include "web/http_server.h"
#include "web_service.h"

namespace host {

struct PoolReport {
  const firmware::ModbusTcpService& modbus_service;
  const modbus::Server& modbus_server;
  const firmware::EtherNetIpCard& eip_card;
  const drive_link::RegisterProxy& proxy;
  const firmware::ParameterWriter& parameter_writer;
  const firmware::WebService& web_service;
  const web::HttpServer& http_server;
  const web::AccessControl& access;
  const hal::Clock& clock;  // web sessions end by time
};

void AppendPoolStats(const PoolReport& report, std::string& out);

}  // namespace host
