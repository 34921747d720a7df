// CardWriteBack: the values the card owns, written back when they change (docs/drive-link.md,
// "Configuration at start-up and reset").
#include "drive_link/card_write_back.h"

#include <algorithm>

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

}  // namespace

bool CardWriteBack::IsOwnedNumber(std::uint16_t number) {
  return std::find(kOwnedNumbers.begin(), kOwnedNumbers.end(), number) != kOwnedNumbers.end();
}

void CardWriteBack::Reload(hal::Micros now) {
  for (std::size_t i = 0; i < owned_.size(); ++i) {
    owned_[i].number = kOwnedNumbers[i];
    owned_[i].written_valid = false;
    owned_[i].wanted_valid = false;
  }
  UpdateStatusValues();
  next_display_at_ = now;
}

void CardWriteBack::MarkAllUnknown() {
  for (OwnedValue& value : owned_) value.written_valid = false;
}

void CardWriteBack::SetCardStatus(const config::CardStatus& status) {
  // c536 follows the last event: a change of the firmware's ethernet_error, or a loss report.
  if (status.ethernet_error != status_.ethernet_error) c536_ = status.ethernet_error;
  status_ = status;
  UpdateStatusValues();
}

void CardWriteBack::SetEthernetError(std::uint16_t value) {
  c536_ = value;
  UpdateStatusValues();
}

void CardWriteBack::SetDriveStatus(std::uint16_t fd01) {
  Set(kC555At, config::DriveStatusCode(fd01));  // written when it changes
}

void CardWriteBack::UpdateStatusValues() {
  for (std::size_t i = 0; i < 2; ++i) Set(kRatesAt + i, status_.port_rates[i]);
  for (std::size_t i = 0; i < 6; ++i) Set(kMacAt + i, status_.mac.octets()[i]);
  for (std::size_t i = 0; i < 4; ++i) {
    Set(kIpAt + i, status_.ip.octets()[i]);
    Set(kNetmaskAt + i, status_.netmask.octets()[i]);
    Set(kGatewayAt + i, status_.gateway.octets()[i]);
  }
  Set(kC536At, c536_);
}

void CardWriteBack::Set(std::size_t index, std::uint16_t value) {
  owned_[index].wanted = value;
  owned_[index].wanted_valid = true;
}

// c041-c046 show the master's command words, c061-c066 the monitor words: display values, sampled every
// display_interval so a changing monitor costs at most one write per interval.
bool CardWriteBack::NextWrite(hal::Micros now, const ScannerWords& commands, const ScannerWords& monitors,
                              OwnJob& job) {
  if (now >= next_display_at_) {
    for (std::size_t w = 0; w < kScannerWordCount; ++w) {
      Set(kCommandDisplayAt + w, commands[w]);
      Set(kMonitorDisplayAt + w, monitors[w]);
    }
    next_display_at_ += config_.display_interval;
    if (next_display_at_ <= now) next_display_at_ = now + config_.display_interval;
  }
  for (std::size_t i = 0; i < owned_.size(); ++i) {
    OwnedValue& value = owned_[i];
    if (!value.wanted_valid || (value.written_valid && value.written == value.wanted)) continue;
    job.kind = OwnJobKind::kOwnedWrite;
    job.index = static_cast<std::uint8_t>(i);
    job.transaction = Transaction::WriteRam(value.number, value.wanted);  // display values: RAM only
    value.written = value.wanted;
    value.written_valid = true;
    return true;
  }
  return false;
}

void CardWriteBack::OnWritten(std::uint8_t index, const Completion& completion) {
  ++counters_.owned_writes;
  if (completion.ok()) return;
  ++counters_.owned_errors;
  // A refused value is not repeated until it changes; one that may not have arrived is.
  if (completion.outcome != Outcome::kErrorReply && index < owned_.size()) owned_[index].written_valid = false;
}

}  // namespace drive_link
