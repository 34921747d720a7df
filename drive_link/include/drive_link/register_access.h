// What the front ends (Modbus TCP, CIP, web) use of the drive: facades implemented by
// drive_link::RegisterProxy and by fakes in tests. Every front end reaches the inverter only through
// these, so the rules of docs/drive-link.md "Register proxy" hold for all of them.
//
// - DriveRegisters: on-demand reads and writes of any communication number, asynchronous (one drive-link
//   round trip each), with precise error results.
// - ScannerImage: the scanner words of the cyclic exchange (c001-c006 out, c021-c026 in).
// - LossSupervision: the front ends' report that their network connection is lost or back; the c100
//   delay, c103 condition and c101 action are carried out behind it.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "base/status.h"
#include "config/access_result.h"
#include "config/card_config.h"
#include "drive_link/drive_registers.h"
#include "hal/clock.h"

namespace drive_link {

// The outcome of one access and the scanner word count are the card's shared vocabulary (config/): the
// front ends name them through this facade.
using config::AccessError;
using config::AccessErrorName;
using config::AccessResult;
using config::kScannerWordCount;

// W writes RAM and EEPROM; P writes RAM only. EEPROM lasts about 100,000 writes (seed 000 §8.5): front
// ends choose kRamAndEeprom only for an explicit parameter write by a user, never for cyclic data.
enum class WriteMode : std::uint8_t { kRamAndEeprom, kRamOnly };


// Names one access in its completion; never kNoAccess.
using AccessToken = std::uint32_t;
inline constexpr AccessToken kNoAccess = 0;

class AccessListener {
 public:
  virtual ~AccessListener() = default;
  // Called from the proxy's Poll, never from inside Read/Write (even for a local refusal), so the caller
  // can finish its own bookkeeping first. May start new accesses.
  virtual void OnAccessDone(AccessToken token, const AccessResult& result) = 0;
};

class DriveRegisters {
 public:
  virtual ~DriveRegisters() = default;
  // Starts an access. kResourceExhausted: every slot of the pool is busy (try again on a later pass);
  // kFailedPrecondition: the drive link is down (e-23). Otherwise the listener gets exactly one
  // OnAccessDone with the token returned, unless Cancel(listener) is called first.
  virtual base::Result<AccessToken> Read(std::uint16_t number, AccessListener& listener) = 0;
  virtual base::Result<AccessToken> Write(std::uint16_t number, std::uint16_t value, WriteMode mode,
                                          AccessListener& listener) = 0;
  // The refusal a Write of `value` to `number` would get now without reaching the inverter; kNone when
  // the inverter decides. The one check of a register write (drive_link::CheckRegisterWrite): a front end
  // asks it before a multi-register write, so that nothing is written when a later register is refused.
  virtual AccessError CheckWrite(std::uint16_t number, std::uint16_t value) const = 0;
  // Forgets every pending completion for `listener` (a connection closed). The accesses themselves run
  // to their end: a write already on the wire cannot be taken back.
  virtual void Cancel(AccessListener& listener) = 0;
};

using ScannerWords = std::array<std::uint16_t, kScannerWordCount>;

// The cyclic exchange's image (seed 000 §3.2.4, §9.2). Word i is scanner word i+1: command word i goes
// to the register c00(i+1) selects, monitor word i comes from the register c02(i+1) selects; a word whose
// menu is 0 ("-") is not exchanged (command: ignored; monitor: reads 0).
class ScannerImage {
 public:
  virtual ~ScannerImage() = default;
  // The master's newest command words. The exchange sends a word when it changed, and refreshes each
  // word in use at a slower rate (RegisterProxy: ProxyConfig::command_refresh_interval); always a RAM
  // write, never EEPROM. Nothing is written before the first call since start/reset.
  virtual void SetCommandWords(const ScannerWords& words) = 0;
  virtual ScannerWords CommandWords() const = 0;
  // The newest monitor words read from the inverter.
  virtual ScannerWords MonitorWords() const = 0;
  // True when `number` is the target of a command word in use: other services may not write it.
  virtual bool IsScannerTarget(std::uint16_t number) const = 0;
};

// FA06/FA07 for the CIP drive profile (assemblies 20/21/100/101, Control Supervisor 0x29, AC/DC Drive
// 0x2A), whatever c001-c006 select, and the feedback registers those need besides FD01.
struct DriveCommandWords {
  std::uint16_t fa06 = 0;
  std::uint16_t fa07 = 0;
  constexpr bool operator==(const DriveCommandWords&) const = default;
};

// The registers the drive command owns: FA06 and FA07. While it is taken, a scanner word whose menu
// targets one of them is displaced (not written by the exchange, not carried by assembly 100): the one
// statement of that rule, for the drive link and the drive profile alike.
constexpr bool IsDriveCommandRegister(std::uint16_t number) { return number == reg::kFa06 || number == reg::kFa07; }

struct DriveFeedbackWords {
  std::uint16_t fd01 = 0;  // status
  std::uint16_t fd00 = 0;  // output frequency, 0.01 Hz
  std::uint16_t fe02 = 0;  // frequency command in force, 0.01 Hz
  bool known = false;      // all three read since feedback was wanted (and since the last load)
};

class DriveCommandChannel {
 public:
  virtual ~DriveCommandChannel() = default;
  // Takes FA06 and FA07 over: both are written by the cyclic exchange as command words are (at once when
  // changed, refreshed when unchanged, RAM only, FA06 bit 13 once per rising edge, nothing while a loss
  // action other than c101 = 1 is in force). While taken, a scanner word whose menu targets FA06 or FA07
  // is not written (the drive profile owns the register) and IsScannerTarget(FA06/FA07) is true.
  virtual void SetDriveCommand(const DriveCommandWords& words) = 0;
  // Gives FA06/FA07 back (to the scanner words, if a menu targets them). Nothing is written for it.
  virtual void ReleaseDriveCommand() = 0;
  virtual bool drive_command_taken() const = 0;
  // A network loss was reported and not restored, and its c101 action (other than 1, continue) runs or
  // will run when c100 is over: the loss supervision owns FA06. Run and speed commands of the explicit
  // paths are refused meanwhile; a stop is taken (docs/drive-control.md).
  virtual bool CommandsHeldByLoss() const = 0;
  // An explicit stop accepted while CommandsHeldByLoss: written to FA06 at once and, until the network is
  // restored, in place of the action's FA06 (c101 = 0, 2, 3, 5; with 4 after the err8 request), so that
  // the action cannot start the drive again (c101 = 5). Fault-reset bit cleared. Ignored otherwise.
  virtual void HoldStopDuringLoss(std::uint16_t fa06) = 0;
  // As ScannerImage::SetCommandWords for the words whose bit is set in `mask` (bit i = word i + 1): the
  // others are not written while the last call's mask leaves them out (an assembly 100 of fewer than
  // 8 words carries fewer scanner words). SetCommandWords is this with every bit set.
  virtual void SetCommandWordsMasked(const ScannerWords& words, std::uint8_t mask) = 0;
  // Whether FD00 and FE02 are read in every exchange cycle (besides FD01); off by default, so the
  // Modbus side's cycle does not get longer.
  virtual void SetFeedbackWanted(bool wanted) = 0;
  virtual DriveFeedbackWords DriveFeedback() const = 0;
};

// What cut the front end's traffic; reported in c536 where the manual has a code for it.
enum class LossCause : std::uint8_t {
  kModbusIoScanning,   // Modbus TCP IO scanning timeout (c523): c536 = 1
  kModbusConnection,   // Modbus TCP traffic timeout (c523), IO scanning not in use: c536 unchanged
  kCipConnection,      // EtherNet/IP connection timeout (RPI x 4 x 2^multiplier): c536 unchanged
  kCarrierLost,        // both Ethernet links down: c536 = 3
};

class LossSupervision {
 public:
  virtual ~LossSupervision() = default;
  // The front end's own timeout expired at `now`. After c100 the c103 condition is checked and the c101
  // action carried out, unless NetworkRestored came first. Repeated calls while lost do nothing.
  virtual void NetworkLost(LossCause cause, hal::Micros now) = 0;
  // Traffic is back: a pending delay is cancelled, an action in force is lifted (an err8 trip stays
  // until the inverter is reset), c536 goes back to 0.
  virtual void NetworkRestored(hal::Micros now) = 0;
  // A loss action is in force (the cyclic exchange is not writing the master's command words).
  virtual bool loss_action_active() const = 0;
};

}  // namespace drive_link
