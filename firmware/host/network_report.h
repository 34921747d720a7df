// The control socket's view of the card's network side (docs/network.md "On the host"): the addressing
// (mode, phase, address in use, ACD state and attribute 11) and the switch's per-port forwarding, as
// `name=value` lines of `stats` and the answer of `address`.
#pragma once

#include <string>

#include "card_addressing.h"
#include "card_indicators.h"
#include "card_netif.h"

namespace host {

struct NetworkReport {
  const firmware::CardNetif& netif;
  const firmware::CardAddressing& addressing;
  const firmware::CardIndicators& indicators;
};

// addr.* and switch.* lines for `stats`.
void AppendNetworkStats(const NetworkReport& report, std::string& out);
// One line: "mode=dhcp phase=in-use ip=A.B.C.D/N gw=G duplicate=0 conflict=<attribute 11 in hex>".
std::string DescribeAddress(const NetworkReport& report);
// The MS/NS inputs as the indicators see them now: "protocol=... configured=... ...".
std::string DescribeLedInputs(const NetworkReport& report);

}  // namespace host
