// The exclusive-owner write lock (docs/security.md "Exclusive-owner write lock"): while an exclusive-owner
// (class 1) connection is open, an explicit request that could start the motor or change its command is
// refused with 0x10 device state conflict unless it comes from the IP address that opened that
// connection. Reads, and every request while no exclusive owner is open, pass.
//
// Control requests (IsControlRequest):
//   0x01 Identity            Reset 0x05: a restart ends the owner's connection (its c100/c101 reaction)
//   0x04 Assembly            Set_Attribute_Single of attribute 3 of an output (20, 21, 100, 101, 102, 105)
//   0x29 Control Supervisor  Set of 3 Run1, 4 Run2, 5 NetCtrl, 12 FaultRst; the Reset service 0x05
//   0x2A AC/DC Drive         Set of 4 NetRef, 8 SpeedRef
//   0x64 / 0x65 Parameter    Set of attribute 3 of a control register (drive_link::reg::IsControlRegister:
//                            FA00-FAFF, cmod, fmod, f207, f899)
//   0x0F Parameter           Set of attribute 1 of an instance whose row is such a control register
// A Forward_Open of an exclusive owner from another originator is the Connection Manager's own refusal
// (0x01 / 0x0106). The owner's originator is an IP address, as for Forward_Close and the O->T data: a PLC
// may send its messages on other TCP connections and sessions than the one that opened its I/O.
//
// The message router asks before the object sees the attribute or the data (MessageRouter::set_guard),
// so a refused request changes nothing and starts no drive access. Device-path code.
#pragma once

#include <cstdint>

#include "cip/io_connection.h"
#include "cip/message_router.h"
#include "cip/object_model.h"

namespace cip::drive {

// Whether `request` (service, class, instance, attribute) is one the lock covers.
bool IsControlRequest(const ServiceRequest& request);

class ControlLock final : public RequestGuard {
 public:
  explicit ControlLock(const ConnectionTable& connections) : connections_(connections) {}
  ControlLock(const ControlLock&) = delete;
  ControlLock& operator=(const ControlLock&) = delete;

  ServiceStatus Admit(const ServiceRequest& request) override;

  // Requests refused so far (the control socket's `stats`: cip.control_lock_refusals).
  std::uint32_t refusals() const { return refusals_; }

 private:
  const ConnectionTable& connections_;
  std::uint32_t refusals_ = 0;
};

}  // namespace cip::drive
