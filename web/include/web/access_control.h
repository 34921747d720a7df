// Sessions, levels, CSRF tokens and the password back-off of the JSON API (docs/web.md "Access"). The
// HTTP side asks this class and maps its answers to status codes; it holds no HTTP itself.
//
// - Login with the read password opens a read-level session: a random 128-bit session token (the
//   ipe_session cookie) and a separate random 128-bit CSRF token, both as 32 lowercase hex digits.
// - Elevate with the write password raises a session to write level.
// - A session unused for kSessionIdle (15 min) ends; write level drops back to read kWriteLevelHold
//   (10 min) after the elevation or the last change (NoteChange). Every call naming a session uses it.
// - At most kMaxSessions (8). A login when all are taken evicts the least recently used session: a
//   forgotten browser tab must not lock the owner out, and the oldest is the likeliest forgotten.
// - Failed password checks, login and elevate together and card-wide: after kFreeFailures (3) in a
//   row, each further attempt must wait 1 s, then 2, 4, ... up to 60 s after the previous failure.
//   Attempts during the wait are refused with the time left, without looking at the password (and do
//   not extend the wait); a success ends it.
//
// Time comes in as `now` (hal::Micros, monotonic); randomness from the hal::RandomSource.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>

#include "base/pool_stats.h"
#include "base/status.h"
#include "hal/clock.h"
#include "hal/random.h"
#include "web/password_store.h"

namespace web {

inline constexpr std::size_t kMaxSessions = 8;
inline constexpr std::size_t kTokenBytes = 16;
inline constexpr std::size_t kTokenHexChars = 2 * kTokenBytes;
inline constexpr hal::Micros kSessionIdle = 15 * 60 * hal::kMicrosPerSecond;
inline constexpr hal::Micros kWriteLevelHold = 10 * 60 * hal::kMicrosPerSecond;
inline constexpr std::uint32_t kFreeFailures = 3;
inline constexpr hal::Micros kFirstBackoff = 1 * hal::kMicrosPerSecond;
inline constexpr hal::Micros kMaxBackoff = 60 * hal::kMicrosPerSecond;

inline constexpr std::string_view kSessionCookieName = "ipe_session";

enum class AccessLevel : std::uint8_t { kNone, kRead, kWrite };

enum class AccessOutcome : std::uint8_t {
  kOk,
  kWrongPassword,  // 401 (a malformed password is just a wrong one)
  kBackoff,        // 429: refused unchecked, retry_after_ms says when
  kNoSession,      // 401: the session named does not exist (or no longer)
};

// 32 lowercase hex digits, no terminator.
struct Token {
  std::array<char, kTokenHexChars> hex{};
  std::string_view text() const { return {hex.data(), hex.size()}; }
};

struct LoginResult {
  AccessOutcome outcome = AccessOutcome::kWrongPassword;
  // kBackoff: the wait left; kWrongPassword: the wait this failure started (0 while failures are free).
  // Milliseconds, rounded up.
  std::uint32_t retry_after_ms = 0;
  AccessLevel level = AccessLevel::kNone;  // kOk: kRead
  Token session;                           // kOk only
  Token csrf;                              // kOk only
};

struct ElevateResult {
  AccessOutcome outcome = AccessOutcome::kWrongPassword;
  std::uint32_t retry_after_ms = 0;  // as LoginResult
};

class AccessControl {
 public:
  // `passwords` must have been loaded (PasswordStore::Load).
  AccessControl(PasswordStore& passwords, hal::RandomSource& random) : passwords_(passwords), random_(random) {}

  AccessControl(const AccessControl&) = delete;
  AccessControl& operator=(const AccessControl&) = delete;

  LoginResult Login(std::string_view password, hal::Micros now);
  // `session`: the cookie's value. kNoSession before any password check (nothing counted).
  ElevateResult Elevate(std::string_view session, std::string_view password, hal::Micros now);
  // False when there was no such session.
  bool Logout(std::string_view session, hal::Micros now);

  // The session's level (kNone: no valid session); the session counts as used.
  AccessLevel Lookup(std::string_view session, hal::Micros now);
  // A change was made: a write-level session keeps write level for another kWriteLevelHold. False
  // when the session is not at write level (nothing changes then).
  bool NoteChange(std::string_view session, hal::Micros now);
  // The X-CSRF-Token header against the session's token, in constant time. False without a session.
  bool CheckCsrf(std::string_view session, std::string_view header, hal::Micros now);

  // The caller has checked write level and CSRF. Refusals as PasswordStore::Set (kOutOfRange empty or
  // too long, kInvalidArgument not printable ASCII, the NV store's error). Sessions stay as they are.
  base::Status ChangePassword(PasswordKind which, std::string_view password) { return passwords_.Set(which, password); }

  // True while either password is still "USER" (GET /api/session "defaults").
  bool defaults() const { return passwords_.defaults(); }
  // Sessions not yet ended at `now` (for statistics and tests).
  std::size_t session_count(hal::Micros now) const;
  // The session table (docs/robustness.md "Exhaustion"): sessions not ended at `now`. Never refused: a
  // login into a full table evicts the least recently used session (counted in evictions()).
  base::PoolStats session_pool(hal::Micros now) const { return session_marks_.Stats(session_count(now), kMaxSessions); }
  std::uint32_t evictions() const { return evictions_; }

 private:
  struct Session {
    std::array<std::uint8_t, kTokenBytes> token{};
    std::array<std::uint8_t, kTokenBytes> csrf{};
    hal::Micros last_used = 0;
    hal::Micros write_since = 0;
    AccessLevel level = AccessLevel::kNone;  // kNone: the slot is free
  };

  // The live session named by `text`, used at `now` (ended or dropped to read as its times say).
  Session* Find(std::string_view text, hal::Micros now);
  Session& FreeOrOldestSlot();
  // The wait left (ms, rounded up) while a back-off is in force, else nothing.
  std::optional<std::uint32_t> BackoffLeft(hal::Micros now) const;
  // Counts a failure; the wait it starts in ms (0 while failures are free).
  std::uint32_t NoteFailure(hal::Micros now);
  Token NewToken(std::array<std::uint8_t, kTokenBytes>& bytes);

  PasswordStore& passwords_;
  hal::RandomSource& random_;
  std::array<Session, kMaxSessions> sessions_{};
  std::uint32_t failures_ = 0;  // in a row, login and elevate together
  hal::Micros retry_at_ = 0;    // with failures_ >= kFreeFailures: no check before this
  base::PoolWatermark session_marks_;
  std::uint32_t evictions_ = 0;
};

// The value of the ipe_session cookie in a Cookie header value ("a=1; ipe_session=...; b=2"), the first
// if there are several; nothing when absent. A value in double quotes (RFC 6265 §4.1.1) is returned
// without them. Reads only `header`.
std::optional<std::string_view> SessionCookie(std::string_view header);

// 32 lowercase hex digits to their 16 bytes; anything else (length, upper case, other characters): none.
std::optional<std::array<std::uint8_t, kTokenBytes>> ParseToken(std::string_view text);

}  // namespace web
