// What the web API reads and writes of the drive, over the register proxy's on-demand accesses
// (docs/web.md "Drive access"):
//
// - WebDriveMonitor: the drive monitor's registers, read in a round every kMonitorPeriod while a client
//   asked for them within kMonitorInterest (nobody watching: no traffic on the serial link). One access
//   at a time, so the page never takes more than one slot of the proxy's pool.
// - WebRegisterJobs: one job per HTTP connection: a list of up to kMaxRegistersPerRequest reads, or one
//   write, run one access at a time; a job refused by a full pool is retried after kPoolRetry.
//
// Device-path code: fixed arrays, no allocation. Completions come from the proxy's Poll.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "drive_link/register_access.h"
#include "hal/clock.h"
#include "web/http_server.h"

namespace firmware {

inline constexpr std::size_t kMonitorRegisterCount = 10;
// FD00 output frequency, FD01 status, FE02 frequency command, FE03 current, FE05 voltage, FE18 torque,
// FC90 trip, FC91 alarms, FE06/FE07 terminals.
extern const std::array<std::uint16_t, kMonitorRegisterCount> kMonitorRegisters;

inline constexpr hal::Micros kMonitorPeriod = 250 * hal::kMicrosPerMilli;
inline constexpr hal::Micros kMonitorInterest = 5 * hal::kMicrosPerSecond;
inline constexpr std::size_t kMaxRegistersPerRequest = 32;
inline constexpr hal::Micros kPoolRetry = 5 * hal::kMicrosPerMilli;

class WebDriveMonitor final : private drive_link::AccessListener {
 public:
  explicit WebDriveMonitor(drive_link::DriveRegisters& registers) : registers_(registers) {}
  ~WebDriveMonitor() override { registers_.Cancel(*this); }
  WebDriveMonitor(const WebDriveMonitor&) = delete;
  WebDriveMonitor& operator=(const WebDriveMonitor&) = delete;

  // A client looked at the values: keep them fresh for kMonitorInterest.
  void NoteInterest(hal::Micros now) { interest_until_ = now + kMonitorInterest; }
  void Poll(hal::Micros now);
  hal::Micros NextDeadline() const;

  // The newest value of kMonitorRegisters[i], and whether it was ever read.
  std::uint16_t value(std::size_t i) const { return values_[i]; }
  bool known(std::size_t i) const { return known_[i]; }
  // When the last complete round ended (0: none yet).
  hal::Micros round_completed() const { return round_completed_; }

 private:
  void OnAccessDone(drive_link::AccessToken token, const drive_link::AccessResult& result) override;
  void StartNext(hal::Micros now);

  drive_link::DriveRegisters& registers_;
  std::array<std::uint16_t, kMonitorRegisterCount> values_{};
  std::array<bool, kMonitorRegisterCount> known_{};
  hal::Micros interest_until_ = 0;
  hal::Micros next_round_ = 0;
  hal::Micros retry_at_ = hal::kNever;
  hal::Micros round_completed_ = 0;
  hal::Micros last_poll_ = 0;
  std::size_t index_ = kMonitorRegisterCount;  // the register being read; kMonitorRegisterCount: idle
  drive_link::AccessToken in_flight_ = drive_link::kNoAccess;
};

struct RegisterJobResult {
  std::uint16_t number = 0;
  drive_link::AccessResult result;
};

class WebRegisterJobs final : private drive_link::AccessListener {
 public:
  explicit WebRegisterJobs(drive_link::DriveRegisters& registers) : registers_(registers) {}
  ~WebRegisterJobs() override { registers_.Cancel(*this); }
  WebRegisterJobs(const WebRegisterJobs&) = delete;
  WebRegisterJobs& operator=(const WebRegisterJobs&) = delete;

  // Starts a job for `client` (replacing any job it had). Reads: 1..kMaxRegistersPerRequest numbers.
  void StartReads(web::HttpClientId client, std::span<const std::uint16_t> numbers, hal::Micros now);
  void StartWrite(web::HttpClientId client, std::uint16_t number, std::uint16_t value, drive_link::WriteMode mode,
                  hal::Micros now);
  bool active(web::HttpClientId client) const { return jobs_[client].kind != Kind::kNone; }
  // Every access of the client's job has completed.
  bool done(web::HttpClientId client) const;
  std::span<const RegisterJobResult> results(web::HttpClientId client) const;
  // Forgets the job (answered, or the connection closed); a completion still on its way is ignored.
  void Finish(web::HttpClientId client);

  void Poll(hal::Micros now);
  hal::Micros NextDeadline() const;

 private:
  enum class Kind : std::uint8_t { kNone, kRead, kWrite };
  struct Job {
    Kind kind = Kind::kNone;
    std::array<RegisterJobResult, kMaxRegistersPerRequest> items{};
    std::size_t count = 0;
    std::size_t completed = 0;
    std::uint16_t write_value = 0;
    drive_link::WriteMode mode = drive_link::WriteMode::kRamAndEeprom;
    drive_link::AccessToken in_flight = drive_link::kNoAccess;
    hal::Micros retry_at = 0;  // when the next access may be started (pool full: a little later)
  };

  void OnAccessDone(drive_link::AccessToken token, const drive_link::AccessResult& result) override;
  void StartNext(Job& job, hal::Micros now);

  drive_link::DriveRegisters& registers_;
  std::array<Job, web::kMaxHttpClients> jobs_{};
};

}  // namespace firmware
