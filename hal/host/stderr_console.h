// The host's console: diagnostics to stderr (unbuffered), and a fatal error ends the process with
// abort(), so that a developer gets a core dump at the failed assertion.
#pragma once

#include "hal/console.h"

namespace hal::host {

class StderrConsole final : public ConsoleOutput, public FatalHandler {
 public:
  void Write(std::string_view text) override;
  [[noreturn]] void Fatal(std::string_view message) override;
};

}  // namespace hal::host
