// A front end that follows the card's configuration as read from the inverter: c500 opens or closes
// its ports, its protocol settings come from the c-parameters. The card status publisher hands every
// configuration load to each front end (docs/architecture.md).
#pragma once

#include "base/status.h"
#include "config/card_config.h"

namespace firmware {

class ConfigurableService {
 public:
  virtual ~ConfigurableService() = default;
  // A failure (no PCB free for a listener) is retried at the next publish.
  virtual base::Status Configure(const config::CardConfig& config) = 0;
};

// What the publisher learns of the drive once per configuration load: FB05 (model code) and FE08
// (CPU version).
class DriveIdentitySink {
 public:
  virtual ~DriveIdentitySink() = default;
  virtual void OnDriveIdentity(std::uint16_t fb05, std::uint16_t fe08) = 0;
};

}  // namespace firmware
