#include "web/access_control.h"

#include <algorithm>

#include "web/sha256.h"

namespace web {
namespace {

constexpr char kHexDigits[] = "0123456789abcdef";

hal::Micros Elapsed(hal::Micros since, hal::Micros now) { return now > since ? now - since : 0; }

std::uint32_t CeilMillis(hal::Micros micros) {
  return static_cast<std::uint32_t>((micros + hal::kMicrosPerMilli - 1) / hal::kMicrosPerMilli);
}

// The wait after failure number `failures` (>= kFreeFailures): 1 s, doubling, capped at 60 s.
hal::Micros BackoffAfter(std::uint32_t failures) {
  const std::uint32_t doublings = failures - kFreeFailures;
  // 2^6 s is past the cap already; stopping there keeps the shift defined for any count.
  if (doublings >= 6) return kMaxBackoff;
  return std::min(kFirstBackoff << doublings, kMaxBackoff);
}

std::optional<std::uint8_t> HexValue(char c) {
  if (c >= '0' && c <= '9') return static_cast<std::uint8_t>(c - '0');
  if (c >= 'a' && c <= 'f') return static_cast<std::uint8_t>(c - 'a' + 10);
  return std::nullopt;
}

std::string_view TrimSpaces(std::string_view text) {
  while (!text.empty() && (text.front() == ' ' || text.front() == '\t')) text.remove_prefix(1);
  while (!text.empty() && (text.back() == ' ' || text.back() == '\t')) text.remove_suffix(1);
  return text;
}

}  // namespace

LoginResult AccessControl::Login(std::string_view password, hal::Micros now) {
  LoginResult result;
  if (const std::optional<std::uint32_t> left = BackoffLeft(now)) {
    result.outcome = AccessOutcome::kBackoff;
    result.retry_after_ms = *left;
    return result;
  }
  if (!passwords_.Verify(PasswordKind::kRead, password)) {
    result.outcome = AccessOutcome::kWrongPassword;
    result.retry_after_ms = NoteFailure(now);
    return result;
  }
  failures_ = 0;
  Session& session = FreeOrOldestSlot();
  if (session.level != AccessLevel::kNone && Elapsed(session.last_used, now) < kSessionIdle) ++evictions_;
  session = Session{};
  result.session = NewToken(session.token);
  result.csrf = NewToken(session.csrf);
  session.level = AccessLevel::kRead;
  session.last_used = now;
  session_marks_.NoteTaken(session_count(now));
  result.outcome = AccessOutcome::kOk;
  result.level = AccessLevel::kRead;
  return result;
}

ElevateResult AccessControl::Elevate(std::string_view session_text, std::string_view password, hal::Micros now) {
  ElevateResult result;
  Session* session = Find(session_text, now);
  if (session == nullptr) {
    result.outcome = AccessOutcome::kNoSession;
    return result;
  }
  if (const std::optional<std::uint32_t> left = BackoffLeft(now)) {
    result.outcome = AccessOutcome::kBackoff;
    result.retry_after_ms = *left;
    return result;
  }
  if (!passwords_.Verify(PasswordKind::kWrite, password)) {
    result.outcome = AccessOutcome::kWrongPassword;
    result.retry_after_ms = NoteFailure(now);
    return result;
  }
  failures_ = 0;
  session->level = AccessLevel::kWrite;
  session->write_since = now;
  result.outcome = AccessOutcome::kOk;
  return result;
}

bool AccessControl::Logout(std::string_view session_text, hal::Micros now) {
  Session* session = Find(session_text, now);
  if (session == nullptr) return false;
  *session = Session{};
  return true;
}

AccessLevel AccessControl::Lookup(std::string_view session_text, hal::Micros now) {
  const Session* session = Find(session_text, now);
  return session == nullptr ? AccessLevel::kNone : session->level;
}

bool AccessControl::NoteChange(std::string_view session_text, hal::Micros now) {
  Session* session = Find(session_text, now);
  if (session == nullptr || session->level != AccessLevel::kWrite) return false;
  session->write_since = now;
  return true;
}

bool AccessControl::CheckCsrf(std::string_view session_text, std::string_view header, hal::Micros now) {
  const Session* session = Find(session_text, now);
  if (session == nullptr) return false;
  const std::optional<std::array<std::uint8_t, kTokenBytes>> presented = ParseToken(header);
  if (!presented) return false;
  return ConstantTimeEqual(*presented, session->csrf);
}

std::size_t AccessControl::session_count(hal::Micros now) const {
  return static_cast<std::size_t>(std::count_if(sessions_.begin(), sessions_.end(), [now](const Session& session) {
    return session.level != AccessLevel::kNone && Elapsed(session.last_used, now) < kSessionIdle;
  }));
}

// Every slot is compared, in constant time, whatever matched before: how long the search takes says
// nothing about how close a guessed token came to a real one.
AccessControl::Session* AccessControl::Find(std::string_view text, hal::Micros now) {
  const std::optional<std::array<std::uint8_t, kTokenBytes>> token = ParseToken(text);
  if (!token) return nullptr;
  Session* found = nullptr;
  for (Session& session : sessions_) {
    const bool match = ConstantTimeEqual(*token, session.token);
    if (match && session.level != AccessLevel::kNone) found = &session;
  }
  if (found == nullptr) return nullptr;
  if (Elapsed(found->last_used, now) >= kSessionIdle) {
    *found = Session{};
    return nullptr;
  }
  if (found->level == AccessLevel::kWrite && Elapsed(found->write_since, now) >= kWriteLevelHold) {
    found->level = AccessLevel::kRead;
  }
  found->last_used = std::max(found->last_used, now);
  return found;
}

// Ended sessions (idle past kSessionIdle) are among the oldest, so they go before any live one.
AccessControl::Session& AccessControl::FreeOrOldestSlot() {
  Session* oldest = &sessions_[0];
  for (Session& session : sessions_) {
    if (session.level == AccessLevel::kNone) return session;
    if (session.last_used < oldest->last_used) oldest = &session;
  }
  return *oldest;
}

std::optional<std::uint32_t> AccessControl::BackoffLeft(hal::Micros now) const {
  if (failures_ < kFreeFailures || now >= retry_at_) return std::nullopt;
  return CeilMillis(retry_at_ - now);
}

std::uint32_t AccessControl::NoteFailure(hal::Micros now) {
  if (failures_ < UINT32_MAX) ++failures_;
  if (failures_ < kFreeFailures) return 0;
  const hal::Micros wait = BackoffAfter(failures_);
  retry_at_ = now + wait;
  return CeilMillis(wait);
}

Token AccessControl::NewToken(std::array<std::uint8_t, kTokenBytes>& bytes) {
  random_.Fill(bytes);
  Token token;
  for (std::size_t i = 0; i < bytes.size(); ++i) {
    token.hex[2 * i] = kHexDigits[bytes[i] >> 4];
    token.hex[2 * i + 1] = kHexDigits[bytes[i] & 0x0F];
  }
  return token;
}

std::optional<std::string_view> SessionCookie(std::string_view header) {
  while (!header.empty()) {
    const std::size_t end = header.find(';');
    const std::string_view pair = TrimSpaces(header.substr(0, end));
    const std::size_t equals = pair.find('=');
    if (equals != std::string_view::npos && TrimSpaces(pair.substr(0, equals)) == kSessionCookieName) {
      std::string_view value = TrimSpaces(pair.substr(equals + 1));
      if (value.size() >= 2 && value.front() == '"' && value.back() == '"') value = value.substr(1, value.size() - 2);
      return value;
    }
    if (end == std::string_view::npos) break;
    header.remove_prefix(end + 1);
  }
  return std::nullopt;
}

std::optional<std::array<std::uint8_t, kTokenBytes>> ParseToken(std::string_view text) {
  if (text.size() != kTokenHexChars) return std::nullopt;
  std::array<std::uint8_t, kTokenBytes> bytes{};
  for (std::size_t i = 0; i < bytes.size(); ++i) {
    const std::optional<std::uint8_t> high = HexValue(text[2 * i]);
    const std::optional<std::uint8_t> low = HexValue(text[2 * i + 1]);
    if (!high || !low) return std::nullopt;
    bytes[i] = static_cast<std::uint8_t>(*high << 4 | *low);
  }
  return bytes;
}

}  // namespace web
