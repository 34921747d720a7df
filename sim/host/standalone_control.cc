#include "standalone_control.h"

#include <array>
#include <cstdint>

#include "control_server.h"
#include "sim_control.h"

namespace sim {
namespace {

constexpr char kHelp[] =
    "help                   this list\n"
    "stats                  the serial line's clients and the protocol server's counters\n"
    "power-cycle            power the inverter off and on (its EEPROM image is stored; the line stays)\n";

void Line(std::string& out, const char* name, std::uint64_t value) {
  out += name;
  out += '=';
  out += std::to_string(value);
  out += '\n';
}

void AppendStats(const SimulatedInverter& inverter, const hal::host::ListeningSerialPort& line, std::string& out) {
  const hal::host::ListeningSerialPort::Counters& serial = line.counters();
  Line(out, "serial.connected", line.connected() ? 1 : 0);
  Line(out, "serial.connections", serial.connections);
  Line(out, "serial.replaced", serial.replaced);
  Line(out, "serial.refused", serial.refused);
  Line(out, "serial.disconnects", serial.disconnects);
  const ServerCounters& server = inverter.server().counters();
  Line(out, "server.requests", server.requests);
  Line(out, "server.ignored", server.ignored);
  Line(out, "server.executed", server.executed);
  Line(out, "server.replies", server.replies);
  Line(out, "server.errors", server.errors);
  Line(out, "server.unanswered", server.unanswered);
  Line(out, "server.in_reset", server.in_reset);
  Line(out, "server.no_reply", server.no_reply);
  Line(out, "server.dropped", server.dropped);
  Line(out, "server.delayed", server.delayed);
  Line(out, "server.corrupted", server.corrupted);
  Line(out, "server.rx_errors", server.rx_errors);
  Line(out, "server.timeouts", server.timeouts);
  const drive_link::wire::FramerCounters& framer = inverter.server().framer_counters();
  Line(out, "framer.frames", framer.frames);
  Line(out, "framer.garbage_bytes", framer.garbage_bytes);
  Line(out, "framer.dropped_frames", framer.dropped_frames);
}

}  // namespace

void HandleStandaloneCommand(std::string_view command, std::string& reply, SimulatedInverter& inverter,
                             const hal::host::ListeningSerialPort& line) {
  std::array<std::string_view, hal::host::kMaxCommandWords> words;
  const std::size_t count = hal::host::SplitCommand(command, words);
  if (count <= words.size() && HandleSimCommand(std::span(words.data(), count), reply, inverter)) return;
  const std::string_view verb = count > 0 ? words[0] : std::string_view();
  if (verb == "help" && count == 1) {
    reply += kHelp;
    reply += kSimControlHelp;
  } else if (verb == "stats" && count == 1) {
    AppendStats(inverter, line, reply);
  } else if (verb == "power-cycle" && count == 1) {
    inverter.PowerCycle();
  } else {
    reply += "error unknown command (try 'help')\n";
    return;
  }
  reply += "ok\n";
}

}  // namespace sim
