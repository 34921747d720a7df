// The register proxy's link scheduler: it owns the LinkClient and is its observer, and it arbitrates
// the link between the proxy's own transactions (configuration reads, loss checks and actions, the
// cyclic exchange, write-backs: one on the link at a time, asked of OwnTransactions) and the on-demand
// accesses of the AccessQueue (one at a time), so with both waiting the link's FIFO alternates them.
// While an access that resets the inverter is on the link, nothing of the proxy's own follows it
// (docs/drive-link.md, "Register proxy").
#pragma once

#include "base/status.h"
#include "drive_link/access_queue.h"
#include "drive_link/link_client.h"
#include "drive_link/own_job.h"
#include "hal/clock.h"
#include "hal/serial_port.h"

namespace drive_link {

// The parts behind the proxy's own slot (the composition dispatches to them by OwnJobKind).
class OwnTransactions {
 public:
  virtual ~OwnTransactions() = default;
  // The next own transaction, in priority order; false when none is due now.
  virtual bool NextOwnJob(hal::Micros now, OwnJob& job) = 0;
  virtual void OnOwnComplete(const OwnJob& job, const Completion& completion, hal::Micros now) = 0;
  virtual void OnLinkStateChanged(LinkState previous, LinkState current) = 0;
};

class LinkScheduler final : private LinkObserver {
 public:
  // `port`, `accesses` and `own` must outlive the scheduler.
  LinkScheduler(hal::SerialPort& port, const LinkConfig& link_config, AccessQueue& accesses, OwnTransactions& own);
  LinkScheduler(const LinkScheduler&) = delete;
  LinkScheduler& operator=(const LinkScheduler&) = delete;

  // Starts the link (its start-up silence). kFailedPrecondition when started.
  base::Status Start(hal::Micros now);
  bool started() const { return started_; }
  // The link's pass: completions arrive, each schedules the next transaction at once, so the link sends
  // it in this same pass.
  void Poll(hal::Micros now);
  // Fills the free slots: the own slot (unless an inverter reset is on the link), then the access slot.
  void Schedule(hal::Micros now);
  hal::Micros NextDeadline() const { return link_.NextDeadline(); }

  // The own slot is free (no own transaction on the link).
  bool own_slot_free() const { return own_request_ == kNoRequestId; }
  bool link_fault() const { return link_.state() == LinkState::kFault; }
  const LinkClient& link() const { return link_; }

 private:
  void OnComplete(RequestId id, const Completion& completion) override;
  void OnLinkStateChanged(LinkState previous, LinkState current) override;

  LinkClient link_;
  AccessQueue& accesses_;
  OwnTransactions& own_;
  bool started_ = false;
  hal::Micros now_ = 0;  // of the current or last pass
  OwnJob own_job_{};
  RequestId own_request_ = kNoRequestId;
};

}  // namespace drive_link
