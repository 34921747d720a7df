#include "web_drive_access.h"

#include <algorithm>

#include "drive_link/drive_registers.h"

namespace firmware {

const std::array<std::uint16_t, kMonitorRegisterCount> kMonitorRegisters = {
    drive_link::reg::kFd00, drive_link::reg::kFd01, drive_link::reg::kFe02, 0xFE03, 0xFE05,
    0xFE18, drive_link::reg::kFc90, drive_link::reg::kFc91, 0xFE06, 0xFE07};

// --- WebDriveMonitor -----------------------------------------------------------------------------------

void WebDriveMonitor::Poll(hal::Micros now) {
  last_poll_ = now;
  if (in_flight_ != drive_link::kNoAccess) return;
  if (index_ < kMonitorRegisterCount) {
    if (now >= retry_at_) StartNext(now);
    return;
  }
  if (now < interest_until_ && now >= next_round_) {
    next_round_ = now + kMonitorPeriod;
    index_ = 0;
    StartNext(now);
  }
}

hal::Micros WebDriveMonitor::NextDeadline() const {
  if (in_flight_ != drive_link::kNoAccess) return hal::kNever;
  if (index_ < kMonitorRegisterCount) return retry_at_;
  if (interest_until_ <= next_round_) return hal::kNever;
  return next_round_;
}

void WebDriveMonitor::StartNext(hal::Micros now) {
  while (index_ < kMonitorRegisterCount) {
    const base::Result<drive_link::AccessToken> token = registers_.Read(kMonitorRegisters[index_], *this);
    if (token.ok()) {
      in_flight_ = *token;
      retry_at_ = hal::kNever;
      return;
    }
    if (token.status().code() == base::StatusCode::kResourceExhausted) {
      retry_at_ = now + kPoolRetry;
      return;
    }
    // The link is down: nothing to read this round; the values stay as last known.
    index_ = kMonitorRegisterCount;
  }
}

void WebDriveMonitor::OnAccessDone(drive_link::AccessToken token, const drive_link::AccessResult& result) {
  if (token != in_flight_ || index_ >= kMonitorRegisterCount) return;
  in_flight_ = drive_link::kNoAccess;
  if (result.ok()) {
    values_[index_] = result.value;
    known_[index_] = true;
  }
  ++index_;
  retry_at_ = 0;  // the next read starts on the next Poll
  if (index_ == kMonitorRegisterCount) {
    retry_at_ = hal::kNever;
    round_completed_ = last_poll_;  // completions arrive within the loop pass after our last Poll
  }
}

// --- WebRegisterJobs -----------------------------------------------------------------------------------

void WebRegisterJobs::StartReads(web::HttpClientId client, std::span<const std::uint16_t> numbers, hal::Micros now) {
  Job& job = jobs_[client];
  job = Job{};
  job.kind = Kind::kRead;
  job.count = std::min(numbers.size(), kMaxRegistersPerRequest);
  for (std::size_t i = 0; i < job.count; ++i) job.items[i].number = numbers[i];
  StartNext(job, now);
}

void WebRegisterJobs::StartWrite(web::HttpClientId client, std::uint16_t number, std::uint16_t value,
                                 drive_link::WriteMode mode, hal::Micros now) {
  Job& job = jobs_[client];
  job = Job{};
  job.kind = Kind::kWrite;
  job.count = 1;
  job.items[0].number = number;
  job.write_value = value;
  job.mode = mode;
  StartNext(job, now);
}

bool WebRegisterJobs::done(web::HttpClientId client) const {
  const Job& job = jobs_[client];
  return job.kind != Kind::kNone && job.completed == job.count;
}

std::span<const RegisterJobResult> WebRegisterJobs::results(web::HttpClientId client) const {
  const Job& job = jobs_[client];
  return std::span<const RegisterJobResult>(job.items.data(), job.completed);
}

void WebRegisterJobs::Finish(web::HttpClientId client) { jobs_[client] = Job{}; }

void WebRegisterJobs::Poll(hal::Micros now) {
  for (Job& job : jobs_) {
    if (job.kind != Kind::kNone && job.in_flight == drive_link::kNoAccess && job.completed < job.count &&
        now >= job.retry_at) {
      StartNext(job, now);
    }
  }
}

hal::Micros WebRegisterJobs::NextDeadline() const {
  hal::Micros next = hal::kNever;
  for (const Job& job : jobs_) {
    if (job.kind == Kind::kNone || job.in_flight != drive_link::kNoAccess) continue;
    // Done: the handler must answer now. Waiting for a pool slot: at retry_at.
    next = std::min(next, job.completed == job.count ? 0 : job.retry_at);
  }
  return next;
}

void WebRegisterJobs::StartNext(Job& job, hal::Micros now) {
  while (job.completed < job.count) {
    RegisterJobResult& item = job.items[job.completed];
    const base::Result<drive_link::AccessToken> token =
        job.kind == Kind::kWrite ? registers_.Write(item.number, job.write_value, job.mode, *this)
                                 : registers_.Read(item.number, *this);
    if (token.ok()) {
      job.in_flight = *token;
      return;
    }
    if (token.status().code() == base::StatusCode::kResourceExhausted) {
      job.retry_at = now + kPoolRetry;
      return;
    }
    // The drive link is down: this access fails at once, the others will too.
    item.result = drive_link::AccessResult{drive_link::AccessError::kLinkDown, item.number, 0};
    ++job.completed;
  }
}

void WebRegisterJobs::OnAccessDone(drive_link::AccessToken token, const drive_link::AccessResult& result) {
  for (Job& job : jobs_) {
    if (job.kind == Kind::kNone || job.in_flight != token) continue;
    job.in_flight = drive_link::kNoAccess;
    job.items[job.completed].result = result;
    ++job.completed;
    job.retry_at = 0;  // the next access starts on the next Poll
    return;
  }
}

}  // namespace firmware
