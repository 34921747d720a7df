// ScannerExchange: the cyclic exchange (command words out: the scanner words and the drive command; monitor
// words, FD01 and the drive feedback in) (docs/drive-link.md, "Cyclic exchange" and "Drive command channel
// (CIP drive profile)"). The drive command's entry points are in drive_command_channel.cc.
#include <algorithm>

#include "drive_link/drive_registers.h"
#include "drive_link/scanner_exchange.h"

namespace drive_link {
namespace {

// F875-F879 choice -> the register it reads, where that register is a monitor source. 0 for none and for
// 3, 4, 6 (FE03, FE05, FE22): trip-hold values, which differ from the FD03/FD05/FD22 menus while tripped.
constexpr std::array<std::uint16_t, 11> kBlockReadSources = {
    0, reg::kFd01, reg::kFd00, 0, 0, reg::kFc91, 0, 0xFD06, 0xFD07, 0xFE35, 0xFE36,
};

constexpr std::uint8_t kNoRead = 0xFF;

std::uint8_t Bit(std::size_t word) { return static_cast<std::uint8_t>(1U << word); }

}  // namespace

// ---- Configuration applied ---------------------------------------------------------------------------

void ScannerExchange::CardReset() {
  held_ = ScannerWords{};
  drive_command_ = DriveCommandWords{};
  armed_ = 0;
  claimed_ = false;
  scanner_mask_ = kAllScannerWords;
  drive_taken_ = false;
  fault_reset_edges_ = 0;
  suspended_ = false;
}

void ScannerExchange::ApplyConfig(hal::Micros now) {
  for (std::size_t i = 0; i < kScannerWordCount; ++i) {
    commands_[i] = CommandWord{};
    commands_[i].target = config::CommandMenuTarget(loader_.config().command_menus[i]);
  }
  commands_[kDriveFa06Word] = CommandWord{};
  commands_[kDriveFa06Word].target = reg::kFa06;
  commands_[kDriveFa07Word] = CommandWord{};
  commands_[kDriveFa07Word].target = reg::kFa07;
  PlanMonitorReads(/*keep_values=*/false);
  fd01_known_ = false;
  feedback_fresh_ = 0;
  feedback_snapshot_ = {};
  released_fa06_valid_ = false;
  cycle_end_known_ = false;
  // Everything the card owns is written again: the inverter may have been reset (RAM-only values at 0).
  write_back_.Reload(now);
  if (const AccessResult& fd01 = loader_.drive_status_read(); fd01.ok()) SetFd01(fd01.value);
  next_cycle_at_ = now;
}

// `keep_values`: the plan changes between loads (the drive feedback wanted or not) and the newest values
// stay, so MonitorWords() does not drop to 0 until the next cycle. The sources of the monitor words keep
// their positions (the feedback's come after them), so a read on the link completes into the right entry.
void ScannerExchange::PlanMonitorReads(bool keep_values) {
  const decltype(reads_) previous = reads_;
  const std::size_t previous_count = keep_values ? read_count_ : 0;
  reads_ = {};
  read_count_ = 0;
  const auto plan = [this](std::uint16_t source) {
    std::size_t r = 0;
    while (r < read_count_ && reads_[r].number != source) ++r;
    if (r == read_count_) reads_[read_count_++].number = source;
    return static_cast<std::uint8_t>(r);
  };
  plan(reg::kFd01);  // always: c555, the c103 condition, "running" for error mapping
  for (std::size_t w = 0; w < kScannerWordCount; ++w) {
    const std::uint16_t source = config::MonitorMenuSource(loader_.config().monitor_menus[w]);
    word_read_[w] = source == 0 ? kNoRead : plan(source);
  }
  if (feedback_wanted_) {
    plan(reg::kFd00);  // shared with a monitor word of menu 2
    plan(reg::kFe02);
  }
  for (std::size_t r = 0; r < read_count_; ++r) {
    for (std::size_t p = 0; p < previous_count; ++p) {
      if (previous[p].number == reads_[r].number) reads_[r].value = previous[p].value;
    }
  }
  // Block read: the leading F875-F879 positions up to the last one that covers a source still needed.
  block_read_count_ = 0;
  block_target_ = {};
  if (!block_reads_) return;
  for (std::size_t p = 0; p < kBlockReadSelections; ++p) {
    const std::uint16_t selection = loader_.block_selections()[p];
    const std::uint16_t source = selection < kBlockReadSources.size() ? kBlockReadSources[selection] : 0;
    if (source == 0) continue;
    for (std::size_t r = 0; r < read_count_; ++r) {
      if (reads_[r].number != source || reads_[r].by_block) continue;
      reads_[r].by_block = true;
      block_target_[p] = static_cast<std::uint8_t>(r + 1);
      block_read_count_ = static_cast<std::uint8_t>(p + 1);
      break;
    }
  }
}

ScannerWords ScannerExchange::MonitorWords() const {
  ScannerWords words{};
  for (std::size_t w = 0; w < kScannerWordCount; ++w) {
    if (word_read_[w] != kNoRead && word_read_[w] < read_count_) words[w] = reads_[word_read_[w]].value;
  }
  return words;
}

// ---- Command words -----------------------------------------------------------------------------------


// A word outside `mask` keeps its held value (CommandWords(), c041-c046) and is not written; one that
// comes back into the mask is written at once (while out, others could write its target).
void ScannerExchange::SetCommandWordsMasked(const ScannerWords& words, std::uint8_t mask) {
  mask = static_cast<std::uint8_t>(mask & kAllScannerWords);
  for (std::size_t w = 0; w < kScannerWordCount; ++w) {
    if ((mask & Bit(w)) == 0) continue;
    if ((scanner_mask_ & Bit(w)) == 0) commands_[w].written_valid = false;
    const bool rising = (held_[w] & reg::command_bit::kFaultReset) == 0 &&
                        (words[w] & reg::command_bit::kFaultReset) != 0;
    // A word the drive command displaces gets no edge: it would reset the inverter when given back.
    if (commands_[w].target == reg::kFa06 && rising && !DisplacedByDriveCommand(w)) fault_reset_edges_ |= Bit(w);
    held_[w] = words[w];
  }
  scanner_mask_ = mask;
  armed_ = static_cast<std::uint8_t>(armed_ | kAllScannerWords);
  claimed_ = true;
  if (suspended_) words_during_suspension_ = static_cast<std::uint8_t>(words_during_suspension_ | kAllScannerWords);
}

bool ScannerExchange::IsScannerTarget(std::uint16_t number) const {
  if (number == 0) return false;
  // The drive profile owns FA06/FA07 while it has taken them.
  if (drive_taken_ && IsDriveCommandRegister(number)) return true;
  // §9.1: with Modbus IO scanning enabled the targets are reserved even before the scanner sends; else
  // from the first words a master sends (Modbus IO scanning or CIP assemblies 102/105).
  const config::CardConfig& card = loader_.config();
  const bool claimed = claimed_ || (card.protocol == config::Protocol::kModbusTcp && card.io_scanning);
  if (!claimed) return false;
  for (std::size_t w = 0; w < kScannerWordCount; ++w) {
    if (commands_[w].target == number && CommandWordInUse(w)) return true;
  }
  return false;
}

// A word in use: a scanner word whose menu is not 0, in the last mask and not displaced by the drive
// command; a drive command word while taken. Its target is reserved (IsScannerTarget).
bool ScannerExchange::CommandWordInUse(std::size_t w) const {
  if (commands_[w].target == 0) return false;
  if (w >= kScannerWordCount) return drive_taken_;
  return (scanner_mask_ & Bit(w)) != 0 && !DisplacedByDriveCommand(w);
}

// ... and written: its words were sent since start/reset (and since a loss action was lifted), and no
// loss action other than "continue" (c101 = 1) is in force.
bool ScannerExchange::CommandWordWritable(std::size_t w) const {
  return !suspended_ && (armed_ & Bit(w)) != 0 && CommandWordInUse(w);
}

std::uint16_t ScannerExchange::HeldWord(std::size_t w) const {
  if (w == kDriveFa06Word) return drive_command_.fa06;
  if (w == kDriveFa07Word) return drive_command_.fa07;
  return held_[w];
}

// The value word `w` puts on the wire: the master's word, except that FA06's fault-reset bit is sent once
// per rising edge of the master's bit (a refresh after the reset would be a new edge: a second reset).
std::uint16_t ScannerExchange::CommandValue(std::size_t w) const {
  std::uint16_t value = HeldWord(w);
  if (commands_[w].target == reg::kFa06) {
    value = static_cast<std::uint16_t>(value & ~reg::command_bit::kFaultReset);
    if ((fault_reset_edges_ & Bit(w)) != 0) value = static_cast<std::uint16_t>(value | reg::command_bit::kFaultReset);
  }
  return value;
}

void ScannerExchange::SuspendCommandWrites() {
  suspended_ = true;
  words_during_suspension_ = 0;
}

// The action overwrote FA06: every word is written again, but only once its master sends words again
// (unless it already did while the action was in force): the scanner words at the next
// SetCommandWords*, the drive command (still taken) at the next SetDriveCommand. A fault-reset edge from
// before the action is stale now.
void ScannerExchange::ResumeCommandWrites() {
  suspended_ = false;
  MarkCommandsUnknown();
  armed_ = static_cast<std::uint8_t>(armed_ & words_during_suspension_);
  fault_reset_edges_ = static_cast<std::uint8_t>(fault_reset_edges_ & words_during_suspension_);
}

// The first word in use on FA06 that the master has sent (one never sent wrote nothing to FA06).
std::uint16_t ScannerExchange::HeldFa06() const {
  if (drive_taken_) return drive_command_.fa06;
  for (std::size_t w = 0; w < kScannerWordCount; ++w) {
    if (commands_[w].target == reg::kFa06 && CommandWordInUse(w) && (armed_ & Bit(w)) != 0) return held_[w];
  }
  return released_fa06_valid_ ? released_fa06_ : 0;
}

bool ScannerExchange::drive_running() const { return fd01_known_ && (fd01_ & reg::status_bit::kRunning) != 0; }

// A changed word goes out in the next own slot, ahead of the rest of the cycle. Between two such writes
// of the same word at least one other own transaction goes (a cycle step or a write-back), so a master
// changing words faster than the link slows the monitor reads down but cannot stop them.
bool ScannerExchange::UrgentCommandWrite(hal::Micros now, OwnJob& job) {
  for (std::size_t w = 0; w < kCommandWordCount; ++w) {
    const CommandWord& word = commands_[w];
    if (!CommandWordWritable(w) || (urgent_since_cycle_step_ & Bit(w)) != 0) continue;
    if (word.written_valid && CommandValue(w) == word.written) continue;
    urgent_since_cycle_step_ = static_cast<std::uint8_t>(urgent_since_cycle_step_ | Bit(w));
    MakeCommandJob(w, now, job);
    return true;
  }
  return false;
}

// Every write of a command word is P (RAM only): cyclic data must never wear the EEPROM, also for the
// parameter targets (acc, dec, ul, vb, vlv, f601), whose EEPROM value returns at the next power-on.
void ScannerExchange::MakeCommandJob(std::size_t w, hal::Micros now, OwnJob& job) {
  const std::uint16_t value = CommandValue(w);
  job.kind = OwnJobKind::kCommandWrite;
  job.index = static_cast<std::uint8_t>(w);
  job.transaction = Transaction::WriteRam(commands_[w].target, value);
  fault_reset_edges_ = static_cast<std::uint8_t>(fault_reset_edges_ & ~Bit(w));
  commands_[w].written = value;
  commands_[w].written_valid = true;
  commands_[w].written_at = now;
}

void ScannerExchange::MarkCommandsUnknown() {
  for (CommandWord& word : commands_) word.written_valid = false;
}

void ScannerExchange::OnCommandWritten(const OwnJob& job, const Completion& completion) {
  ++counters_.command_writes;
  if (job.index >= kScannerWordCount) ++counters_.drive_command_writes;
  const Transaction& sent = job.transaction;
  const bool fault_reset = sent.comm_number == reg::kFa06 && (sent.data & reg::command_bit::kFaultReset) != 0;
  if (fault_reset && (completion.ok() || completion.outcome == Outcome::kNoReply)) {
    // The inverter reset and forgot FA06/FA07 (seed 003 §13.10): write every word again after its silence.
    MarkCommandsUnknown();
    return;
  }
  if (completion.ok()) return;
  ++counters_.command_errors;
  // An error reply (0001 out of range, 0000 not now) is not repeated until the word changes or its
  // refresh is due; a write that may not have arrived is repeated at once.
  if (completion.outcome != Outcome::kErrorReply && job.index < commands_.size()) {
    commands_[job.index].written_valid = false;
  }
}

// ---- The cycle -------------------------------------------------------------------------------------------

void ScannerExchange::StartCycle(hal::Micros now) {
  cycle_active_ = true;
  cycle_command_ = 0;
  cycle_read_ = 0;
  cycle_block_done_ = false;
  cycle_started_at_ = now;
  wrote_back_since_cycle_ = false;
}

void ScannerExchange::EndCycle(hal::Micros now) {
  cycle_active_ = false;
  ++counters_.cycles;
  TakeFeedbackSnapshot();
  if (cycle_end_known_) {
    const hal::Micros period = now - last_cycle_end_;
    counters_.cycle_period_last = period;
    counters_.cycle_period_min = counters_.cycle_period_min == 0 ? period : std::min(counters_.cycle_period_min, period);
    counters_.cycle_period_max = std::max(counters_.cycle_period_max, period);
  }
  last_cycle_end_ = now;
  cycle_end_known_ = true;
  // Base time: the next start is one period after this one's start, or now when the cycle overran it.
  next_cycle_at_ = config_.min_cycle_period == 0 ? now : std::max(now, cycle_started_at_ + config_.min_cycle_period);
}

// One transaction of the cycle: refreshes (and changes) of command words (scanner words, then the drive
// command), then the block read, then the R reads. Between two cycles one housekeeping write may go (more
// while waiting for min_cycle_period).
bool ScannerExchange::CycleJob(hal::Micros now, OwnJob& job) {
  if (!NextCycleStep(now, job)) return false;
  urgent_since_cycle_step_ = 0;
  return true;
}

bool ScannerExchange::NextCycleStep(hal::Micros now, OwnJob& job) {
  for (int pass = 0; pass < 2; ++pass) {
    if (cycle_active_) {
      while (cycle_command_ < kCommandWordCount) {
        const std::size_t w = cycle_command_++;
        const CommandWord& word = commands_[w];
        if (!CommandWordWritable(w)) continue;
        const bool due = !word.written_valid || CommandValue(w) != word.written ||
                         now - word.written_at >= config_.command_refresh_interval;
        if (!due) continue;
        MakeCommandJob(w, now, job);
        return true;
      }
      if (!cycle_block_done_ && block_read_count_ > 0) {
        cycle_block_done_ = true;
        job.kind = OwnJobKind::kBlockRead;
        job.index = 0;
        job.transaction = Transaction::Block(std::span<const std::uint16_t>(), block_read_count_);
        return true;
      }
      while (cycle_read_ < read_count_) {
        const std::size_t r = cycle_read_++;
        if (reads_[r].by_block) continue;
        job.kind = OwnJobKind::kMonitorRead;
        job.index = static_cast<std::uint8_t>(r);
        job.transaction = Transaction::Read(reads_[r].number);
        return true;
      }
      EndCycle(now);  // called only with the own slot free: the cycle's last transaction has completed
    }
    if (WriteBackJob(now, job)) return true;
    if (now < next_cycle_at_) return false;
    StartCycle(now);
  }
  return false;
}

void ScannerExchange::OnMonitorRead(const OwnJob& job, const Completion& completion) {
  if (loader_.loading()) return;  // the plan is being replaced
  if (job.kind == OwnJobKind::kBlockRead) {
    ++counters_.block_reads;
  } else {
    ++counters_.monitor_reads;
  }
  if (!completion.ok()) {
    ++counters_.monitor_errors;
    return;
  }
  if (job.kind == OwnJobKind::kMonitorRead) {
    // The plan may have changed while the read was on the link (SetFeedbackWanted): only into its entry.
    if (job.index < read_count_ && reads_[job.index].number == job.transaction.comm_number) {
      StoreRead(job.index, completion.data);
    }
    return;
  }
  // Block positions stand for registers (their F875-F879 selections), whatever the plan is now.
  const std::size_t groups = std::min<std::size_t>(completion.block_read_count, block_read_count_);
  for (std::size_t p = 0; p < groups; ++p) {
    if (block_target_[p] != 0) StoreRead(block_target_[p] - 1U, completion.block_data[p]);
  }
}

void ScannerExchange::StoreRead(std::size_t r, std::uint16_t value) {
  reads_[r].value = value;
  if (r == 0) SetFd01(value);
  if (!feedback_wanted_) return;
  // DriveFeedback().known: each of the three read since the feedback was wanted (and since the load).
  if (reads_[r].number == reg::kFd01) feedback_fresh_ |= kFreshFd01;
  if (reads_[r].number == reg::kFd00) feedback_fresh_ |= kFreshFd00;
  if (reads_[r].number == reg::kFe02) feedback_fresh_ |= kFreshFe02;
}

void ScannerExchange::SetFd01(std::uint16_t fd01) {
  fd01_ = fd01;
  fd01_known_ = true;
  write_back_.SetDriveStatus(fd01);  // c555, written when it changes
}

// Between two cycles one write-back may go (more while waiting for min_cycle_period).
bool ScannerExchange::WriteBackJob(hal::Micros now, OwnJob& job) {
  if (wrote_back_since_cycle_ && now >= next_cycle_at_) return false;
  if (!write_back_.NextWrite(now, held_, MonitorWords(), job)) return false;
  wrote_back_since_cycle_ = true;
  return true;
}

}  // namespace drive_link
