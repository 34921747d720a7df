#include "standalone_inverter.h"

#include <memory>

#include "control_server.h"
#include "host_clock.h"
#include "listening_serial_port.h"
#include "poll_waiter.h"
#include "signal_source.h"
#include "sim_inverter.h"
#include "standalone_control.h"

namespace sim {
namespace {

constexpr char kProgram[] = "ipe002z-inverter";

// One stderr line per change of the serial line's client (a QEMU start, exit or restart).
class LineEvents {
 public:
  LineEvents(const hal::host::ListeningSerialPort& line, std::FILE* log) : line_(line), log_(log) {}

  void Report() {
    const hal::host::ListeningSerialPort::Counters& now = line_.counters();
    if (now.disconnects > seen_.disconnects) Print("serial client gone");
    if (now.connections > seen_.connections) Print("serial client connected");
    if (now.refused > seen_.refused) Print("serial client refused: the line has a client already");
    seen_ = now;
  }

 private:
  void Print(const char* text) {
    std::fprintf(log_, "%s: %s\n", kProgram, text);
    std::fflush(log_);
  }

  const hal::host::ListeningSerialPort& line_;
  std::FILE* log_;
  hal::host::ListeningSerialPort::Counters seen_;
};

}  // namespace

StandaloneExit RunStandaloneInverter(const StandaloneOptions& options, std::FILE* out, std::FILE* log,
                                     std::string& error) {
  // First, so that a stop signal arriving while the inverter starts waits in the signalfd.
  hal::host::SignalSource signals;
  hal::host::HostClock clock;
  hal::host::PollWaiter waiter(clock);

  auto listening = hal::host::ListeningSerialPort::Listen(options.serial, &error);
  if (!listening.ok()) return StandaloneExit::kFailed;
  hal::host::ListeningSerialPort& line = *listening.value();

  SimInverterConfig config;
  config.model = options.model;
  config.directory = options.state_dir + "/inverter";
  config.presets = options.params;
  config.server = ServerConfigFromOptions(options);
  config.program = kProgram;
  std::unique_ptr<SimulatedInverter> inverter = SimulatedInverter::Create(config, line, clock, log, error);
  if (!inverter) return StandaloneExit::kFailed;
  if (options.ip_given && !KeyManualAddress(*inverter, options.address, error)) return StandaloneExit::kFailed;

  waiter.Register(line);                     // new clients, and request bytes that wake the inverter
  waiter.Register(inverter->poll_source());  // the server's reply and receive timers
  waiter.Register(signals);
  std::unique_ptr<hal::host::ControlServer> control;
  if (!options.sim_control_path.empty()) {
    control = std::make_unique<hal::host::ControlServer>(
        options.sim_control_path, [&](std::string_view command, std::string& reply) {
          HandleStandaloneCommand(command, reply, *inverter, line);
        });
    if (!control->Start(error)) return StandaloneExit::kFailed;
    waiter.Register(*control);
  }

  std::fprintf(out, "inverter-ready serial=%s control=%s model=%s state=%s\n", line.endpoint().c_str(),
               options.sim_control_path.empty() ? "-" : options.sim_control_path.c_str(),
               ModelName(options.model), options.state_dir.c_str());
  std::fflush(out);

  LineEvents events(line, log);
  while (!signals.stop_requested()) {
    // The store check is the loop's one service: the wait ends for it at the latest.
    waiter.WaitUntil(inverter->NextDeadline());
    inverter->Poll(clock.NowMicros());
    events.Report();
  }
  inverter->SaveIfChanged();  // at exit: the drive keeps what it was told
  return StandaloneExit::kStopped;
}

}  // namespace sim
