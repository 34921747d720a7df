// The register proxy's own transactions (one on the link at a time): which part asked for one, so its
// completion goes back to that part (docs/drive-link.md, "Register proxy").
#pragma once

#include <cstdint>

#include "drive_link/link_client.h"

namespace drive_link {

enum class OwnJobKind : std::uint8_t {
  kNone,
  kConfigRead,    // ConfigLoader; index: position in kConfigNumbers, then F875-F879, then FD01
  kLossCheck,     // LossSupervisor; index: 0 cmod, 1 fmod (c103 = 1/2)
  kLossAction,    // LossSupervisor: the c101 write (index 0), a stop held during the loss (index 1)
  kCommandWrite,  // ScannerExchange; index: command word (0-5 scanner words, 6/7 the drive command)
  kBlockRead,     // ScannerExchange
  kMonitorRead,   // ScannerExchange; index: position in its read plan
  kOwnedWrite,    // CardWriteBack; index: position in its table
};

struct OwnJob {
  OwnJobKind kind = OwnJobKind::kNone;
  std::uint8_t index = 0;
  Transaction transaction{};
};

}  // namespace drive_link
