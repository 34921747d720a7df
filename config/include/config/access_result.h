// The outcome of one register access: what the card's layers say about a read or write of the
// inverter's registers (the register proxy produces it, the configuration records it for a value it
// could not read, each front end maps it onto its protocol's error: docs/modbus.md, docs/cip.md).
#pragma once

#include <cstdint>

namespace config {

// Why an access failed. Each maps onto one protocol error in each front end (docs/modbus.md, docs/cip.md).
enum class AccessError : std::uint8_t {
  kNone,
  kNoSuchRegister,           // a number ending A-F (refused locally) or the inverter's 0002
  kOutOfRange,               // the inverter's 0001 "data error"
  kNotWritableWhileRunning,  // the inverter's 0000 on a parameter write while the drive runs
  kReadOnly,                 // a monitor (FC00-FEFF), a value the card owns (c502/c503, c517-c522,
                             // c524-c536, c555, c041-c046, c061-c066) or FA30 (the card's fault
                             // line): refused locally
  kReservedForScanner,       // a command register the cyclic exchange owns (IO scanning, §9.1)
  kRefused,                  // the inverter's 0000 otherwise, or 0003 "command error"
  kLinkDown,                 // option fault e-23 or configuration not loaded yet: nothing was sent
  kTimeout,                  // no reply after every retry
  kNetworkLost,              // a run or speed command (FA06 with run/jog, FA07) while a network loss holds
                             // the drive (CommandsHeldByLoss): refused locally, docs/drive-control.md
};

const char* AccessErrorName(AccessError error);

struct AccessResult {
  AccessError error = AccessError::kNone;
  std::uint16_t number = 0;  // the communication number accessed
  std::uint16_t value = 0;   // read: the value; write: the value the inverter accepted
  bool ok() const { return error == AccessError::kNone; }
};

}  // namespace config
