// ConfigLoader: the reads of a configuration load and their validation (docs/drive-link.md,
// "Configuration at start-up and reset").
#include "drive_link/config_loader.h"

#include "drive_link/drive_registers.h"

namespace drive_link {
namespace {

// F875-F879, read after kConfigNumbers: the block read selections in force. FD01 is read last, so the
// drive's status is known the moment the load ends (a card reset resets the inverter too: the status
// from before is gone, and the drive profile must not see "unknown" between the load and the first cycle).
constexpr std::uint16_t kF875 = 0x0875;
constexpr std::size_t kFd01LoadIndex = kConfigLoadReads - 1;
// F875-F879 choices 0-10 (seed 003 §4).
constexpr std::uint16_t kMaxBlockReadSelection = 10;

std::uint16_t LoadNumber(std::size_t index) {
  if (index == kFd01LoadIndex) return reg::kFd01;
  return index < config::kConfigNumberCount
             ? config::kConfigNumbers[index]
             : static_cast<std::uint16_t>(kF875 + (index - config::kConfigNumberCount));
}

}  // namespace

void ConfigLoader::Begin() {
  loading_ = true;
  loaded_ = false;
  index_ = 0;
}

bool ConfigLoader::NextRead(OwnJob& job) const {
  if (!loading_ || index_ >= kConfigLoadReads) return false;
  job.kind = OwnJobKind::kConfigRead;
  job.index = index_;
  job.transaction = Transaction::Read(LoadNumber(index_));
  return true;
}

bool ConfigLoader::OnRead(std::uint8_t index, const Completion& completion) {
  if (!loading_ || index != index_) return false;  // a load abandoned by e-23
  if (completion.outcome == Outcome::kLinkDown) return false;
  AccessResult& read = reads_[index];
  read = AccessResult{};
  read.number = LoadNumber(index);
  if (completion.ok()) {
    read.value = completion.data;
  } else if (completion.outcome == Outcome::kErrorReply) {
    switch (completion.error) {
      case wire::ErrorCode::kCommunicationNumberError:
        read.error = AccessError::kNoSuchRegister;
        break;
      case wire::ErrorCode::kDataError:
        read.error = AccessError::kOutOfRange;
        break;
      case wire::ErrorCode::kChecksumError:
        read.error = AccessError::kTimeout;
        break;
      case wire::ErrorCode::kImpossibleToExecute:
      case wire::ErrorCode::kCommandError:
        read.error = AccessError::kRefused;
        break;
    }
  } else {
    read.error = AccessError::kTimeout;
  }
  ++index_;
  if (index_ < kConfigLoadReads) return false;
  Finish();
  return true;
}

void ConfigLoader::Finish() {
  parsed_ = config::ParseCardConfig(
      std::span<const AccessResult, config::kConfigNumberCount>(reads_.data(), config::kConfigNumberCount));
  // F875-F879: a value the inverter cannot hold is reported like a configuration problem and not used.
  for (std::size_t i = 0; i < kBlockReadSelections; ++i) {
    const AccessResult& read = reads_[config::kConfigNumberCount + i];
    const bool valid = read.ok() && read.value <= kMaxBlockReadSelection;
    block_selections_[i] = valid ? read.value : 0;
    if (valid) continue;
    const config::ConfigProblem problem{
        read.number, read.value,
        read.ok() ? config::ConfigProblem::Kind::kOutOfRange : config::ConfigProblem::Kind::kUnreadable,
        read.error};
    if (parsed_.problem_count < parsed_.problems.size()) parsed_.problems[parsed_.problem_count++] = problem;
    ++parsed_.problems_total;
  }
  loading_ = false;
  loaded_ = true;
}

}  // namespace drive_link
