// tools/ipe's command line: `ipe [OPTIONS] COMMAND ARGS... [OPTIONS]`, options anywhere. Pure parsing
// and help texts; the commands live in commands_*.cc.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace ipe {

struct Options {
  std::string command;             // discover, identity, get, set, backup, restore, watch, io, eds
  std::vector<std::string> args;   // the positional arguments after the command
  bool help = false;
  bool modbus = false;             // get/set/backup/restore/watch over Modbus TCP
  std::optional<std::uint16_t> port;
  std::uint32_t timeout_ms = 2000;  // per request
  std::uint8_t unit = 1;           // Modbus unit id (0-248 reach the inverter)
  // discover
  std::string interface_name;
  std::string broadcast;
  // restore
  bool dry_run = false;
  // watch
  std::uint32_t interval_ms = 1000;
  std::optional<std::uint32_t> count;
  // io
  std::uint16_t output_instance = 21;
  std::uint16_t input_instance = 71;
  std::uint32_t rpi_ms = 10;
  bool run = false;
  std::string speed;               // as typed ("30Hz"); parsed against fh's unit by the io command
  std::optional<std::uint32_t> duration_ms;
  std::string io_bind;             // local address of UDP 2222 ("" = chosen from the host)
};

struct ParsedCommandLine {
  bool ok = false;
  Options options;
  std::string error;  // !ok: one line, without the "ipe: " prefix
};

ParsedCommandLine ParseCommandLine(const std::vector<std::string>& arguments);

// The tool's usage (every command, the exit codes), and one command's help ("" for an unknown command).
std::string UsageText();
std::string CommandHelp(const std::string& command);

// The port a command talks to unless --port says otherwise: 44818, or 502 with --modbus.
std::uint16_t DefaultPort(const Options& options);

}  // namespace ipe
