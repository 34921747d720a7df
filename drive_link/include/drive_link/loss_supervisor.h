// The register proxy's loss supervision: the front end reports its network lost; after c100 the c103
// condition is checked (cmod/fmod read fresh for 1 and 2) and the c101 action carried out over the link,
// FA06 (or FA30 for err8) written and refreshed until the network returns; c536 shows the cause; a stop
// taken during the loss is held (seed 000 §3.2.3; docs/drive-link.md, "Loss actions";
// docs/drive-control.md). While an action is in force the scanner exchange writes no command word.
#pragma once

#include <cstdint>

#include "drive_link/card_write_back.h"
#include "drive_link/config_loader.h"
#include "drive_link/own_job.h"
#include "drive_link/proxy_config.h"
#include "drive_link/register_access.h"
#include "drive_link/scanner_exchange.h"
#include "hal/clock.h"

namespace drive_link {

class LossSupervisor {
 public:
  LossSupervisor(const ConfigLoader& loader, ScannerExchange& exchange, CardWriteBack& write_back,
                 const ProxyConfig& config, ProxyCounters& counters)
      : loader_(loader), exchange_(exchange), write_back_(write_back), config_(config), counters_(counters) {}

  // ---- The front ends (LossSupervision, DriveCommandChannel) ----
  // False when a loss was already reported (nothing changes).
  bool NetworkLost(LossCause cause, hal::Micros now);
  void NetworkRestored();
  bool action_active() const { return state_ == State::kActive && action_ != kContinue; }
  bool CommandsHeldByLoss() const;
  // False when the stop was not taken (no loss holds FA06, or `fa06` runs the drive).
  bool HoldStopDuringLoss(std::uint16_t fa06);

  // ---- The proxy ----
  // Start-up or f899: the loss state starts afresh.
  void CardReset();
  // A load ended: an action in force is carried out again (the inverter may have lost it).
  void OnConfigLoaded();
  // c100 ran out (with a configuration loaded): decide, or start the c103 check.
  void Poll(hal::Micros now);
  // When Poll has something to do (c100 running), else hal::kNever.
  hal::Micros Deadline() const;
  // When the action's next refresh is due while the own slot idles, else hal::kNever.
  hal::Micros RefreshDeadline() const;
  // The c103 check's read or the action's write, when due.
  bool NextJob(hal::Micros now, OwnJob& job);
  void OnCheckRead(std::uint8_t index, const Completion& completion);
  void OnActionWritten(std::uint8_t index, const Completion& completion, hal::Micros now);

 private:
  enum class State : std::uint8_t {
    kNone,        // traffic is fine
    kDelay,       // NetworkLost: c100 runs
    kChecking,    // c100 over, c103 = 1/2: reading cmod/fmod
    kActive,      // c101 in force (c103 allowed it)
    kNotApplied,  // c103 did not allow it: nothing done until restored
  };
  static constexpr std::uint16_t kContinue = 1;  // c101 = 1: operation continues

  hal::Micros LossDeadline() const;
  void Decide();
  std::uint16_t ActionFa06() const;

  const ConfigLoader& loader_;
  ScannerExchange& exchange_;
  CardWriteBack& write_back_;
  const ProxyConfig& config_;
  ProxyCounters& counters_;

  State state_ = State::kNone;
  hal::Micros lost_at_ = 0;  // NetworkLost's time: c100 counts from it
  std::uint16_t action_ = kContinue;  // c101 in force while kActive
  bool action_written_ = false;  // accepted since it started (or since the last reset)
  hal::Micros action_written_at_ = 0;
  std::uint8_t check_index_ = 0;
  std::uint16_t checked_cmod_ = 0;
  std::uint16_t checked_fmod_ = 0;
  // An explicit stop taken while the loss holds FA06 (HoldStopDuringLoss): the action writes it instead
  // of its own FA06; with c101 = 4 it is written after the err8 request (index 1 of kLossAction).
  std::uint16_t stop_hold_ = 0;
  bool stop_hold_valid_ = false;
  bool stop_hold_written_ = false;
  hal::Micros stop_hold_written_at_ = 0;
};

}  // namespace drive_link
