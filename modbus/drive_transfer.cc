#include "modbus/drive_transfer.h"

#include <algorithm>

#include "drive_link/drive_registers.h"

namespace modbus {

using drive_link::AccessError;

ExceptionCode ExceptionForReadError(AccessError error) {
  // kNoSuchRegister never ends a read (it reads 0x8000). The seed lists no 04 for FC 03 (§8.4), but a
  // read the inverter could not answer has no true value to return: 04, as for the writes.
  static_cast<void>(error);
  return ExceptionCode::kServerDeviceFailure;
}

ExceptionCode ExceptionForWriteError(AccessError error) {
  switch (error) {
    case AccessError::kNone:
      return ExceptionCode::kNone;
    // The address cannot be written by this request, now or later: "illegal data address".
    case AccessError::kNoSuchRegister:
    case AccessError::kReadOnly:
    case AccessError::kReservedForScanner:
      return ExceptionCode::kIllegalDataAddress;
    // The inverter's "data error": the value is outside the parameter's range.
    case AccessError::kOutOfRange:
      return ExceptionCode::kIllegalDataValue;
    // The request was valid; the drive could not carry it out now.
    case AccessError::kNotWritableWhileRunning:
    case AccessError::kRefused:
    case AccessError::kLinkDown:
    case AccessError::kTimeout:
    // A loss action holds the drive (docs/drive-control.md): the seed lists 01-04 for FC 06/16 (§8.5), and
    // 04 is the one that says "not carried out"; 06 (busy) would promise that a retry succeeds.
    case AccessError::kNetworkLost:
      return ExceptionCode::kServerDeviceFailure;
  }
  return ExceptionCode::kServerDeviceFailure;
}

ExceptionCode CheckDriveRead(std::uint16_t first, std::uint16_t count) {
  return LastCommunicationNumber(first, count) > 0xFFFF ? ExceptionCode::kIllegalDataAddress : ExceptionCode::kNone;
}

ExceptionCode CheckDriveWrite(std::uint16_t first, std::span<const std::uint16_t> values,
                              const drive_link::DriveRegisters& drive, bool control_locked) {
  const auto count = static_cast<std::uint16_t>(values.size());
  if (LastCommunicationNumber(first, count) > 0xFFFF) return ExceptionCode::kIllegalDataAddress;
  std::uint32_t number = first;
  for (std::uint16_t i = 0; i < count; ++i, number = NextCommunicationNumber(number)) {
    const auto n = static_cast<std::uint16_t>(number);
    const ExceptionCode refusal = ExceptionForWriteError(drive.CheckWrite(n, values[i]));
    if (refusal == ExceptionCode::kIllegalDataAddress) return refusal;
    if (control_locked && drive_link::reg::IsControlRegister(n)) return ExceptionCode::kIllegalDataAddress;
  }
  return ExceptionCode::kNone;
}

void DriveTransfer::StartRead(drive_link::DriveRegisters& drive, drive_link::AccessListener& listener,
                              std::uint16_t first, std::uint16_t count, hal::Micros now) {
  Start(drive, listener, false, first, std::min(count, kMaxReadRegisters), now);
}

void DriveTransfer::StartWrite(drive_link::DriveRegisters& drive, drive_link::AccessListener& listener,
                               std::uint16_t first, std::span<const std::uint16_t> values, hal::Micros now) {
  const std::size_t count = std::min<std::size_t>(values.size(), values_.size());
  std::copy_n(values.begin(), count, values_.begin());
  Start(drive, listener, true, first, static_cast<std::uint16_t>(count), now);
}

void DriveTransfer::Start(drive_link::DriveRegisters& drive, drive_link::AccessListener& listener, bool write,
                          std::uint16_t first, std::uint16_t count, hal::Micros now) {
  drive_ = &drive;
  listener_ = &listener;
  state_ = State::kRunning;
  write_ = write;
  count_ = count;
  index_ = 0;
  number_ = first;
  token_ = drive_link::kNoAccess;
  exception_ = ExceptionCode::kNone;
  IssueNext(now);
}

void DriveTransfer::IssueNext(hal::Micros now) {
  while (state_ == State::kRunning) {
    if (index_ >= count_) {
      Finish(ExceptionCode::kNone);
      return;
    }
    const auto number = static_cast<std::uint16_t>(number_);
    // Only a read's start can name a number ending A-F (the walk skips them, a write is checked
    // before it starts): it does not exist, no need to ask.
    if (!write_ && !drive_link::reg::HasDecimalLastDigit(number)) {
      values_[index_] = kNoSuchRegisterValue;
      Advance();
      continue;
    }
    const base::Result<drive_link::AccessToken> started =
        write_ ? drive_->Write(number, values_[index_], drive_link::WriteMode::kRamAndEeprom, *listener_)
               : drive_->Read(number, *listener_);
    if (started.ok()) {
      token_ = *started;
      retry_at_ = hal::kNever;
      return;
    }
    if (started.status().code() == base::StatusCode::kResourceExhausted) {
      retry_at_ = now + kDriveBusyRetry;
      return;
    }
    // kFailedPrecondition: the drive link is down (e-23); nothing was sent.
    Finish(write_ ? ExceptionForWriteError(AccessError::kLinkDown) : ExceptionForReadError(AccessError::kLinkDown));
    return;
  }
}

bool DriveTransfer::Complete(drive_link::AccessToken token, const drive_link::AccessResult& result,
                             hal::Micros now) {
  if (state_ != State::kRunning || token == drive_link::kNoAccess || token != token_) return false;
  token_ = drive_link::kNoAccess;
  if (write_) {
    if (!result.ok()) {
      Finish(ExceptionForWriteError(result.error));
      return true;
    }
  } else if (result.ok()) {
    values_[index_] = result.value;
  } else if (result.error == AccessError::kNoSuchRegister) {
    values_[index_] = kNoSuchRegisterValue;
  } else {
    Finish(ExceptionForReadError(result.error));
    return true;
  }
  Advance();
  IssueNext(now);
  return true;
}

void DriveTransfer::Poll(hal::Micros now) {
  if (state_ == State::kRunning && token_ == drive_link::kNoAccess && now >= retry_at_) IssueNext(now);
}

void DriveTransfer::Reset() {
  state_ = State::kIdle;
  token_ = drive_link::kNoAccess;
  retry_at_ = hal::kNever;
  count_ = 0;
}

void DriveTransfer::Advance() {
  ++index_;
  number_ = NextCommunicationNumber(number_);
}

void DriveTransfer::Finish(ExceptionCode exception) {
  state_ = State::kDone;
  exception_ = exception;
  retry_at_ = hal::kNever;
}

}  // namespace modbus
