// Exit codes of tools/ipe (docs/commissioning.md "Exit codes") and the failure a command throws to end
// with one. Host-only code: the commands are straight-line sequences of network steps, and a failure
// anywhere ends the command with its code and one message.
#pragma once

#include <string>
#include <utility>

namespace ipe {

enum ExitCode : int {
  kExitOk = 0,
  kExitRefused = 1,      // the card answered with an error (CIP status, Modbus exception, encapsulation status)
  kExitUsage = 2,        // bad arguments, unknown parameter, value out of range, wrong model in a file
  kExitUnreachable = 3,  // no answer, connection refused, timeout, a reply that does not decode
};

struct Failure {
  int code;
  std::string message;
};

[[noreturn]] inline void Fail(int code, std::string message) { throw Failure{code, std::move(message)}; }

}  // namespace ipe
