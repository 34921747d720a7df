// The lines a card prints about itself, the same on the host's stdout and a board's console: the
// "ready" line (the card-side part) and the "address" line. Built in a fixed buffer (no allocation),
// so a board prints them without a heap; docs/architecture.md "The ready line" defines the fields.
#pragma once

#include <cstdint>

#include "card.h"
#include "hal/frame_port.h"
#include "hal/text_line.h"

namespace firmware {

// The line builder lives in the HAL (hal/text_line.h): a board's LED and console lines use it too.
using TextLine = hal::TextLine;

// "mode=dhcp phase=in-use ip=A.B.C.D/N gw=G duplicate=0 conflict=<attribute 11 in hex>".
void DescribeAddress(const CardAddressing& addressing, TextLine& line);
// "ip=A.B.C.D mac=aa:bb:cc:dd:ee:ff": the start of the ready line.
void DescribeIdentity(const Card& card, TextLine& line);
// "modbus=A:502 enip=A:44818 enip-udp=A:44818 io=A:2222 http=A:80" for the address in use.
void DescribeEndpoints(base::Ipv4Address address, TextLine& line);

}  // namespace firmware
