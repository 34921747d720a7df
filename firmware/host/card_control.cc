#include "card_control.h"

#include <span>
#include <string>

#include "card_lines.h"
#include "card_report.h"
#include "control_server.h"
#include "sim_control.h"

namespace host {
namespace {

// The shared report's lines appended to a control socket reply.
class ReplySink final : public firmware::ReportSink {
 public:
  explicit ReplySink(std::string& out) : out_(out) {}
  void Line(std::string_view line) override {
    out_ += line;
    out_ += '\n';
  }

 private:
  std::string& out_;
};

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
  ReplySink sink(out);
  firmware::ReportLoopStats(report.loop, sink);
  AppendLine(out, "loop.waits", report.waiter.wait_count());
  firmware::ReportNetifStats(report.netif, sink);
  if (report.card != nullptr) firmware::ReportCardStats(*report.card, sink);
}

void HandleControlCommand(std::string_view command, std::string& reply, const CardReport& report,
                          const SetPlugged& set_plugged, hal::ResetControl& reset,
                          sim::SimulatedInverter* inverter) {
  // "link L down" -> words. More than kMaxCommandWords words is no command of ours: the count says so.
  std::string_view words[hal::host::kMaxCommandWords];
  const std::size_t count = hal::host::SplitCommand(command, words);
  const std::string_view verb = count > 0 ? words[0] : std::string_view();
  if (inverter != nullptr && count <= hal::host::kMaxCommandWords &&
      sim::HandleSimCommand(std::span(words, count), reply, *inverter)) {
    return;
  }
  if (verb == "help" && count == 1) {
    reply += kHelp;
    if (inverter != nullptr) reply += sim::kSimControlHelp;
  } else if (verb == "stats" && count == 1) {
    AppendStats(report, reply);
  } else if (verb == "config" && count == 1 && report.card != nullptr) {
    ReplySink sink(reply);
    firmware::ReportCardConfig(*report.card, sink);
  } else if (verb == "leds" && count == 1) {
    reply += report.leds.Describe() + "\n";
  } else if (verb == "address" && count == 1 && report.card != nullptr) {
    hal::TextLine line;
    firmware::DescribeAddress(report.card->addressing(), line);
    reply += std::string(line.view()) + "\n";
  } else if (verb == "led-inputs" && count == 1 && report.card != nullptr) {
    hal::TextLine line;
    firmware::DescribeLedInputs(*report.card, line);
    reply += std::string(line.view()) + "\n";
  } else if (verb == "power-cycle" && count == 1) {
    // The card and the drive lose power together: the inverter's image is stored before the card
    // restarts (re-exec), and the new process starts the inverter from it.
    if (inverter != nullptr) inverter->PowerCycle();
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
