// The host-native card: the composition root that builds the firmware on the host HAL and runs it.
//
// It owns every subsystem object (clock, ports, lwIP netif, event loop, LEDs, store, control socket)
// and wires them through constructors; nothing below it keeps global state except the lwIP platform
// binding (see lwip_port.h).
#pragma once

#include <string>

#include "host_options.h"

namespace host {

enum class CardExit {
  kStopped,   // SIGINT/SIGTERM: exit 0
  kRestart,   // reset requested (control 'power-cycle', Identity Reset): the caller re-executes
  kFailed,    // start-up failed; `error` says why
};

CardExit RunHostCard(const HostOptions& options, std::string& error);

}  // namespace host
