// The control socket's view of the drive link, the register proxy and the front ends: `stats` lines
// (drive.*, proxy.*, modbus.*, eip.*, cip.*, io.*, params.*) and the `config` command (the configuration read from the inverter and
// every problem found in it). Kept apart from card_report.cc, which covers the network side.
#pragma once

#include <string>

#include "drive_link/register_proxy.h"
#include "modbus/server.h"
#include "ethernet_ip_card.h"
#include "modbus_tcp_service.h"
#include "parameter_writer.h"

namespace host {

struct DriveReport {
  const drive_link::RegisterProxy& proxy;
  const modbus::Server& modbus_server;
  const firmware::ModbusTcpService& modbus_service;
  const firmware::EtherNetIpCard& eip_card;
  const firmware::ParameterWriter& parameter_writer;
};

void AppendDriveStats(const DriveReport& report, std::string& out);

// `config`: one `name=value` line per setting in force, then `problem=<number> <value> <kind>` lines.
void AppendDriveConfig(const DriveReport& report, std::string& out);

}  // namespace host
