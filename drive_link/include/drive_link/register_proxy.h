// The card's register proxy: the one owner of the drive link, composed of named parts, each one concern
// (docs/drive-link.md, "Register proxy"):
//
// - LinkScheduler (link_scheduler.h): owns the LinkClient and arbitrates its slots between the parts;
// - ConfigLoader (config_loader.h): config::kConfigNumbers, F875-F879 and FD01 read at start-up, after
//   f899 = 1 and after the link recovers from e-23, validated into the configuration in force;
// - ScannerExchange (scanner_exchange.h): the cyclic exchange, command words c001-c006 (and FA06/FA07 for
//   the CIP drive profile) out, monitor words c021-c026, FD01 and the drive feedback in;
// - AccessQueue (access_queue.h): on-demand reads and writes, the one place that checks a register
//   access for every front end;
// - LossSupervisor (loss_supervisor.h): c100 delay, c103 condition and c101 action over the link;
// - CardWriteBack (card_write_back.h): the values the card writes back (c502-c536, c555, c041-c066).
//
// RegisterProxy wires them and implements the front ends' facades (register_access.h) on them.
//
// Device-path code: no exceptions, RTTI, heap or threads; every pool has a fixed size. Time is injected:
// Start(now), Poll(now) and NextDeadline() have the meaning of firmware::Service (absolute microseconds on
// hal::Clock), so the firmware wraps the proxy in a Service. Listeners are called from Poll only.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "base/pool_stats.h"
#include "base/status.h"
#include "config/card_config.h"
#include "drive_link/access_queue.h"
#include "drive_link/card_write_back.h"
#include "drive_link/config_loader.h"
#include "drive_link/link_client.h"
#include "drive_link/link_scheduler.h"
#include "drive_link/loss_supervisor.h"
#include "drive_link/own_job.h"
#include "drive_link/proxy_config.h"
#include "drive_link/register_access.h"
#include "drive_link/scanner_exchange.h"
#include "hal/clock.h"
#include "hal/serial_port.h"

