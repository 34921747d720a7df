#include "standalone_options.h"

#include "listening_serial_port.h"

namespace sim {

const char* StandaloneUsage() {
  static const std::string usage =
      std::string(
          "usage: ipe002z-inverter --serial unix:PATH|tcp:HOST:PORT [options]\n"
          "The simulated VF-MB1 / VF-S15 inverter as its own process: it serves the Toshiba inverter protocol\n"
          "on a listening socket, one client at a time (QEMU's UART: -chardev socket,id=ID,path=PATH).\n"
          "  --serial unix:PATH|tcp:HOST:PORT   where the inverter's serial line listens (required); HOST a\n"
          "                                     numeric address or localhost; PORT 0 picks a free port\n"
          "  --state-dir DIR                    persistent state (default: a fresh temporary dir)\n"
          "  --sim-control PATH                 UNIX control socket (line protocol; 'help' lists it)\n"
          "  --ip A.B.C.D/N[,GW]                the card's address, keyed into the inverter at every start:\n"
          "                                     c504 = 0 (manual) and c505-c516 (gateway default 0.0.0.0)\n"
          "simulated inverter (its EEPROM is kept in DIR/inverter/MODEL.eeprom):\n") +
      kInverterOptionsUsage + "  --help                             this text\n";
  return usage.c_str();
}

StandaloneParse ParseStandaloneOptions(int argc, const char* const* argv, StandaloneOptions& options,
                                       std::string& error) {
  for (int i = 1; i < argc; ++i) {
    const std::string flag = argv[i];
    if (flag == "--help" || flag == "-h") return StandaloneParse::kHelp;
    if (TakeInverterSwitch(flag, options)) continue;
    if (i + 1 >= argc) {
      error = flag.rfind("--", 0) == 0 ? "missing value for " + flag : "unexpected argument " + flag;
      return StandaloneParse::kError;
    }
    const std::string value = argv[++i];
    bool ok = true;
    if (flag == "--serial") {
      std::string reason;
      if (!hal::host::ListeningSerialPort::CheckEndpoint(value, &reason)) {
        error = "invalid value for --serial: '" + value + "' (" + reason + ")";
        return StandaloneParse::kError;
      }
      options.serial = value;
    } else if (flag == "--state-dir") {
      options.state_dir = value;
    } else if (flag == "--sim-control") {
      options.sim_control_path = value;
    } else if (flag == "--ip") {
      ok = ParseAddressPlan(value, options.address);
      options.ip_given = ok;
    } else if (const FlagOutcome taken = TakeInverterFlag(flag, value, options); taken != FlagOutcome::kNotOurs) {
      ok = taken == FlagOutcome::kTaken;
    } else {
      error = "unknown option " + flag;
      return StandaloneParse::kError;
    }
    if (!ok || value.empty()) {
      error = "invalid value for " + flag + ": '" + value + "'";
      return StandaloneParse::kError;
    }
  }
  if (options.serial.empty()) {
    error = "missing --serial (unix:PATH or tcp:HOST:PORT)";
    return StandaloneParse::kError;
  }
  if (!CheckPresets(options, error)) return StandaloneParse::kError;
  return StandaloneParse::kRun;
}

}  // namespace sim
