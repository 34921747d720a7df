// The card's own NV records (hal::NvStore ids) and the factory MAC kept in one of them. The TCP/IP
// settings' record is firmware::kNvTcpIpExtras (cip_providers.h). docs/robustness.md "Power loss" says
// what a power cut during the write of each leaves.
#pragma once

#include "hal/frame_port.h"
#include "hal/nv_store.h"
#include "hal/random.h"

namespace firmware {

// The MAC is factory data: a production line writes it once. A card without one (the host card's
// first start, a board fresh from the debugger) makes up a locally administered one and keeps it.
inline constexpr hal::NvRecordId kNvFactoryMac = 0x0001;
// A board without a true random number generator keeps the seed of its random generator here, renewed
// at every start (docs/board.md "Random numbers").
inline constexpr hal::NvRecordId kNvRandomSeed = 0x0002;
// The web server's read and write passwords, as salted hashes (docs/web.md "Passwords and sessions").
inline constexpr hal::NvRecordId kNvWebPasswords = 0x0020;

// The MAC in kNvFactoryMac; when there is none (or it is not 6 bytes long), a new random unicast,
// locally administered one, written there. A failing write still gives a working card (a read-only
// store), only with a new MAC at each start.
base::MacAddress LoadOrCreateMac(hal::NvStore& store, hal::RandomSource& random);

}  // namespace firmware
