// The values the card owns and writes back into the inverter, always P and only when changed: c502/c503,
// c517-c522 and c524-c535 (the card's status), c536 (the last network event), c555 (the drive status
// code from FD01), c041-c046 / c061-c066 (the scanner words, sampled every display_interval)
// (docs/drive-link.md, "Configuration at start-up and reset"). The scanner exchange offers its writes
// between two cycles.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "config/card_config.h"
#include "drive_link/own_job.h"
#include "drive_link/proxy_config.h"
#include "drive_link/register_access.h"
#include "hal/clock.h"

namespace drive_link {

// Values the card owns and writes back: c502/c503, c517-c522, c524-c535, c536, c555, c041-c046, c061-c066.
inline constexpr std::size_t kOwnedValueCount = 2 + 6 + 12 + 1 + 1 + 6 + 6;

class CardWriteBack {
 public:
  CardWriteBack(const ProxyConfig& config, ProxyCounters& counters) : config_(config), counters_(counters) {}

  // True for the numbers the card owns (written back by the card, refused to other writers).
  static bool IsOwnedNumber(std::uint16_t number);

  // A configuration was loaded: everything is written again (the inverter may have been reset, RAM-only
  // values at 0); c555 and the display values wait for their next value, the first sample is due at `now`.
  void Reload(hal::Micros now);
  // Values that may have been lost in the inverter (a reset too short for e-23) are written again.
  void MarkAllUnknown();

  // c502/c503, c517-c535 and, when ethernet_error changed, c536.
  void SetCardStatus(const config::CardStatus& status);
  // c536: the last network event (a loss cause, 0 when restored or at a card reset).
  void SetEthernetError(std::uint16_t value);
  std::uint16_t ethernet_error() const { return c536_; }
  // c555 from FD01.
  void SetDriveStatus(std::uint16_t fd01);

  // The next write-back; the display values c041-c046 / c061-c066 are sampled first when their
  // interval is due, from `commands` and `monitors`. False when nothing differs from what was written.
  bool NextWrite(hal::Micros now, const ScannerWords& commands, const ScannerWords& monitors, OwnJob& job);
  void OnWritten(std::uint8_t index, const Completion& completion);
  hal::Micros next_display_at() const { return next_display_at_; }

 private:
  struct OwnedValue {
    std::uint16_t number = 0;
    std::uint16_t wanted = 0;
    std::uint16_t written = 0;
    bool written_valid = false;
    bool wanted_valid = false;  // there is a value to show (c555: FD01 was read; c041-c066: sampled)
  };

  void UpdateStatusValues();
  void Set(std::size_t index, std::uint16_t value);

  const ProxyConfig& config_;
  ProxyCounters& counters_;
  std::array<OwnedValue, kOwnedValueCount> owned_{};
  config::CardStatus status_{};
  std::uint16_t c536_ = 0;
  hal::Micros next_display_at_ = 0;
};

}  // namespace drive_link