namespace drive_link {

// Told when a configuration has been read and validated (start-up, f899 = 1, link recovery), so the
// firmware can (re)start the front ends with it.
class ConfigListener {
 public:
  virtual ~ConfigListener() = default;
  virtual void OnConfigLoaded(const config::ParsedConfig& parsed) = 0;
};

class RegisterProxy final : public DriveRegisters,
                            public ScannerImage,
                            public DriveCommandChannel,
                            public LossSupervision,
                            private AccessRules,
                            private OwnTransactions {
 public:
  // `port` must outlive the proxy. The link's configuration is checked at Start().
  RegisterProxy(hal::SerialPort& port, const LinkConfig& link_config, const ProxyConfig& config);
  RegisterProxy(const RegisterProxy&) = delete;
  RegisterProxy& operator=(const RegisterProxy&) = delete;

  // Starts the link (its start-up silence) and the configuration load. kFailedPrecondition when started.
  base::Status Start(hal::Micros now);
  void Poll(hal::Micros now);
  hal::Micros NextDeadline() const;

  // Optional; called from Poll after each configuration load. May be null.
  void SetConfigListener(ConfigListener* listener) { config_listener_ = listener; }
  // The values the card shows in c502/c503, c517-c535 and c536 (ethernet_error: see "Loss actions").
  // Written back (P) when they differ from what was last written.
  void SetCardStatus(const config::CardStatus& status);

  // The configuration in force: factory defaults until the first load.
  const config::CardConfig& config() const { return loader_.config(); }
  const config::ParsedConfig& parsed_config() const { return loader_.parsed(); }
  bool config_loaded() const { return loader_.loaded(); }
  // F875-F879 as read at the last load (the selections in force since the inverter's last reset).
  const std::array<std::uint16_t, kBlockReadSelections>& block_read_selections() const {
    return loader_.block_selections();
  }
  // Status word FD01 from the newest cycle (0 until read) and whether it was read since the last load.
  std::uint16_t drive_status() const { return exchange_.drive_status(); }
  bool drive_status_known() const { return exchange_.drive_status_known(); }
  // The value c536 shows.
  std::uint16_t ethernet_error() const { return write_back_.ethernet_error(); }

  const ProxyCounters& counters() const { return counters_; }
  // The on-demand access pool (docs/robustness.md "Exhaustion"); refused: Read/Write answered
  // kResourceExhausted (counters().pool_full).
  base::PoolStats access_pool() const { return accesses_.pool(); }
  const LinkClient& link() const { return scheduler_.link(); }

  // --- DriveRegisters ---
  base::Result<AccessToken> Read(std::uint16_t number, AccessListener& listener) override;
  base::Result<AccessToken> Write(std::uint16_t number, std::uint16_t value, WriteMode mode,
                                  AccessListener& listener) override;
  AccessError CheckWrite(std::uint16_t number, std::uint16_t value) const override {
    return accesses_.CheckWrite(number, value);
  }
  void Cancel(AccessListener& listener) override { accesses_.Cancel(listener); }

  // --- ScannerImage ---
  void SetCommandWords(const ScannerWords& words) override { SetCommandWordsMasked(words, kAllScannerWords); }
  ScannerWords CommandWords() const override { return exchange_.CommandWords(); }
  ScannerWords MonitorWords() const override { return exchange_.MonitorWords(); }
  bool IsScannerTarget(std::uint16_t number) const override { return exchange_.IsScannerTarget(number); }

  // --- DriveCommandChannel ---
  void SetDriveCommand(const DriveCommandWords& words) override;
  void ReleaseDriveCommand() override;
  bool drive_command_taken() const override { return exchange_.drive_command_taken(); }
  bool CommandsHeldByLoss() const override { return loss_.CommandsHeldByLoss(); }
  void HoldStopDuringLoss(std::uint16_t fa06) override;
  void SetCommandWordsMasked(const ScannerWords& words, std::uint8_t mask) override;
  void SetFeedbackWanted(bool wanted) override;
  DriveFeedbackWords DriveFeedback() const override { return exchange_.DriveFeedback(); }

  // --- LossSupervision ---
  void NetworkLost(LossCause cause, hal::Micros now) override;
  void NetworkRestored(hal::Micros now) override;
  bool loss_action_active() const override { return loss_.action_active(); }

  // True for the numbers the card owns (written back by the card, refused to other writers).
  static bool IsOwnedNumber(std::uint16_t number) { return CardWriteBack::IsOwnedNumber(number); }

 private:
  // AccessRules.
  bool ConfigLoaded() const override { return loader_.loaded(); }
  bool DriveRunning() const override { return exchange_.drive_running(); }
  void OnWriteAccepted(std::uint16_t number, std::uint16_t value) override;
  void OnInverterReset(bool card_reset) override;

  // OwnTransactions.
  bool NextOwnJob(hal::Micros now, OwnJob& job) override;
  void OnOwnComplete(const OwnJob& job, const Completion& completion, hal::Micros now) override;
  void OnLinkStateChanged(LinkState previous, LinkState current) override;

  void BeginLoad(bool card_reset);
  void FinishLoad(hal::Micros now);
  void FailWaitingAccesses(AccessError error);

  ProxyConfig config_;
  ProxyCounters counters_{};
  ConfigLoader loader_;
  CardWriteBack write_back_;
  ScannerExchange exchange_;
  LossSupervisor loss_;
  AccessQueue accesses_;
  LinkScheduler scheduler_;
  ConfigListener* config_listener_ = nullptr;
  hal::Micros now_ = 0;  // of the current or last Poll
  // Something changed outside Poll (new words, an access, a loss report): NextDeadline says "at once".
  bool wake_ = false;
  bool notify_loaded_ = false;  // OnConfigLoaded due at the end of this Poll
};

}  // namespace drive_link
