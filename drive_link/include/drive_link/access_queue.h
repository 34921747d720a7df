// The register proxy's on-demand accesses (DriveRegisters): THE place that checks a register access
// before it reaches the inverter, for Modbus, CIP and the web alike (CheckRead/CheckWrite); the pool of
// kMaxPendingAccesses, one access on the link at a time in acceptance order, the mapping of the link's
// outcome onto AccessError, and delivery from Poll (docs/drive-link.md, "Register proxy"). What it must
// know of the rest of the proxy (the configuration, the scanner's targets, a loss holding the drive)
// and what a completed write means to it come through AccessRules.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "base/pool_stats.h"
#include "base/status.h"
#include "drive_link/link_client.h"
#include "drive_link/proxy_config.h"
#include "drive_link/register_access.h"

namespace drive_link {

// On-demand accesses accepted and not yet delivered: one outstanding access for each of 8 Modbus TCP
// clients, or fewer Modbus clients plus CIP explicit messages (Parameter objects, assemblies 101/105). A
// cancelled access whose request is already on the link keeps its slot until the link completes it.
inline constexpr std::size_t kMaxPendingAccesses = 8;

class AccessRules {
 public:
  virtual ~AccessRules() = default;
  // A configuration is loaded (accesses are refused with kLinkDown until then).
  virtual bool ConfigLoaded() const = 0;
  virtual bool IsScannerTarget(std::uint16_t number) const = 0;
  virtual bool CommandsHeldByLoss() const = 0;
  // FD01 known and bit 10 set: a parameter write the inverter refuses with 0000 is "not while running".
  virtual bool DriveRunning() const = 0;
  // A write went through (or, resetting the inverter, went out unanswered as expected).
  virtual void OnWriteAccepted(std::uint16_t number, std::uint16_t value) = 0;
  // ... and it reset the inverter: f899 = 1 (`card_reset`: the option's configuration too) or a fault
  // reset (FA06/FA00 bit 13).
  virtual void OnInverterReset(bool card_reset) = 0;
};

// The local refusals of a write, in this order: kNoSuchRegister (xxxA-xxxF), kReadOnly (a monitor, a
// value the card owns, FA30), kLinkDown (no configuration loaded), kReservedForScanner, kNetworkLost (a
// run or speed command while a loss holds the drive). kNone: the inverter decides. Only the queries of
// `rules` are asked.
AccessError CheckRegisterWrite(std::uint16_t number, std::uint16_t value, const AccessRules& rules);

class AccessQueue {
 public:
  AccessQueue(AccessRules& rules, ProxyCounters& counters) : rules_(rules), counters_(counters) {}

  // A read's local refusals: kNoSuchRegister, kLinkDown. A write's: CheckRegisterWrite.
  AccessError CheckRead(std::uint16_t number) const;
  AccessError CheckWrite(std::uint16_t number, std::uint16_t value) const {
    return CheckRegisterWrite(number, value, rules_);
  }

  // DriveRegisters, after the proxy's own precondition (the link is up). A refusal is delivered on the
  // next Deliver like any result.
  base::Result<AccessToken> Read(std::uint16_t number, AccessListener& listener);
  base::Result<AccessToken> Write(std::uint16_t number, std::uint16_t value, WriteMode mode,
                                  AccessListener& listener);
  void Cancel(AccessListener& listener);

  // ---- The link (through the scheduler) ----
  // The oldest waiting access, when none is on the link; null otherwise.
  const Transaction* NextToSend();
  // NextToSend's access went to the link as `request`, or the link refused it (kResourceExhausted: it
  // waits; otherwise it ends in kLinkDown or kRefused).
  void Sent(RequestId request);
  void SendRefused(base::StatusCode code);
  // False when `request` is not an access's.
  bool OnComplete(RequestId request, const Completion& completion);
  // An access on the link resets the inverter (f899 = 1, a fault reset): nothing else may follow it.
  bool reset_on_link() const { return reset_on_link_; }
  bool on_link() const { return on_link_; }

  // Every access not yet sent ends in `error` (e-23, a configuration being replaced).
  void FailWaiting(AccessError error);
  // Completed accesses to their listeners, in acceptance order.
  void Deliver();

  base::PoolStats pool() const { return marks_.Stats(InUse(), kMaxPendingAccesses); }

 private:
  struct Access {
    enum class State : std::uint8_t { kFree, kWaiting, kOnLink, kDone };
    State state = State::kFree;
    AccessToken token = kNoAccess;
    AccessListener* listener = nullptr;  // null once cancelled
    std::uint32_t order = 0;             // acceptance order: FIFO on the link and in delivery
    Transaction transaction{};
    RequestId request = kNoRequestId;
    AccessResult result{};
  };

  base::Result<AccessToken> Accept(const Transaction& transaction, AccessListener& listener,
                                   AccessError local_refusal);
  void Finish(Access& access, AccessError error, std::uint16_t value);
  std::size_t InUse() const;
  Access* OldestWaiting();
  void Complete(Access& access, const Completion& completion);
  AccessError MapError(const Access& access, const Completion& completion) const;

  AccessRules& rules_;
  ProxyCounters& counters_;
  std::array<Access, kMaxPendingAccesses> accesses_{};
  base::PoolWatermark marks_;
  AccessToken next_token_ = 1;
  std::uint32_t next_order_ = 0;
  bool on_link_ = false;
  bool reset_on_link_ = false;  // that access resets the inverter (f899 = 1, a fault reset)
};

}  // namespace drive_link
