// LinkScheduler: the link's two slots, the proxy's own transactions and the on-demand accesses
// (docs/drive-link.md, "Register proxy").
#include "drive_link/link_scheduler.h"

namespace drive_link {

LinkScheduler::LinkScheduler(hal::SerialPort& port, const LinkConfig& link_config, AccessQueue& accesses,
                             OwnTransactions& own)
    : link_(port, link_config, this), accesses_(accesses), own_(own) {}

base::Status LinkScheduler::Start(hal::Micros now) {
  if (started_) return base::FailedPrecondition();
  if (base::Status status = link_.Start(now); !status.ok()) return status;
  started_ = true;
  now_ = now;
  return base::OkStatus();
}

void LinkScheduler::Poll(hal::Micros now) {
  if (!started_) return;
  now_ = now;
  link_.Poll(now);
}

void LinkScheduler::Schedule(hal::Micros now) {
  if (!started_ || link_fault()) return;
  // While an access that resets the inverter (f899, fault reset) is on the link, nothing of the proxy's
  // own follows it: the master's command words must not reach an inverter that has just been reset.
  if (own_request_ == kNoRequestId && !accesses_.reset_on_link()) {
    OwnJob job;
    if (own_.NextOwnJob(now, job)) {
      const base::Result<RequestId> id = link_.Submit(job.transaction);
      if (id.ok()) {
        own_job_ = job;
        own_request_ = *id;
      }
    }
  }
  if (accesses_.on_link()) return;
  const Transaction* next = accesses_.NextToSend();
  if (next == nullptr) return;
  const base::Result<RequestId> id = link_.Submit(*next);
  if (id.ok()) {
    accesses_.Sent(*id);
  } else {
    accesses_.SendRefused(id.status().code());
  }
}

void LinkScheduler::OnComplete(RequestId id, const Completion& completion) {
  if (id == own_request_) {
    const OwnJob job = own_job_;
    own_request_ = kNoRequestId;
    own_job_ = OwnJob{};
    own_.OnOwnComplete(job, completion, now_);
  } else {
    accesses_.OnComplete(id, completion);
  }
  Schedule(now_);
}

void LinkScheduler::OnLinkStateChanged(LinkState previous, LinkState current) {
  own_.OnLinkStateChanged(previous, current);
}

}  // namespace drive_link
