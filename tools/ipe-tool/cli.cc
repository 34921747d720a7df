#include "cli.h"

#include <algorithm>
#include <array>
#include <cstdlib>
#include <string_view>

#include "values.h"

namespace ipe {
namespace {

struct CommandSpec {
  const char* name;
  std::size_t min_args;
  std::size_t max_args;  // SIZE_MAX: any number
  const char* options;   // the command's own options, space-separated
  const char* help;
};

constexpr std::size_t kMany = static_cast<std::size_t>(-1);

constexpr std::array<CommandSpec, 9> kCommands{{
    {"discover", 0, 0, "--interface --broadcast",
     "usage: ipe discover [--interface IF | --broadcast ADDR] [--timeout MS] [--port N]\n"
     "Sends an EtherNet/IP ListIdentity (UDP 44818) to the broadcast address of IF (or to ADDR, or to\n"
     "255.255.255.255) and prints one line per card that answers within the timeout:\n"
     "  IP vendor product-code product-name serial revision status\n"},
    {"identity", 1, 1, "",
     "usage: ipe identity HOST [--port N] [--timeout MS]\n"
     "Reads the Identity object (class 0x01 instance 1, Get_Attributes_All) and prints every attribute.\n"},
    {"get", 2, kMany, "--modbus --unit",
     "usage: ipe get HOST NAME... [--modbus [--unit ID]] [--port N] [--timeout MS]\n"
     "Reads drive parameters by panel title (acc, dec, fh, c101, fd00 ...) and prints 'name = value unit'.\n"
     "EtherNet/IP: Parameter object 0x64 (0x65 for c-parameters) attribute 3; --modbus: FC 03 on the\n"
     "communication number (unit 1 unless --unit).\n"},
    {"set", 2, kMany, "--modbus --unit",
     "usage: ipe set HOST NAME=VALUE... [--modbus [--unit ID]] [--port N] [--timeout MS]\n"
     "Writes drive parameters in their own unit (acc=5.0 or acc=5s, fh=60Hz). Every value is checked\n"
     "against the parameter's limits for the card's model before anything is sent (exit 2).\n"},
    {"backup", 2, 2, "--modbus --unit",
     "usage: ipe backup HOST FILE [--modbus [--unit ID]] [--port N] [--timeout MS]\n"
     "Saves every writable EEPROM parameter of the card's model to FILE (text: a header, then\n"
     "'name = value unit  # number function' lines). Progress on stderr.\n"},
    {"restore", 2, 2, "--modbus --unit --dry-run",
     "usage: ipe restore HOST FILE [--dry-run] [--modbus [--unit ID]] [--port N] [--timeout MS]\n"
     "Compares FILE with the card, prints 'name: card -> file' for each difference and writes only\n"
     "those (not with --dry-run). Refuses a file of another model (exit 2) and a running drive (exit 1).\n"
     "Lists the parameters that act only after a reset (f899 = 1 or a power cycle). Exit 1 when any\n"
     "write was refused (each is named with the card's status).\n"},
    {"watch", 2, kMany, "--modbus --unit --interval --count",
     "usage: ipe watch HOST NAME... [--interval MS] [--count N] [--modbus [--unit ID]]\n"
     "Prints the named values (fd00 output frequency, fd01 status ...) on one line per interval until\n"
     "Ctrl-C (exit 0) or N lines.\n"},
    {"io", 1, 1, "--connection --rpi --run --speed --duration --io-bind",
     "usage: ipe io HOST [--connection 21/71] [--rpi 10ms] [--run] [--speed 30Hz] [--duration S]\n"
     "               [--io-bind ADDR]\n"
     "Opens a class 1 exclusive-owner connection (output 21, input 71), sends Run Fwd/NetCtrl/NetRef and\n"
     "the speed (in Hz, converted to rpm with the card's f856) at the RPI on UDP 2222 and shows the\n"
     "input assembly decoded on one line. At Ctrl-C or after S seconds it sends a stop for 1 s (when it\n"
     "ran) and closes with Forward_Close. UDP 2222 is bound on 127.0.0.1 for a loopback card, else on\n"
     "any address (--io-bind overrides).\n"},
    {"eds", 2, 2, "",
     "usage: ipe eds HOST FILE [--port N] [--timeout MS]\n"
     "Uploads the card's EDS through the File object (class 0x37 instance 0xC8: Initiate_Upload,\n"
     "Upload_Transfer) into FILE and checks its checksum.\n"},
}};

const CommandSpec* FindCommand(std::string_view name) {
  for (const CommandSpec& spec : kCommands) {
    if (name == spec.name) return &spec;
  }
  return nullptr;
}

bool CommandTakes(const CommandSpec& spec, std::string_view option) {
  std::string_view list = spec.options;
  while (!list.empty()) {
    const std::size_t space = list.find(' ');
    if (list.substr(0, space) == option) return true;
    if (space == std::string_view::npos) break;
    list.remove_prefix(space + 1);
  }
  return false;
}

bool ParseUnsigned(std::string_view text, std::uint32_t max, std::uint32_t& value) {
  if (text.empty() || text.size() > 10) return false;
  std::uint64_t v = 0;
  for (char c : text) {
    if (c < '0' || c > '9') return false;
    v = v * 10 + static_cast<std::uint64_t>(c - '0');
  }
  if (v > max) return false;
  value = static_cast<std::uint32_t>(v);
  return true;
}

ParsedCommandLine Error(std::string message) {
  ParsedCommandLine parsed;
  parsed.error = std::move(message);
  return parsed;
}

constexpr std::array<const char*, 3> kFlags{"--modbus", "--run", "--dry-run"};
constexpr std::array<const char*, 3> kGlobalOptions{"--port", "--timeout", "--help"};

}  // namespace

ParsedCommandLine ParseCommandLine(const std::vector<std::string>& arguments) {
  ParsedCommandLine parsed;
  Options& o = parsed.options;
  std::vector<std::pair<std::string, std::string>> options;  // name, value ("" for flags)
  for (std::size_t i = 0; i < arguments.size(); ++i) {
    std::string argument = arguments[i];
    if (argument == "-h" || argument == "--help") {
      o.help = true;
      continue;
    }
    if (argument.size() > 2 && argument.rfind("--", 0) == 0) {
      std::string value;
      const std::size_t equals = argument.find('=');
      const bool flag = std::find(kFlags.begin(), kFlags.end(), argument) != kFlags.end();
      if (equals != std::string::npos) {
        value = argument.substr(equals + 1);
        argument.resize(equals);
      } else if (!flag) {
        if (i + 1 >= arguments.size()) return Error("option " + argument + " needs a value");
        value = arguments[++i];
      }
      options.emplace_back(argument, value);
      continue;
    }
    if (o.command.empty()) o.command = argument;
    else o.args.push_back(argument);
  }
  if (o.command.empty()) {
    if (o.help) {
      parsed.ok = true;
      return parsed;
    }
    return Error("no command given (try: ipe --help)");
  }
  const CommandSpec* spec = FindCommand(o.command);
  if (spec == nullptr) return Error("unknown command '" + o.command + "' (try: ipe --help)");
  if (o.help) {
    parsed.ok = true;
    return parsed;
  }
  for (const auto& [name, value] : options) {
    const bool global = std::find(kGlobalOptions.begin(), kGlobalOptions.end(), name) != kGlobalOptions.end();
    if (!global && !CommandTakes(*spec, name)) return Error("option " + name + " does not apply to '" + o.command + "'");
    std::uint32_t number = 0;
    if (name == "--port") {
      if (!ParseUnsigned(value, 65535, number) || number == 0) return Error("--port wants 1-65535, not '" + value + "'");
      o.port = static_cast<std::uint16_t>(number);
    } else if (name == "--timeout") {
      if (!ParseMillis(value, number) || number > 60000) return Error("--timeout wants 1-60000 ms, not '" + value + "'");
      o.timeout_ms = number;
    } else if (name == "--modbus") {
      o.modbus = true;
    } else if (name == "--unit") {
      if (!ParseUnsigned(value, 248, number)) return Error("--unit wants 0-248 (the drive's unit ids), not '" + value + "'");
      o.unit = static_cast<std::uint8_t>(number);
    } else if (name == "--interface") {
      o.interface_name = value;
    } else if (name == "--broadcast") {
      o.broadcast = value;
    } else if (name == "--dry-run") {
      o.dry_run = true;
    } else if (name == "--interval") {
      if (!ParseMillis(value, number)) return Error("--interval wants a duration (500ms, 1s), not '" + value + "'");
      o.interval_ms = number;
    } else if (name == "--count") {
      if (!ParseUnsigned(value, 1000000, number) || number == 0) return Error("--count wants 1-1000000, not '" + value + "'");
      o.count = number;
    } else if (name == "--connection") {
      const std::size_t slash = value.find('/');
      std::uint32_t out = 0, in = 0;
      if (slash == std::string::npos || !ParseUnsigned(value.substr(0, slash), 65535, out) ||
          !ParseUnsigned(value.substr(slash + 1), 65535, in)) {
        return Error("--connection wants OUTPUT/INPUT assembly instances (21/71), not '" + value + "'");
      }
      if (out != 21 || in != 71) return Error("--connection: only 21/71 is supported by ipe io");
      o.output_instance = static_cast<std::uint16_t>(out);
      o.input_instance = static_cast<std::uint16_t>(in);
    } else if (name == "--rpi") {
      if (!ParseMillis(value, number) || number > 10000) return Error("--rpi wants 1ms-10s, not '" + value + "'");
      o.rpi_ms = number;
    } else if (name == "--run") {
      o.run = true;
    } else if (name == "--speed") {
      o.speed = value;
    } else if (name == "--duration") {
      std::uint32_t millis = 0;
      // Seconds by default ("--duration 5"); "500ms" and "2s" are taken too.
      const bool plain = !value.empty() && value.find_first_not_of("0123456789.") == std::string::npos;
      if (!ParseMillis(plain ? value + "s" : value, millis)) return Error("--duration wants seconds, not '" + value + "'");
      o.duration_ms = millis;
    } else if (name == "--io-bind") {
      o.io_bind = value;
    }
  }
  if (!o.interface_name.empty() && !o.broadcast.empty()) return Error("discover takes --interface or --broadcast, not both");
  if (o.args.size() < spec->min_args || o.args.size() > spec->max_args) {
    return Error("wrong number of arguments for '" + o.command + "'\n" + spec->help);
  }
  parsed.ok = true;
  return parsed;
}

std::string UsageText() {
  std::string text =
      "usage: ipe [--port N] [--timeout MS] COMMAND ARGS...\n"
      "Commissioning tool for the IPE002Z-class EtherNet/IP + Modbus TCP card (docs/commissioning.md).\n"
      "commands:\n";
  for (const CommandSpec& spec : kCommands) {
    const std::string help = spec.help;
    text += "  " + help.substr(7, help.find('\n') - 7) + "\n";
  }
  text +=
      "'ipe COMMAND --help' describes one command.\n"
      "exit codes: 0 ok, 1 refused by the card, 2 bad arguments/unknown parameter/value out of range/wrong\n"
      "model, 3 host unreachable/timeout/connection refused/undecodable reply.\n";
  return text;
}

std::string CommandHelp(const std::string& command) {
  const CommandSpec* spec = FindCommand(command);
  return spec == nullptr ? "" : spec->help;
}

std::uint16_t DefaultPort(const Options& options) {
  if (options.port) return *options.port;
  return options.modbus ? 502 : 44818;
}

}  // namespace ipe
