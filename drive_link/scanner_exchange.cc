// RegisterProxy: the cyclic exchange (command words out: the scanner words and the drive command; monitor
// words, FD01 and the drive feedback in) and the values the card writes back (docs/drive-link.md, "Cyclic
// exchange", "Drive command channel (CIP drive profile)" and "Configuration at start-up and reset"). The
// DriveCommandChannel entry points are in drive_command_channel.cc.
#include <algorithm>

#include "drive_link/drive_registers.h"
#include "drive_link/register_proxy.h"

namespace drive_link {
namespace {

// The values the card owns, in the order they are written back after a load.
constexpr std::array<std::uint16_t, kOwnedValueCount> kOwnedNumbers = {
    0xC502, 0xC503,                                  // actual rate, L and R port
    0xC517, 0xC518, 0xC519, 0xC520, 0xC521, 0xC522,  // MAC (decimal titles: c519 is followed by c520)
    0xC524, 0xC525, 0xC526, 0xC527,                  // actual IP
    0xC528, 0xC529, 0xC530, 0xC531,                  // actual mask
    0xC532, 0xC533, 0xC534, 0xC535,                  // actual gateway
    0xC536,                                          // Ethernet error
    0xC555,                                          // drive status
    0xC041, 0xC042, 0xC043, 0xC044, 0xC045, 0xC046,  // command scanner values
    0xC061, 0xC062, 0xC063, 0xC064, 0xC065, 0xC066,  // monitor scanner values
};
constexpr std::size_t kRatesAt = 0;
constexpr std::size_t kMacAt = 2;
constexpr std::size_t kIpAt = 8;
constexpr std::size_t kNetmaskAt = 12;
constexpr std::size_t kGatewayAt = 16;
constexpr std::size_t kC536At = 20;
constexpr std::size_t kC555At = 21;
constexpr std::size_t kCommandDisplayAt = 22;
constexpr std::size_t kMonitorDisplayAt = 28;

// F875-F879 choice -> the register it reads, where that register is a monitor source. 0 for none and for
// 3, 4, 6 (FE03, FE05, FE22): trip-hold values, which differ from the FD03/FD05/FD22 menus while tripped.
constexpr std::array<std::uint16_t, 11> kBlockReadSources = {
    0, reg::kFd01, reg::kFd00, 0, 0, reg::kFc91, 0, 0xFD06, 0xFD07, 0xFE35, 0xFE36,
};

constexpr std::uint8_t kNoRead = 0xFF;

std::uint8_t Bit(std::size_t word) { return static_cast<std::uint8_t>(1U << word); }

}  // namespace

bool RegisterProxy::IsOwnedNumber(std::uint16_t number) {
  return std::find(kOwnedNumbers.begin(), kOwnedNumbers.end(), number) != kOwnedNumbers.end();
}

// ---- Configuration applied ---------------------------------------------------------------------------

void RegisterProxy::ApplyConfig() {
  for (std::size_t i = 0; i < kScannerWordCount; ++i) {
    commands_[i] = CommandWord{};
    commands_[i].target = CommandMenuTarget(config().command_menus[i]);
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
  for (std::size_t i = 0; i < owned_.size(); ++i) {
    owned_[i].number = kOwnedNumbers[i];
    owned_[i].written_valid = false;
    owned_[i].wanted_valid = false;
  }
  UpdateStatusValues();
}

// `keep_values`: the plan changes between loads (the drive feedback wanted or not) and the newest values
// stay, so MonitorWords() does not drop to 0 until the next cycle. The sources of the monitor words keep
// their positions (the feedback's come after them), so a read on the link completes into the right entry.
void RegisterProxy::PlanMonitorReads(bool keep_values) {
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
    const std::uint16_t source = MonitorMenuSource(config().monitor_menus[w]);
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
  if (!config_.use_block_reads || link_.config().mode != wire::Mode::kBinary) return;
  for (std::size_t p = 0; p < kBlockReadSelections; ++p) {
    const std::uint16_t selection = block_selections_[p];
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

ScannerWords RegisterProxy::MonitorWords() const {
  ScannerWords words{};
  for (std::size_t w = 0; w < kScannerWordCount; ++w) {
    if (word_read_[w] != kNoRead && word_read_[w] < read_count_) words[w] = reads_[word_read_[w]].value;
  }
  return words;
}

// ---- Command words -----------------------------------------------------------------------------------

void RegisterProxy::SetCommandWords(const ScannerWords& words) { SetCommandWordsMasked(words, kAllScannerWords); }

// A word outside `mask` keeps its held value (CommandWords(), c041-c046) and is not written; one that
// comes back into the mask is written at once (while out, others could write its target).
void RegisterProxy::SetCommandWordsMasked(const ScannerWords& words, std::uint8_t mask) {
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
  if (loss_ == LossState::kActive) {
    words_during_action_ = static_cast<std::uint8_t>(words_during_action_ | kAllScannerWords);
  }
  wake_ = true;
}

bool RegisterProxy::IsScannerTarget(std::uint16_t number) const {
  if (number == 0) return false;
  // The drive profile owns FA06/FA07 while it has taken them.
  if (drive_taken_ && (number == reg::kFa06 || number == reg::kFa07)) return true;
  // §9.1: with Modbus IO scanning enabled the targets are reserved even before the scanner sends; else
  // from the first words a master sends (Modbus IO scanning or CIP assemblies 102/105).
  const bool claimed = claimed_ || (config().protocol == Protocol::kModbusTcp && config().io_scanning);
  if (!claimed) return false;
  for (std::size_t w = 0; w < kScannerWordCount; ++w) {
    if (commands_[w].target == number && CommandWordInUse(w)) return true;
  }
  return false;
}

// A word in use: a scanner word whose menu is not 0, in the last mask and not displaced by the drive
// command; a drive command word while taken. Its target is reserved (IsScannerTarget).
bool RegisterProxy::CommandWordInUse(std::size_t w) const {
  if (commands_[w].target == 0) return false;
  if (w >= kScannerWordCount) return drive_taken_;
  return (scanner_mask_ & Bit(w)) != 0 && !DisplacedByDriveCommand(w);
}

// ... and written: its words were sent since start/reset (and since a loss action was lifted), and no
// loss action other than "continue" (c101 = 1) is in force.
bool RegisterProxy::CommandWordWritable(std::size_t w) const {
  return CommandWritesAllowed() && (armed_ & Bit(w)) != 0 && CommandWordInUse(w);
}

std::uint16_t RegisterProxy::HeldWord(std::size_t w) const {
  if (w == kDriveFa06Word) return drive_command_.fa06;
  if (w == kDriveFa07Word) return drive_command_.fa07;
  return held_[w];
}

// The value word `w` puts on the wire: the master's word, except that FA06's fault-reset bit is sent once
// per rising edge of the master's bit (a refresh after the reset would be a new edge: a second reset).
std::uint16_t RegisterProxy::CommandValue(std::size_t w) const {
  std::uint16_t value = HeldWord(w);
  if (commands_[w].target == reg::kFa06) {
    value = static_cast<std::uint16_t>(value & ~reg::command_bit::kFaultReset);
    if ((fault_reset_edges_ & Bit(w)) != 0) value = static_cast<std::uint16_t>(value | reg::command_bit::kFaultReset);
  }
  return value;
}

// Not while a loss action other than "continue" (c101 = 1) is in force: it owns FA06 then.
bool RegisterProxy::CommandWritesAllowed() const { return !loss_action_active(); }

// A changed word goes out in the next own slot, ahead of the rest of the cycle. Between two such writes
// of the same word at least one other own transaction goes (a cycle step or a write-back), so a master
// changing words faster than the link slows the monitor reads down but cannot stop them.
bool RegisterProxy::UrgentCommandWrite(Job& job) {
  for (std::size_t w = 0; w < kCommandWordCount; ++w) {
    const CommandWord& word = commands_[w];
    if (!CommandWordWritable(w) || (urgent_since_cycle_step_ & Bit(w)) != 0) continue;
    if (word.written_valid && CommandValue(w) == word.written) continue;
    urgent_since_cycle_step_ = static_cast<std::uint8_t>(urgent_since_cycle_step_ | Bit(w));
    MakeCommandJob(w, job);
    return true;
  }
  return false;
}

// Every write of a command word is P (RAM only): cyclic data must never wear the EEPROM, also for the
// parameter targets (acc, dec, ul, vb, vlv, f601), whose EEPROM value returns at the next power-on.
void RegisterProxy::MakeCommandJob(std::size_t w, Job& job) {
  const std::uint16_t value = CommandValue(w);
  job.kind = JobKind::kCommandWrite;
  job.index = static_cast<std::uint8_t>(w);
  job.transaction = Transaction::WriteRam(commands_[w].target, value);
  fault_reset_edges_ = static_cast<std::uint8_t>(fault_reset_edges_ & ~Bit(w));
  commands_[w].written = value;
  commands_[w].written_valid = true;
  commands_[w].written_at = now_;
}

void RegisterProxy::MarkCommandsUnknown() {
  for (CommandWord& word : commands_) word.written_valid = false;
}

void RegisterProxy::OnCommandWritten(const Job& job, const Completion& completion) {
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

void RegisterProxy::StartCycle(hal::Micros now) {
  cycle_active_ = true;
  cycle_command_ = 0;
  cycle_read_ = 0;
  cycle_block_done_ = false;
  cycle_started_at_ = now;
  housekept_since_cycle_ = false;
}

void RegisterProxy::EndCycle(hal::Micros now) {
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
bool RegisterProxy::CycleJob(hal::Micros now, Job& job) {
  if (!NextCycleStep(now, job)) return false;
  urgent_since_cycle_step_ = 0;
  return true;
}

bool RegisterProxy::NextCycleStep(hal::Micros now, Job& job) {
  for (int pass = 0; pass < 2; ++pass) {
    if (cycle_active_) {
      while (cycle_command_ < kCommandWordCount) {
        const std::size_t w = cycle_command_++;
        const CommandWord& word = commands_[w];
        if (!CommandWordWritable(w)) continue;
        const bool due = !word.written_valid || CommandValue(w) != word.written ||
                         now - word.written_at >= config_.command_refresh_interval;
        if (!due) continue;
        MakeCommandJob(w, job);
        return true;
      }
      if (!cycle_block_done_ && block_read_count_ > 0) {
        cycle_block_done_ = true;
        job.kind = JobKind::kBlockRead;
        job.index = 0;
        job.transaction = Transaction::Block(std::span<const std::uint16_t>(), block_read_count_);
        return true;
      }
      while (cycle_read_ < read_count_) {
        const std::size_t r = cycle_read_++;
        if (reads_[r].by_block) continue;
        job.kind = JobKind::kMonitorRead;
        job.index = static_cast<std::uint8_t>(r);
        job.transaction = Transaction::Read(reads_[r].number);
        return true;
      }
      EndCycle(now);  // called only with the own slot free: the cycle's last transaction has completed
    }
    if (HousekeepingJob(now, job)) return true;
    if (now < next_cycle_at_) return false;
    StartCycle(now);
  }
  return false;
}

void RegisterProxy::OnMonitorRead(const Job& job, const Completion& completion) {
  if (loading_) return;  // the plan is being replaced
  if (job.kind == JobKind::kBlockRead) {
    ++counters_.block_reads;
  } else {
    ++counters_.monitor_reads;
  }
  if (!completion.ok()) {
    ++counters_.monitor_errors;
    return;
  }
  if (job.kind == JobKind::kMonitorRead) {
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

void RegisterProxy::StoreRead(std::size_t r, std::uint16_t value) {
  reads_[r].value = value;
  if (r == 0) SetFd01(value);
  if (!feedback_wanted_) return;
  // DriveFeedback().known: each of the three read since the feedback was wanted (and since the load).
  if (reads_[r].number == reg::kFd01) feedback_fresh_ |= kFreshFd01;
  if (reads_[r].number == reg::kFd00) feedback_fresh_ |= kFreshFd00;
  if (reads_[r].number == reg::kFe02) feedback_fresh_ |= kFreshFe02;
}

void RegisterProxy::SetFd01(std::uint16_t fd01) {
  fd01_ = fd01;
  fd01_known_ = true;
  SetOwned(kC555At, DriveStatusCode(fd01));  // written when it changes
}

// ---- Values the card owns ----------------------------------------------------------------------------

void RegisterProxy::SetCardStatus(const CardStatus& status) {
  // c536 follows the last event: a change of the firmware's ethernet_error, or a loss report.
  if (status.ethernet_error != status_.ethernet_error) c536_ = status.ethernet_error;
  status_ = status;
  UpdateStatusValues();
  wake_ = true;
}

void RegisterProxy::UpdateStatusValues() {
  for (std::size_t i = 0; i < 2; ++i) SetOwned(kRatesAt + i, status_.port_rates[i]);
  for (std::size_t i = 0; i < 6; ++i) SetOwned(kMacAt + i, status_.mac.octets()[i]);
  for (std::size_t i = 0; i < 4; ++i) {
    SetOwned(kIpAt + i, status_.ip.octets()[i]);
    SetOwned(kNetmaskAt + i, status_.netmask.octets()[i]);
    SetOwned(kGatewayAt + i, status_.gateway.octets()[i]);
  }
  SetOwned(kC536At, c536_);
}

void RegisterProxy::SetOwned(std::size_t index, std::uint16_t value) {
  owned_[index].wanted = value;
  owned_[index].wanted_valid = true;
}

// c041-c046 show the master's command words, c061-c066 the monitor words: display values, sampled every
// display_interval so a changing monitor costs at most one write per interval.
void RegisterProxy::SampleDisplay() {
  const ScannerWords monitors = MonitorWords();
  for (std::size_t w = 0; w < kScannerWordCount; ++w) {
    SetOwned(kCommandDisplayAt + w, held_[w]);
    SetOwned(kMonitorDisplayAt + w, monitors[w]);
  }
}

bool RegisterProxy::HousekeepingJob(hal::Micros now, Job& job) {
  if (housekept_since_cycle_ && now >= next_cycle_at_) return false;
  if (now >= next_display_at_) {
    SampleDisplay();
    next_display_at_ += config_.display_interval;
    if (next_display_at_ <= now) next_display_at_ = now + config_.display_interval;
  }
  for (std::size_t i = 0; i < owned_.size(); ++i) {
    OwnedValue& value = owned_[i];
    if (!value.wanted_valid || (value.written_valid && value.written == value.wanted)) continue;
    job.kind = JobKind::kOwnedWrite;
    job.index = static_cast<std::uint8_t>(i);
    job.transaction = Transaction::WriteRam(value.number, value.wanted);  // display values: RAM only
    value.written = value.wanted;
    value.written_valid = true;
    housekept_since_cycle_ = true;
    return true;
  }
  return false;
}

void RegisterProxy::OnOwnedWritten(std::uint8_t index, const Completion& completion) {
  ++counters_.owned_writes;
  if (completion.ok()) return;
  ++counters_.owned_errors;
  // A refused value is not repeated until it changes; one that may not have arrived is.
  if (completion.outcome != Outcome::kErrorReply) owned_[index].written_valid = false;
}

}  // namespace drive_link
