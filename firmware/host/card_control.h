// The control socket's commands: what the card reports (stats, LEDs) and what a test may do to it
// (unplug a cable, power-cycle); the simulated inverter's commands are in sim_control.h. Kept apart
// from the assembly in host_card.cc.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <string_view>

#include "card.h"
#include "card_netif.h"
#include "event_loop.h"
#include "hal/reset.h"
#include "logging_leds.h"
#include "poll_waiter.h"
#include "sim_inverter.h"

namespace host {

struct CardReport {
  firmware::CardNetif& netif;
  firmware::EventLoop& loop;
  hal::host::LoggingLeds& leds;
  hal::host::PollWaiter& waiter;
  // The rest of the card (drive link, front ends, addressing, pools: firmware/card/card_report.h);
  // null in tests of the network side alone.
  const firmware::Card* card = nullptr;
};

using SetPlugged = std::function<base::Status(hal::PortId, bool)>;

// Appends one `name=value` line: the format of every `stats` counter.
void AppendLine(std::string& out, const std::string& name, std::uint64_t value);

// Appends `name=value` lines: event loop, netif, per-port counters, every lwIP protocol and pool
// counter. Pool lines read lwip.memp.<POOL>.used/max/avail/err; lwip.tcp_pcbs.* count the TCP PCBs by
// list (active, listening, TIME_WAIT: the TCP_PCB pool's used is active + time_wait).
void AppendStats(const CardReport& report, std::string& out);

// Runs one control command and appends its answer (data lines, then "ok" or "error <reason>").
// The inverter's commands (get, set, terminal, trip, inject, status) go to HandleSimCommand;
// power-cycle power-cycles the inverter, stores its image and requests a restart of the card.
// `inverter` is null when the inverter is another process (--drive): its commands are then unknown
// here, and power-cycle restarts the card alone.
void HandleControlCommand(std::string_view command, std::string& reply, const CardReport& report,
                          const SetPlugged& set_plugged, hal::ResetControl& reset,
                          sim::SimulatedInverter* inverter);

}  // namespace host
