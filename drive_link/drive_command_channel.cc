// ScannerExchange: the drive command, FA06/FA07 for the CIP drive profile, and the feedback it needs
// (docs/drive-link.md, "Drive command channel (CIP drive profile)"). The drive command is command words 6
// and 7 of the exchange's table (scanner_exchange.cc), so it is written by the same code as the scanner
// words: changes at once, refreshes, RAM only, the fault-reset edge, no writes during a loss action.
#include "drive_link/drive_registers.h"
#include "drive_link/scanner_exchange.h"

namespace drive_link {
namespace {

constexpr std::uint8_t kDriveCommandWords = (1U << kDriveFa06Word) | (1U << kDriveFa07Word);

constexpr std::uint8_t Bit(std::size_t word) { return static_cast<std::uint8_t>(1U << word); }

}  // namespace

void ScannerExchange::SetDriveCommand(const DriveCommandWords& words) {
  released_fa06_valid_ = false;
  if (!drive_taken_) {
    // Take-over: FA06 and FA07 are written at once, whatever a scanner word wrote there before. A
    // fault-reset edge a displaced scanner word still had pending is dropped with it.
    drive_taken_ = true;
    commands_[kDriveFa06Word].written_valid = false;
    commands_[kDriveFa07Word].written_valid = false;
    for (std::size_t w = 0; w < kScannerWordCount; ++w) {
      if (DisplacedByDriveCommand(w)) fault_reset_edges_ = static_cast<std::uint8_t>(fault_reset_edges_ & ~Bit(w));
    }
  }
  // drive_command_ is {} before a take-over: bit 13 already set in the first words is an edge, as it is
  // for the scanner words' first words after start/reset.
  const bool rising = (drive_command_.fa06 & reg::command_bit::kFaultReset) == 0 &&
                      (words.fa06 & reg::command_bit::kFaultReset) != 0;
  if (rising) fault_reset_edges_ = static_cast<std::uint8_t>(fault_reset_edges_ | Bit(kDriveFa06Word));
  drive_command_ = words;
  armed_ = static_cast<std::uint8_t>(armed_ | kDriveCommandWords);
  if (suspended_) words_during_suspension_ = static_cast<std::uint8_t>(words_during_suspension_ | kDriveCommandWords);
}

bool ScannerExchange::ReleaseDriveCommand() {
  if (!drive_taken_) return false;
  // Nothing is written for the release itself: what the drive should do then (stop, keep running) is the
  // drive profile's decision, made with its last SetDriveCommand.
  drive_taken_ = false;
  // FA06 keeps the drive profile's last value in the inverter: a loss action reported after the release
  // (a connection closed, then c100 ran out) decelerates or presets from it (LossActionFa06).
  released_fa06_ = drive_command_.fa06;
  released_fa06_valid_ = true;
  drive_command_ = DriveCommandWords{};
  const auto keep = static_cast<std::uint8_t>(~kDriveCommandWords);
  armed_ = static_cast<std::uint8_t>(armed_ & keep);
  fault_reset_edges_ = static_cast<std::uint8_t>(fault_reset_edges_ & keep);
  words_during_suspension_ = static_cast<std::uint8_t>(words_during_suspension_ & keep);
  // Scanner words on FA06/FA07 take over again, written at once: the registers hold the drive profile's
  // values, not theirs.
  for (std::size_t w = 0; w < kScannerWordCount; ++w) {
    if (IsDriveCommandRegister(commands_[w].target)) commands_[w].written_valid = false;
  }
  return true;
}

bool ScannerExchange::DisplacedByDriveCommand(std::size_t w) const {
  return drive_taken_ && w < kScannerWordCount && IsDriveCommandRegister(commands_[w].target);
}

// FD00 and FE02 are read in each cycle only while wanted: the Modbus side's cycle does not pay for them.
// The plan changes at once (the monitor words' reads keep their values); `known` starts over.
bool ScannerExchange::SetFeedbackWanted(bool wanted) {
  if (wanted == feedback_wanted_) return false;
  feedback_wanted_ = wanted;
  feedback_fresh_ = 0;
  feedback_snapshot_ = {};
  if (loader_.loaded()) PlanMonitorReads(/*keep_values=*/true);  // otherwise planned when the load ends
  return true;
}

DriveFeedbackWords ScannerExchange::DriveFeedback() const {
  return feedback_wanted_ ? feedback_snapshot_ : DriveFeedbackWords{};
}

// At the end of each cycle: the three registers of this cycle become the feedback, once all three have
// been read since the feedback was wanted.
void ScannerExchange::TakeFeedbackSnapshot() {
  if (!feedback_wanted_ || feedback_fresh_ != (kFreshFd01 | kFreshFd00 | kFreshFe02)) return;
  feedback_snapshot_ = DriveFeedbackWords{fd01_, PlannedReadValue(reg::kFd00), PlannedReadValue(reg::kFe02), true};
}

// The newest value of a source in the read plan; 0 when it is not read.
std::uint16_t ScannerExchange::PlannedReadValue(std::uint16_t number) const {
  for (std::size_t r = 0; r < read_count_; ++r) {
    if (reads_[r].number == number) return reads_[r].value;
  }
  return 0;
}

}  // namespace drive_link
