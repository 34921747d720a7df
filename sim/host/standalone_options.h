// Command line of the stand-alone simulated inverter (ipe002z-inverter): where its serial line listens,
// its state dir and control socket, the address keyed into it, and the inverter flags it shares with
// ipe002z-host (inverter_options.h).
#pragma once

#include <string>

#include "address_plan.h"
#include "inverter_options.h"

namespace sim {

struct StandaloneOptions : InverterOptions {
  std::string serial;            // --serial unix:PATH | tcp:HOST:PORT (required)
  std::string state_dir;         // --state-dir; empty: a fresh temporary directory
  std::string sim_control_path;  // --sim-control; empty: no control socket
  bool ip_given = false;         // --ip: c504 = 0 and c505-c516 keyed in at every start
  AddressPlan address;
};

enum class StandaloneParse { kRun, kHelp, kError };

// Parses argv[1..]. On kError, `error` says what was wrong in one line.
StandaloneParse ParseStandaloneOptions(int argc, const char* const* argv, StandaloneOptions& options,
                                       std::string& error);
const char* StandaloneUsage();

}  // namespace sim
