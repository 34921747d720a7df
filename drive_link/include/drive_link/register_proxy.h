// The card's register proxy: the one owner of the drive link. It implements the front ends' facades
// (register_access.h) on a LinkClient it owns:
//
// - DriveRegisters: on-demand reads and writes of any communication number, queued in a pool of
//   kMaxPendingAccesses, refused locally where the card knows better than the inverter;
// - ScannerImage: the cyclic exchange (command words c001-c006 out as RAM writes, monitor words
//   c021-c026 and FD01 in, by block read where F875-F879 allow);
// - DriveCommandChannel: FA06/FA07 taken over for the CIP drive profile, written by the same exchange as
//   two more command words, and FD00/FE02 read in each cycle when wanted;
// - LossSupervision: c100 delay, c103 condition and c101 action carried out over the link;
// - the configuration: kConfigNumbers read at start-up, after f899 = 1 and after the link recovers from
//   e-23, and the values the card owns written back (c502-c536, c555, c041-c066).
//
// docs/drive-link.md ("Register proxy", "Cyclic exchange", "Drive command channel (CIP drive profile)",
// "Configuration at start-up and reset", "Loss actions") gives every rule and its reason.
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
#include "drive_link/link_client.h"
#include "drive_link/register_access.h"
#include "hal/clock.h"
#include "hal/serial_port.h"

