// The register proxy's cyclic exchange: the command words out (the scanner words c001-c006 and, for the
// CIP drive profile, FA06/FA07 as two more words) as RAM writes, at once when changed and refreshed when
// unchanged; the monitor words c021-c026, FD01 and the drive feedback FD00/FE02 in, by block read where
// F875-F879 allow; between two cycles, one write-back of the card's values (docs/drive-link.md, "Cyclic
// exchange", "Drive command channel (CIP drive profile)"). Its transactions go out through the link
// scheduler; the loss supervision suspends the command writes while a c101 action owns FA06.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "drive_link/card_write_back.h"
#include "drive_link/config_loader.h"
#include "drive_link/own_job.h"
#include "drive_link/proxy_config.h"
#include "drive_link/register_access.h"
#include "hal/clock.h"

namespace drive_link {

// The command words the exchange writes: the 6 scanner words (index 0-5, targets from c001-c006), then
// the drive command (6 = FA06, 7 = FA07, fixed targets, in use while taken). One table, so changes,
// refreshes, the fault-reset edge and the loss rules are the same code for both; a uint8_t holds one bit
// per word.
inline constexpr std::size_t kCommandWordCount = kScannerWordCount + 2;
inline constexpr std::size_t kDriveFa06Word = kScannerWordCount;
inline constexpr std::size_t kDriveFa07Word = kScannerWordCount + 1;
// SetCommandWordsMasked's mask with every scanner word (what SetCommandWords uses).
inline constexpr std::uint8_t kAllScannerWords = (1U << kScannerWordCount) - 1;

class ScannerExchange {
 public:
  // `block_reads`: monitors may be read by block (ProxyConfig::use_block_reads and a binary link).
  ScannerExchange(const ConfigLoader& loader, CardWriteBack& write_back, const ProxyConfig& config,
                  ProxyCounters& counters, bool block_reads)
      : loader_(loader), write_back_(write_back), config_(config), counters_(counters), block_reads_(block_reads) {}

  // ---- The configuration ----
  // Start-up or f899: the held words are forgotten (nothing is written until the master sends again),
  // the drive command is given back, the targets are no longer claimed.
  void CardReset();
  // The load ended: targets and read plan from the configuration in force, FD01 from the load, the
  // first cycle due at `now`.
  void ApplyConfig(hal::Micros now);
  // A load or e-23 interrupts the cycle; the next one starts from its beginning.
  void AbandonCycle() { cycle_active_ = false; }
  // The inverter may have forgotten FA06/FA07 (a fault reset, a short silence): every word is written again.
  void MarkCommandsUnknown();

  // ---- The front ends (ScannerImage, DriveCommandChannel) ----
  void SetCommandWordsMasked(const ScannerWords& words, std::uint8_t mask);
  ScannerWords CommandWords() const { return held_; }
  ScannerWords MonitorWords() const;
  bool IsScannerTarget(std::uint16_t number) const;
  void SetDriveCommand(const DriveCommandWords& words);
  // False when it was not taken (nothing changed).
  bool ReleaseDriveCommand();
  bool drive_command_taken() const { return drive_taken_; }
  // False when `wanted` was already in force.
  bool SetFeedbackWanted(bool wanted);
  DriveFeedbackWords DriveFeedback() const;

  // ---- The loss supervision ----
  // A c101 action owns FA06: no command word is written until ResumeCommandWrites. Words sent meanwhile
  // are remembered, so that their masters need not send again.
  void SuspendCommandWrites();
  // The action is lifted: every word is written again once its master sends again (or at once if it did
  // while suspended); a fault-reset edge from before is stale.
  void ResumeCommandWrites();
  // The master's FA06 as held now (fault-reset bit as sent): the drive command's while taken, else the
  // first scanner word in use on FA06 that the master has sent, else the drive command's last FA06 if it
  // was released since; 0 when none.
  std::uint16_t HeldFa06() const;

  // ---- The link (through the scheduler) ----
  // A changed command word, ahead of the cycle.
  bool UrgentCommandWrite(hal::Micros now, OwnJob& job);
  // The next step of the cycle, or a write-back between two cycles.
  bool CycleJob(hal::Micros now, OwnJob& job);
  void OnCommandWritten(const OwnJob& job, const Completion& completion);
  void OnMonitorRead(const OwnJob& job, const Completion& completion);
  // The own slot idles until then between cycles.
  hal::Micros NextCycleAt() const { return cycle_active_ ? hal::kNever : next_cycle_at_; }

  // Status word FD01 from the newest cycle (0 until read) and whether it was read since the last load.
  std::uint16_t drive_status() const { return fd01_; }
  bool drive_status_known() const { return fd01_known_; }
  bool drive_running() const;

 private:
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

  void PlanMonitorReads(bool keep_values);
  bool CommandWordInUse(std::size_t w) const;
  bool CommandWordWritable(std::size_t w) const;
  bool DisplacedByDriveCommand(std::size_t w) const;
  std::uint16_t HeldWord(std::size_t w) const;
  std::uint16_t CommandValue(std::size_t w) const;
  void MakeCommandJob(std::size_t w, hal::Micros now, OwnJob& job);
  bool NextCycleStep(hal::Micros now, OwnJob& job);
  void StartCycle(hal::Micros now);
  void EndCycle(hal::Micros now);
  bool WriteBackJob(hal::Micros now, OwnJob& job);
  void StoreRead(std::size_t r, std::uint16_t value);
  void SetFd01(std::uint16_t fd01);
  void TakeFeedbackSnapshot();
  std::uint16_t PlannedReadValue(std::uint16_t number) const;

  const ConfigLoader& loader_;
  CardWriteBack& write_back_;
  const ProxyConfig& config_;
  ProxyCounters& counters_;
  const bool block_reads_;

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
  bool suspended_ = false;                    // a loss action owns FA06
  std::uint8_t words_during_suspension_ = 0;  // bit per word: sent again while suspended

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
  bool wrote_back_since_cycle_ = false;
};

}  // namespace drive_link
