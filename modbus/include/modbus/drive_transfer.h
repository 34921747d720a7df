// Registers of units 0-248 moved between one Modbus request and the inverter (seed 000 §8.2, §8.9):
// the register address is the communication number, reached through drive_link::DriveRegisters.
//
// One access at a time, one after another, in register order: the drive link carries one request on
// the wire anyway, and a write must not overtake an earlier one. Register k of a transfer is the k-th
// existing communication number from the start (numbers ending A-F are skipped, §8.9 (5)).
//
// Results (docs/modbus.md "Exceptions" has the table with reasons):
//   read:  a number that does not exist reads 0x8000 (§8.4) and the transfer goes on; any other
//          failure ends it with exception 04.
//   write: kNoSuchRegister, kReadOnly, kReservedForScanner -> 02; kOutOfRange -> 03; running, refused,
//          link down, timeout -> 04. A write stops at the first refused register: the ones before it
//          keep their new values (a write on the wire cannot be taken back), the ones after it are not
//          written. CheckDriveWrite refuses what can be known before anything is written.
#pragma once

#include <array>
#include <cstdint>
#include <span>

#include "drive_link/register_access.h"
#include "hal/clock.h"
#include "modbus/pdu.h"

namespace modbus {

// When every slot of the register proxy is busy (kResourceExhausted), the access is tried again
// this much later.
inline constexpr hal::Micros kDriveBusyRetry = hal::kMicrosPerMilli;

ExceptionCode ExceptionForReadError(drive_link::AccessError error);
ExceptionCode ExceptionForWriteError(drive_link::AccessError error);

// Checks a read before it starts: 02 when it runs past communication number FFF9.
ExceptionCode CheckDriveRead(std::uint16_t first, std::uint16_t count);
// Checks a write before anything is written: 02 when it runs past FFF9, when the drive's own check
// (DriveRegisters::CheckWrite, the one check of a register write) refuses a register for its address
// (no such register, read-only, reserved for IO scanning: the errors that map to 02), or, with
// `control_locked` (the client is not the IO scanning master: ControlLockedFor), when a register is a
// control register (reg::IsControlRegister). A refusal that may pass (link down, a loss holding the
// drive) is left to the access itself.
ExceptionCode CheckDriveWrite(std::uint16_t first, std::span<const std::uint16_t> values,
                              const drive_link::DriveRegisters& drive, bool control_locked);

class DriveTransfer {
 public:
  enum class State : std::uint8_t { kIdle, kRunning, kDone };

  DriveTransfer() = default;
  DriveTransfer(const DriveTransfer&) = delete;
  DriveTransfer& operator=(const DriveTransfer&) = delete;

  // Starts a transfer; completions must be passed to Complete(). May finish at once (kDone).
  void StartRead(drive_link::DriveRegisters& drive, drive_link::AccessListener& listener, std::uint16_t first,
                 std::uint16_t count, hal::Micros now);
  void StartWrite(drive_link::DriveRegisters& drive, drive_link::AccessListener& listener, std::uint16_t first,
                  std::span<const std::uint16_t> values, hal::Micros now);

  // A completion for `listener`. False when it is not this transfer's (a stale token).
  bool Complete(drive_link::AccessToken token, const drive_link::AccessResult& result, hal::Micros now);
  // Retries an access the proxy had no slot for.
  void Poll(hal::Micros now);
  hal::Micros NextDeadline() const { return state_ == State::kRunning ? retry_at_ : hal::kNever; }
  // Forgets the transfer (the connection closed). Pending completions are cancelled by the caller.
  void Reset();

  State state() const { return state_; }
  bool done() const { return state_ == State::kDone; }
  // kDone: kNone when every register was transferred.
  ExceptionCode exception() const { return exception_; }
  std::span<const std::uint16_t> values() const { return std::span<const std::uint16_t>(values_).first(count_); }

 private:
  void Start(drive_link::DriveRegisters& drive, drive_link::AccessListener& listener, bool write,
             std::uint16_t first, std::uint16_t count, hal::Micros now);
  void IssueNext(hal::Micros now);
  void Advance();
  void Finish(ExceptionCode exception);

  drive_link::DriveRegisters* drive_ = nullptr;
  drive_link::AccessListener* listener_ = nullptr;
  State state_ = State::kIdle;
  bool write_ = false;
  std::uint16_t count_ = 0;
  std::uint16_t index_ = 0;
  std::uint32_t number_ = 0;
  // Read: the values read; write: the values to write.
  std::array<std::uint16_t, kMaxWriteRegisters> values_{};
  drive_link::AccessToken token_ = drive_link::kNoAccess;
  hal::Micros retry_at_ = hal::kNever;  // kNever while an access is on its way
  ExceptionCode exception_ = ExceptionCode::kNone;
};

}  // namespace modbus