namespace drive_link {

// On-demand accesses accepted and not yet delivered: one outstanding access for each of 8 Modbus TCP
// clients, or fewer Modbus clients plus CIP explicit messages (Parameter objects, assemblies 101/105). A
// cancelled access whose request is already on the link keeps its slot until the link completes it.
inline constexpr std::size_t kMaxPendingAccesses = 8;

// F875-F879: the block read selections (seed 003 §4).
inline constexpr std::size_t kBlockReadSelections = 5;

// The configuration load reads kConfigNumbers, then F875-F879, then FD01 (register_proxy.cc).
inline constexpr std::size_t kConfigLoadReads = config::kConfigNumberCount + kBlockReadSelections + 1;

// The command words the exchange writes: the 6 scanner words (index 0-5, targets from c001-c006), then
// the drive command (6 = FA06, 7 = FA07, fixed targets, in use while taken). One table, so changes,
// refreshes, the fault-reset edge and the loss rules are the same code for both; a uint8_t holds one bit
// per word.
inline constexpr std::size_t kCommandWordCount = kScannerWordCount + 2;
inline constexpr std::size_t kDriveFa06Word = kScannerWordCount;
inline constexpr std::size_t kDriveFa07Word = kScannerWordCount + 1;
// SetCommandWordsMasked's mask with every scanner word (what SetCommandWords uses).
inline constexpr std::uint8_t kAllScannerWords = (1U << kScannerWordCount) - 1;

// Values the card owns and writes back: c502/c503, c517-c522, c524-c535, c536, c555, c041-c046, c061-c066.
inline constexpr std::size_t kOwnedValueCount = 2 + 6 + 12 + 1 + 1 + 6 + 6;

// Every value is documented with its reason in docs/drive-link.md.
struct ProxyConfig {
  // A new exchange cycle starts at most this often (on a fixed base time); 0 = back to back, as fast as
  // the link allows.
  hal::Micros min_cycle_period = 0;
  // A command word in use is written again this long after its last write even when unchanged: the
  // inverter forgets FA06/FA07 when a panel or terminal reset clears a trip, and the panel may change a
  // parameter target (acc, ul...). A changed word is written at once.
  hal::Micros command_refresh_interval = 500 * hal::kMicrosPerMilli;
  // The display values c041-c046 / c061-c066 are sampled this often and written when they changed.
  hal::Micros display_interval = hal::kMicrosPerSecond;
  // Read monitors by block (X) where the F875-F879 selections in force cover them (binary mode only).
  bool use_block_reads = true;
};

// Told when a configuration has been read and validated (start-up, f899 = 1, link recovery), so the
// firmware can (re)start the front ends with it.
class ConfigListener {
 public:
  virtual ~ConfigListener() = default;
  virtual void OnConfigLoaded(const config::ParsedConfig& parsed) = 0;
};

inline constexpr std::size_t kAccessErrorCount = static_cast<std::size_t>(AccessError::kNetworkLost) + 1;

struct ProxyCounters {
  std::uint32_t config_loads = 0;      // configurations read and parsed
  std::uint32_t cycles = 0;            // exchange cycles completed (every monitor word read once)
  hal::Micros cycle_period_last = 0;   // between the ends of the last two cycles
  hal::Micros cycle_period_min = 0;    // 0 until two cycles have ended
  hal::Micros cycle_period_max = 0;
  std::uint32_t command_writes = 0;    // P writes of command words (changes and refreshes): scanner
                                       // words and the drive command
  std::uint32_t command_errors = 0;    // ... refused by the inverter or unanswered
  std::uint32_t drive_command_writes = 0;  // the part of command_writes that wrote the drive command
  std::uint32_t monitor_reads = 0;     // R reads of monitor sources, FD01 and the drive feedback
  std::uint32_t block_reads = 0;       // X requests reading monitor sources
  std::uint32_t monitor_errors = 0;    // monitor reads (R or X) that failed
  std::uint32_t owned_writes = 0;      // write-backs of c502-c536, c555, c041-c066
  std::uint32_t owned_errors = 0;
  std::uint32_t loss_actions = 0;      // c101 actions started (c103 allowing)
  std::uint32_t loss_action_writes = 0;  // writes carrying them out (FA06 or FA30)
  std::uint32_t loss_action_errors = 0;  // ... refused by the inverter or unanswered
  std::uint32_t accesses = 0;          // on-demand accesses accepted
  std::uint32_t accesses_ok = 0;       // ... completed without error
  std::uint32_t pool_full = 0;         // Read/Write refused with kResourceExhausted
  // On-demand accesses that ended in each AccessError (index = the enum value; [0] is unused).
  std::array<std::uint32_t, kAccessErrorCount> access_errors{};
};

class RegisterProxy final : public DriveRegisters,
                            public ScannerImage,
                            public DriveCommandChannel,
                            public LossSupervision,
                            private LinkObserver {
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
  const config::CardConfig& config() const { return parsed_.config; }
  const config::ParsedConfig& parsed_config() const { return parsed_; }
  bool config_loaded() const { return loaded_; }
  // F875-F879 as read at the last load (the selections in force since the inverter's last reset).
  const std::array<std::uint16_t, kBlockReadSelections>& block_read_selections() const { return block_selections_; }
  // Status word FD01 from the newest cycle (0 until read) and whether it was read since the last load.
  std::uint16_t drive_status() const { return fd01_; }
  bool drive_status_known() const { return fd01_known_; }
  // The value c536 shows.
  std::uint16_t ethernet_error() const { return c536_; }

  const ProxyCounters& counters() const { return counters_; }
  // The on-demand access pool (docs/robustness.md "Exhaustion"); refused: Read/Write answered
  // kResourceExhausted (counters().pool_full).
  base::PoolStats access_pool() const { return access_marks_.Stats(AccessesInUse(), kMaxPendingAccesses); }
  const LinkClient& link() const { return link_; }

  // --- DriveRegisters ---
  base::Result<AccessToken> Read(std::uint16_t number, AccessListener& listener) override;
  base::Result<AccessToken> Write(std::uint16_t number, std::uint16_t value, WriteMode mode,
                                  AccessListener& listener) override;
  void Cancel(AccessListener& listener) override;

  // --- ScannerImage ---
  void SetCommandWords(const ScannerWords& words) override;
  ScannerWords CommandWords() const override { return held_; }
  ScannerWords MonitorWords() const override;
  bool IsScannerTarget(std::uint16_t number) const override;

  // --- DriveCommandChannel (drive_command_channel.cc; SetCommandWordsMasked in scanner_exchange.cc) ---
  void SetDriveCommand(const DriveCommandWords& words) override;
  void ReleaseDriveCommand() override;
  bool drive_command_taken() const override { return drive_taken_; }
  bool CommandsHeldByLoss() const override;
  void HoldStopDuringLoss(std::uint16_t fa06) override;
  void SetCommandWordsMasked(const ScannerWords& words, std::uint8_t mask) override;
  void SetFeedbackWanted(bool wanted) override;
  DriveFeedbackWords DriveFeedback() const override;

  // --- LossSupervision ---
  void NetworkLost(LossCause cause, hal::Micros now) override;
  void NetworkRestored(hal::Micros now) override;
  bool loss_action_active() const override;

  // True for the numbers the card owns (written back by the card, refused to other writers).
  static bool IsOwnedNumber(std::uint16_t number);

 private:
  // ---- The proxy's own transactions (one on the link at a time) ----
  enum class JobKind : std::uint8_t {
    kNone,
    kConfigRead,    // index: position in config::kConfigNumbers, then F875-F879
    kLossCheck,     // index: 0 cmod, 1 fmod (c103 = 1/2)
    kLossAction,    // the c101 write
    kCommandWrite,  // index: command word (0-5 scanner words, 6/7 the drive command)
    kBlockRead,
    kMonitorRead,   // index: position in reads_
    kOwnedWrite,    // index: position in owned_
  };
  struct Job {
    JobKind kind = JobKind::kNone;
    std::uint8_t index = 0;
    Transaction transaction{};
  };

  // ---- On-demand accesses ----
  struct Access {
    enum class State : std::uint8_t { kFree, kWaiting, kOnLink, kDone };
    State state = State::kFree;
    AccessToken token = kNoAccess;
    AccessListener* listener = nullptr;  // null once cancelled
    std::uint32_t order = 0;             // acceptance order: FIFO on the link and in delivery
    Transaction transaction{};
    RequestId request = kNoRequestId;
    AccessResult result{};
  };

  // ---- Cyclic exchange ----
  struct CommandWord {
    std::uint16_t target = 0;  // 0: menu 0, not exchanged
    std::uint16_t written = 0;  // the last value sent
    bool written_valid = false;  // false: unknown in the inverter, write at once
    hal::Micros written_at = 0;
  };
  struct MonitorRead {
    std::uint16_t number = 0;
    std::uint16_t value = 0;
    bool by_block = false;  // covered by the block read
  };
  struct OwnedValue {
    std::uint16_t number = 0;
    std::uint16_t wanted = 0;
    std::uint16_t written = 0;
    bool written_valid = false;
    bool wanted_valid = false;  // there is a value to show (c555: FD01 was read; c041-c066: sampled)
  };

  enum class LossState : std::uint8_t {
    kNone,        // traffic is fine
    kDelay,       // NetworkLost: c100 runs
    kChecking,    // c100 over, c103 = 1/2: reading cmod/fmod
    kActive,      // c101 in force (c103 allowed it)
    kNotApplied,  // c103 did not allow it: nothing done until restored
  };

  // LinkObserver.
  void OnComplete(RequestId id, const Completion& completion) override;
  void OnLinkStateChanged(LinkState previous, LinkState current) override;

  // register_proxy.cc: scheduling and the configuration load.
  void Schedule(hal::Micros now);
  bool NextJob(hal::Micros now, Job& job);
  void OnOwnComplete(const Job& job, const Completion& completion);
  void BeginLoad(bool card_reset);
  bool NextConfigRead(Job& job);
  void OnConfigRead(std::uint8_t index, const Completion& completion);
  void FinishLoad();

  // scanner_exchange.cc: command words, monitors, owned values.
  void ApplyConfig();
  void PlanMonitorReads(bool keep_values);
  std::uint16_t HeldWord(std::size_t word) const;
  std::uint16_t CommandValue(std::size_t word) const;
  bool CommandWritesAllowed() const;
  bool CommandWordInUse(std::size_t word) const;
  bool CommandWordWritable(std::size_t word) const;
  bool UrgentCommandWrite(Job& job);
  void MakeCommandJob(std::size_t word, Job& job);
  bool CycleJob(hal::Micros now, Job& job);
  bool NextCycleStep(hal::Micros now, Job& job);
  bool HousekeepingJob(hal::Micros now, Job& job);
  void StartCycle(hal::Micros now);
  void EndCycle(hal::Micros now);
  void TakeFeedbackSnapshot();
  void MarkCommandsUnknown();
  void OnCommandWritten(const Job& job, const Completion& completion);
  void OnMonitorRead(const Job& job, const Completion& completion);
  void StoreRead(std::size_t read, std::uint16_t value);
  void SetFd01(std::uint16_t fd01);
  void SetOwned(std::size_t index, std::uint16_t value);
  void UpdateStatusValues();
  void SampleDisplay();
  void OnOwnedWritten(std::uint8_t index, const Completion& completion);

  // drive_command_channel.cc.
  bool DisplacedByDriveCommand(std::size_t word) const;
  std::uint16_t PlannedReadValue(std::uint16_t number) const;

  // proxy_access.cc: on-demand accesses.
  base::Result<AccessToken> Accept(const Transaction& transaction, AccessListener& listener,
                                   AccessError local_refusal);
  void FinishAccess(Access& access, AccessError error, std::uint16_t value);
  std::size_t AccessesInUse() const;
  void SubmitAccess();
  void OnAccessComplete(Access& access, const Completion& completion);
  AccessError MapError(const Access& access, const Completion& completion) const;
  void FailWaitingAccesses(AccessError error);
  void DeliverAccesses();

  // loss_actions.cc.
  hal::Micros LossDeadline() const;
  void PollLoss(hal::Micros now);
  bool LossJob(hal::Micros now, Job& job);
  void DecideLossAction();
  std::uint16_t LossActionFa06() const;
  void OnLossCheckRead(std::uint8_t index, const Completion& completion);
  void OnLossActionWritten(std::uint8_t index, const Completion& completion, hal::Micros now);

  LinkClient link_;
  ProxyConfig config_;
  ConfigListener* config_listener_ = nullptr;
  bool started_ = false;
  hal::Micros now_ = 0;  // of the current or last Poll
  // Something changed outside Poll (new words, an access, a loss report): NextDeadline says "at once".
  bool wake_ = false;

  // The own transaction on the link.
  Job own_job_{};
  RequestId own_request_ = kNoRequestId;

  // Configuration.
  bool loaded_ = false;
  bool loading_ = false;
  bool notify_loaded_ = false;       // OnConfigLoaded due at the end of this Poll
  std::uint8_t load_index_ = 0;
  std::array<AccessResult, kConfigLoadReads> load_reads_{};
  config::ParsedConfig parsed_{};
  std::array<std::uint16_t, kBlockReadSelections> block_selections_{};

  // Command words (bit i of the masks = commands_[i]).
  ScannerWords held_{};
  DriveCommandWords drive_command_{};  // the drive profile's FA06/FA07 while taken ({} otherwise)
  std::array<CommandWord, kCommandWordCount> commands_{};
  // Bit per word: its words were sent since start/reset (scanner words: SetCommandWords*, the drive
  // command: SetDriveCommand), so it may be written; cleared again when a loss action is lifted.
  std::uint8_t armed_ = 0;
  bool claimed_ = false;  // the master sent scanner words since start/reset: their targets are reserved
  std::uint8_t scanner_mask_ = kAllScannerWords;  // the last SetCommandWordsMasked mask: the scanner words in use
  bool drive_taken_ = false;          // SetDriveCommand since start/reset/ReleaseDriveCommand
  std::uint8_t fault_reset_edges_ = 0;  // bit per word: the master raised FA06 bit 13, send it once
  std::uint8_t urgent_since_cycle_step_ = 0;  // bit per word: written ahead of the cycle since its last step

  // Monitors: FD01 first, then each distinct source of a monitor word in use, then FD00 and FE02 when
  // the drive feedback is wanted and no monitor word reads them already.
  std::array<MonitorRead, kScannerWordCount + 3> reads_{};
  std::size_t read_count_ = 0;
  std::array<std::uint8_t, kScannerWordCount> word_read_{};  // monitor word -> reads_ index
  std::uint8_t block_read_count_ = 0;                        // nR of the block read; 0 = none
  std::array<std::uint8_t, kBlockReadSelections> block_target_{};  // block position -> reads_ index + 1
  std::uint16_t fd01_ = 0;
  bool fd01_known_ = false;
  bool feedback_wanted_ = false;
  // Bits of the feedback registers read since the feedback was wanted and since the last load.
  static constexpr std::uint8_t kFreshFd01 = 1U << 0;
  static constexpr std::uint8_t kFreshFd00 = 1U << 1;
  static constexpr std::uint8_t kFreshFe02 = 1U << 2;
  std::uint8_t feedback_fresh_ = 0;
  // FD01, FD00 and FE02 as the end of the last cycle left them: one consistent set (a drive that just
  // started must not look "at reference" because FD00 and FE02 are still the stopped cycle's zeros).
  DriveFeedbackWords feedback_snapshot_{};
  // The drive command's FA06 when it was released, for a loss action that follows (until taken again).
  std::uint16_t released_fa06_ = 0;
  bool released_fa06_valid_ = false;

  // The cycle.
  bool cycle_active_ = false;
  bool cycle_block_done_ = false;
  std::uint8_t cycle_command_ = 0;  // next word to consider for a refresh
  std::uint8_t cycle_read_ = 0;     // next reads_ index
  hal::Micros cycle_started_at_ = 0;
  hal::Micros next_cycle_at_ = 0;
  hal::Micros last_cycle_end_ = 0;
  bool cycle_end_known_ = false;  // last_cycle_end_ is the end of the previous cycle (no break since)
  bool housekept_since_cycle_ = false;

  // Owned values.
  std::array<OwnedValue, kOwnedValueCount> owned_{};
  config::CardStatus status_{};
  std::uint16_t c536_ = 0;
  hal::Micros next_display_at_ = 0;

  // Loss supervision.
  LossState loss_ = LossState::kNone;
  hal::Micros lost_at_ = 0;  // NetworkLost's time: c100 counts from it
  std::uint16_t loss_action_ = 1;  // c101 in force while kActive
  bool loss_action_written_ = false;  // accepted since it started (or since the last reset)
  hal::Micros loss_action_written_at_ = 0;
  std::uint8_t loss_check_index_ = 0;
  std::uint16_t checked_cmod_ = 0;
  std::uint16_t checked_fmod_ = 0;
  std::uint8_t words_during_action_ = 0;  // bit per word: sent again while the action was in force
  // An explicit stop taken while the loss holds FA06 (HoldStopDuringLoss): the action writes it instead
  // of its own FA06; with c101 = 4 it is written after the err8 request (index 1 of kLossAction).
  std::uint16_t stop_hold_ = 0;
  bool stop_hold_valid_ = false;
  bool stop_hold_written_ = false;
  hal::Micros stop_hold_written_at_ = 0;

  // On-demand accesses.
  std::array<Access, kMaxPendingAccesses> accesses_{};
  base::PoolWatermark access_marks_;
  AccessToken next_token_ = 1;
  std::uint32_t next_order_ = 0;
  bool access_on_link_ = false;
  bool reset_on_link_ = false;  // that access resets the inverter (f899 = 1, a fault reset)

  ProxyCounters counters_{};
};

}  // namespace drive_link
