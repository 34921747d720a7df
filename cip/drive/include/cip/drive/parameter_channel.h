// The parameter channel of assemblies 101/151 and 105/155 (seed 000 §5.1.7-§5.1.8, §5.1.11-§5.1.12;
// docs/drive-profile.md "Parameter channel").
//
// An output assembly carries a request (read or write one communication number); the input assembly
// shows the response: the request's index echoed with the data read, the data written, or an error.
//
//   101 bytes 4-5  index: bits 0-13 communication number, bit 15 write (0x8000)
//   101 bytes 6-7  data to write
//   151 bytes 4-5  index echoed: bits 0-13 number, bit 15 write, bit 14 error (0x4000)
//   151 bytes 6-7  data read / written, or the error code 0x1100 (data out of range) / 0x1101 (bad address)
//   105 byte 1     function 0x00 read / 0x80 write; bytes 2-3 index (16 bits); bytes 4-5 data
//   155 byte 1     result 0x00 done / 0x40 error; bytes 2-3 index echoed; bytes 4-5 data or 0x0001
//
// ParameterChannel (one per connection) decides when an access is due. The output assembly arrives every
// RPI with the same request: a request is executed ONCE, when it differs from the previous one (index,
// function/write flag or data). A master repeats a read or a write by changing the request in between
// (e.g. through index 0 or another parameter). Until the access completes, the response of the previous
// request stays in the input assembly, so a master knows its answer has arrived when the echo matches.
// Pure state: the access itself (drive_link::DriveRegisters) is the caller's.
#pragma once

#include <cstdint>

#include "drive_link/register_access.h"

namespace cip::drive {

inline constexpr std::uint16_t kParameterWriteFlag = 0x8000;  // 101/151 index bit 15
inline constexpr std::uint16_t kParameterErrorFlag = 0x4000;  // 151 index bit 14
inline constexpr std::uint16_t kParameterIndexMask = 0x3FFF;  // 101/151: the communication number
inline constexpr std::uint16_t kErrorDataOutOfRange = 0x1100;  // 151 data on error
inline constexpr std::uint16_t kErrorBadAddress = 0x1101;      // 151 data on error
inline constexpr std::uint8_t kFunctionRead = 0x00;            // 105 byte 1
inline constexpr std::uint8_t kFunctionWrite = 0x80;           // 105 byte 1
inline constexpr std::uint8_t kFunctionResultError = 0x40;     // 155 byte 1 (0x00 when done)
inline constexpr std::uint16_t kErrorToshibaSpecific = 0x0001;  // 155 data on error

struct ParameterRequest {
  bool present = false;  // the output assembly has a parameter channel (101, 105)
  bool valid = true;     // 105: the function code is 0x00 or 0x80; false -> error answer, no access
  bool write = false;
  std::uint16_t number = 0;  // the communication number (101: 14 bits)
  std::uint16_t data = 0;    // the value to write (also compared for reads: any change is a new request)
  std::uint8_t function = 0;  // 105: the function byte as received (0x00 / 0x80 when valid)
  friend constexpr bool operator==(const ParameterRequest&, const ParameterRequest&) = default;
};

struct ParameterResponse {
  bool present = false;  // a request has been answered (else the input assembly carries zeros)
  bool write = false;
  bool error = false;
  drive_link::AccessError cause = drive_link::AccessError::kNone;  // when error
  std::uint16_t number = 0;  // echoed as the request carried it
  std::uint16_t value = 0;   // read: the value; write: the value the inverter took
  friend constexpr bool operator==(const ParameterResponse&, const ParameterResponse&) = default;
};

// 151's error code for an access error: the address class (a number the inverter does not have, a
// number that may not be written: monitor, card-owned value, scanner target) is 0x1101 "bad address";
// everything else (out of range, refused, not writable while running, timeout, link down) is 0x1100.
// §5.1.8 names only these two codes.
constexpr std::uint16_t Error151(drive_link::AccessError cause) {
  switch (cause) {
    case drive_link::AccessError::kNoSuchRegister:
    case drive_link::AccessError::kReadOnly:
    case drive_link::AccessError::kReservedForScanner:
      return kErrorBadAddress;
    default:
      return kErrorDataOutOfRange;
  }
}

// Parameter writes through 101/105 are a user's explicit parameter writes: RAM and EEPROM (W), once per
// request (seed 004 §15 (2); the FA command registers are RAM only in the inverter whatever the mode).
inline constexpr drive_link::WriteMode kParameterWriteMode = drive_link::WriteMode::kRamAndEeprom;

class ParameterChannel {
 public:
  // The request of the newest consumed output assembly. A request equal to the previous one does
  // nothing; a new one replaces a request not started yet. An invalid request (105 function code other
  // than 0x00/0x80) is answered at once with an error, without an access; a request not present
  // (instances without a channel) is ignored.
  void Offer(const ParameterRequest& request);
  // An access to start now: a new request is waiting and none is on the way. Marks it on the way.
  bool TakeDue(ParameterRequest& request);
  // The access started by the last TakeDue ended. Its answer becomes the response unless a newer
  // request was offered meanwhile (the newer one is answered instead; an error for an invalid newer
  // request must not be overwritten by an older echo).
  void Complete(const drive_link::AccessResult& result);
  // The access could not be started (pool full: try again later): the request is due again.
  void Retry();
  // Connection opened or closed: no request, no response (the input assembly shows zeros).
  void Reset();

  const ParameterResponse& response() const { return response_; }
  bool busy() const { return in_flight_; }

 private:
  ParameterRequest last_;        // the newest request offered
  bool seen_ = false;            // a request has been offered since Reset
  bool due_ = false;             // last_ waits for an access
  bool in_flight_ = false;       // an access is on the way
  bool superseded_ = false;      // a newer request came while it was on the way
  ParameterRequest started_;     // the request on the way
  ParameterResponse response_;
};

}  // namespace cip::drive
