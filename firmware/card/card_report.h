// What the card reports about itself, the same on the host's control socket and a board's console:
// the `stats` counters (`name=value` lines), the `config` read from the inverter and the MS/NS model's
// inputs. Written line by line into a ReportSink, with no allocation, so a board reports without a
// heap and the host appends the same lines to its reply (docs/architecture.md "Control socket" lists
// the names; docs/robustness.md "Exhaustion" the pool.* blocks).
#pragma once

#include <cstdint>
#include <initializer_list>
#include <string_view>

#include "card.h"
#include "card_netif.h"
#include "event_loop.h"
#include "hal/text_line.h"

namespace firmware {

// Receives a report, one line at a time (without its newline).
class ReportSink {
 public:
  virtual void Line(std::string_view line) = 0;

  // "NAME=VALUE", the name given in parts ("pool.", "modbus_clients", ".used").
  void Value(std::initializer_list<std::string_view> name, std::uint64_t value);
  void Text(std::initializer_list<std::string_view> name, std::string_view value);

 protected:
  ~ReportSink() = default;
};

// loop.passes, loop.frames_in, loop.bounded_passes, loop.link_changes.
void ReportLoopStats(const EventLoop& loop, ReportSink& out);
// netif.*, port.L.* / port.R.*, and lwIP's protocol, heap, pool and TCP PCB counters (lwip.*).
void ReportNetifStats(const CardNetif& netif, ReportSink& out);
// Everything else the card counts: drive.*, proxy.*, modbus.*, eip.*, cip.*, io.*, params.*, addr.*,
// switch.*, lldp.* (counters and one `lldp.L.0 chassis=... port=... ttl=... name=... mgmt=...` line per
// neighbour), and every fixed pool as pool.<name>.used/capacity/high_water/refused.
void ReportCardStats(const Card& card, ReportSink& out);
// `config`: loaded=, one `name=value` line per setting in force, then `problem=<number> <value> <kind>`.
void ReportCardConfig(const Card& card, ReportSink& out);
// `led-inputs`: "protocol=... configured=... fault=... address=... acquiring=... duplicate=... link=...
// connections=...".
void DescribeLedInputs(const Card& card, hal::TextLine& line);

}  // namespace firmware
