// Access to the JSON API (docs/web.md "Access"): login and exact tokens, levels and their timeouts at
// the exact boundaries, eviction of the least recently used session, CSRF, the card-wide back-off
// sequence 1/2/4/.../60 s, password changes, and the session cookie parser.
#include "web/access_control.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "web_fakes.h"

namespace web {
namespace {

using hal::kMicrosPerMilli;
using hal::kMicrosPerSecond;

constexpr hal::Micros kMinute = 60 * kMicrosPerSecond;
constexpr hal::Micros kStart = 1000 * kMicrosPerSecond;

// The hex of 16 counting bytes starting at `first` (what CountingRandom hands out).
std::string CountingHex(unsigned first) {
  static constexpr char kDigits[] = "0123456789abcdef";
  std::string text;
  for (unsigned i = 0; i < 16; ++i) {
    const unsigned byte = (first + i) & 0xFF;
    text += kDigits[byte >> 4];
    text += kDigits[byte & 0x0F];
  }
  return text;
}

class AccessControlTest : public ::testing::Test {
 protected:
  AccessControlTest() { EXPECT_TRUE(passwords_.Load().ok()); }  // salts 00..1f

  std::string LoginOk(hal::Micros now) {
    const LoginResult result = access_.Login("USER", now);
    EXPECT_EQ(result.outcome, AccessOutcome::kOk);
    return std::string(result.session.text());
  }

  test::CountingRandom random_;
  test::MemoryNvStore nv_;
  PasswordStore passwords_{nv_, 0x0020, random_};
  AccessControl access_{passwords_, random_};
};

TEST_F(AccessControlTest, LoginGivesRandomHexTokensAndReadLevel) {
  const LoginResult result = access_.Login("USER", kStart);
  ASSERT_EQ(result.outcome, AccessOutcome::kOk);
  EXPECT_EQ(result.level, AccessLevel::kRead);
  EXPECT_EQ(result.retry_after_ms, 0U);
  EXPECT_EQ(result.session.text(), "202122232425262728292a2b2c2d2e2f");
  EXPECT_EQ(result.csrf.text(), "303132333435363738393a3b3c3d3e3f");
  EXPECT_EQ(access_.Lookup(result.session.text(), kStart), AccessLevel::kRead);
  EXPECT_EQ(access_.session_count(kStart), 1U);
  const LoginResult second = access_.Login("USER", kStart);
  EXPECT_EQ(second.session.text(), CountingHex(0x40));
  EXPECT_EQ(second.csrf.text(), CountingHex(0x50));
  EXPECT_EQ(access_.session_count(kStart), 2U);
}

TEST_F(AccessControlTest, OnlyTheExactTokenFindsTheSession) {
  const std::string session = LoginOk(kStart);
  std::string upper = session;
  for (char& c : upper) c = static_cast<char>(c >= 'a' && c <= 'f' ? c - 'a' + 'A' : c);
  EXPECT_EQ(access_.Lookup(upper, kStart), AccessLevel::kNone);
  EXPECT_EQ(access_.Lookup(session.substr(0, 31), kStart), AccessLevel::kNone);
  EXPECT_EQ(access_.Lookup(session + "0", kStart), AccessLevel::kNone);
  EXPECT_EQ(access_.Lookup("", kStart), AccessLevel::kNone);
  EXPECT_EQ(access_.Lookup(std::string(32, '0'), kStart), AccessLevel::kNone);  // a free slot's bytes
  for (std::size_t i = 0; i < session.size(); ++i) {
    std::string other = session;
    other[i] = other[i] == '0' ? '1' : '0';
    EXPECT_EQ(access_.Lookup(other, kStart), AccessLevel::kNone) << i;
  }
  EXPECT_EQ(access_.Lookup(session, kStart), AccessLevel::kRead);
}

TEST_F(AccessControlTest, WrongPasswordsAreFreeThreeTimes) {
  const LoginResult first = access_.Login("user", kStart);
  EXPECT_EQ(first.outcome, AccessOutcome::kWrongPassword);
  EXPECT_EQ(first.retry_after_ms, 0U);
  EXPECT_EQ(first.session.text(), std::string(32, '\0'));
  EXPECT_EQ(access_.Login("", kStart).retry_after_ms, 0U);
  const LoginResult third = access_.Login(std::string(40, 'x'), kStart);
  EXPECT_EQ(third.outcome, AccessOutcome::kWrongPassword);
  EXPECT_EQ(third.retry_after_ms, 1000U);
  EXPECT_EQ(access_.session_count(kStart), 0U);
}

// Waits after failure 3, 4, 5, ...: 1, 2, 4, 8, 16, 32, then 60 s for good. One microsecond before the
// end of each wait an attempt is refused (even with the right password) and rounds up to 1 ms; at the
// end exactly the password is checked again.
TEST_F(AccessControlTest, BackoffSequenceAtItsExactBoundaries) {
  hal::Micros now = kStart;
  access_.Login("a", now);
  access_.Login("b", now);
  std::uint32_t wait_ms = access_.Login("c", now).retry_after_ms;
  const std::vector<std::uint32_t> expected = {1000, 2000, 4000, 8000, 16000, 32000, 60000, 60000, 60000};
  for (std::size_t i = 0; i < expected.size(); ++i) {
    ASSERT_EQ(wait_ms, expected[i]) << i;
    const LoginResult early = access_.Login("USER", now);
    EXPECT_EQ(early.outcome, AccessOutcome::kBackoff);
    EXPECT_EQ(early.retry_after_ms, expected[i]);
    const hal::Micros end = now + wait_ms * kMicrosPerMilli;
    const LoginResult almost = access_.Login("USER", end - 1);
    EXPECT_EQ(almost.outcome, AccessOutcome::kBackoff);
    EXPECT_EQ(almost.retry_after_ms, 1U);
    EXPECT_EQ(access_.Login("USER", end - 1001).retry_after_ms, 2U);
    now = end;
    const LoginResult checked = access_.Login("wrong", now);
    EXPECT_EQ(checked.outcome, AccessOutcome::kWrongPassword);
    wait_ms = checked.retry_after_ms;
  }
  EXPECT_EQ(wait_ms, 60000U);
  EXPECT_EQ(access_.session_count(now), 0U);
}

TEST_F(AccessControlTest, RefusedAttemptsDoNotExtendTheWaitAndASuccessResets) {
  for (int i = 0; i < 4; ++i) access_.Login("nope", kStart);  // 3rd: 1 s, 4th refused
  for (hal::Micros t = kStart; t < kStart + kMicrosPerSecond; t += 100 * kMicrosPerMilli) {
    EXPECT_EQ(access_.Login("nope", t).outcome, AccessOutcome::kBackoff);
  }
  const hal::Micros end = kStart + kMicrosPerSecond;
  EXPECT_EQ(access_.Login("USER", end).outcome, AccessOutcome::kOk);
  // Three free failures again.
  EXPECT_EQ(access_.Login("x", end).retry_after_ms, 0U);
  EXPECT_EQ(access_.Login("x", end).retry_after_ms, 0U);
  EXPECT_EQ(access_.Login("x", end).retry_after_ms, 1000U);
}

TEST_F(AccessControlTest, LoginAndElevateFailuresCountTogether) {
  const std::string session = LoginOk(kStart);
  EXPECT_EQ(access_.Login("x", kStart).retry_after_ms, 0U);
  EXPECT_EQ(access_.Elevate(session, "y", kStart).retry_after_ms, 0U);
  const ElevateResult third = access_.Elevate(session, "z", kStart);
  EXPECT_EQ(third.outcome, AccessOutcome::kWrongPassword);
  EXPECT_EQ(third.retry_after_ms, 1000U);
  const LoginResult refused = access_.Login("USER", kStart + 500 * kMicrosPerMilli);
  EXPECT_EQ(refused.outcome, AccessOutcome::kBackoff);
  EXPECT_EQ(refused.retry_after_ms, 500U);
  const ElevateResult also = access_.Elevate(session, "USER", kStart + 999 * kMicrosPerMilli);
  EXPECT_EQ(also.outcome, AccessOutcome::kBackoff);
  EXPECT_EQ(also.retry_after_ms, 1U);
  EXPECT_EQ(access_.Lookup(session, kStart + kMicrosPerSecond), AccessLevel::kRead);
  EXPECT_EQ(access_.Elevate(session, "USER", kStart + kMicrosPerSecond).outcome, AccessOutcome::kOk);
  EXPECT_EQ(access_.Login("x", kStart + kMicrosPerSecond).retry_after_ms, 0U);
}

TEST_F(AccessControlTest, ElevateWithoutSessionIsNotAPasswordCheck) {
  for (int i = 0; i < 5; ++i) {
    EXPECT_EQ(access_.Elevate(CountingHex(0x20), "wrong", kStart).outcome, AccessOutcome::kNoSession);
    EXPECT_EQ(access_.Elevate("", "USER", kStart).outcome, AccessOutcome::kNoSession);
  }
  EXPECT_EQ(access_.Login("x", kStart).retry_after_ms, 0U);
  EXPECT_EQ(access_.Login("x", kStart).retry_after_ms, 0U);
}

TEST_F(AccessControlTest, ElevateNeedsTheWritePassword) {
  ASSERT_TRUE(access_.ChangePassword(PasswordKind::kWrite, "change it").ok());
  const std::string session = LoginOk(kStart);
  EXPECT_EQ(access_.Elevate(session, "USER", kStart).outcome, AccessOutcome::kWrongPassword);
  EXPECT_EQ(access_.Lookup(session, kStart), AccessLevel::kRead);
  const ElevateResult result = access_.Elevate(session, "change it", kStart);
  EXPECT_EQ(result.outcome, AccessOutcome::kOk);
  EXPECT_EQ(result.retry_after_ms, 0U);
  EXPECT_EQ(access_.Lookup(session, kStart), AccessLevel::kWrite);
  EXPECT_EQ(access_.Login("change it", kStart).outcome, AccessOutcome::kWrongPassword);  // not the read one
}

TEST_F(AccessControlTest, WriteLevelDropsTenMinutesAfterTheLastChange) {
  const std::string session = LoginOk(kStart);
  EXPECT_FALSE(access_.NoteChange(session, kStart));  // read level: nothing to hold
  ASSERT_EQ(access_.Elevate(session, "USER", kStart).outcome, AccessOutcome::kOk);
  EXPECT_EQ(access_.Lookup(session, kStart + 10 * kMinute - 1), AccessLevel::kWrite);
  EXPECT_EQ(access_.Lookup(session, kStart + 10 * kMinute), AccessLevel::kRead);

  const std::string other = LoginOk(kStart);
  ASSERT_EQ(access_.Elevate(other, "USER", kStart).outcome, AccessOutcome::kOk);
  EXPECT_TRUE(access_.NoteChange(other, kStart + 6 * kMinute));
  EXPECT_EQ(access_.Lookup(other, kStart + 16 * kMinute - 1), AccessLevel::kWrite);
  EXPECT_EQ(access_.Lookup(other, kStart + 16 * kMinute), AccessLevel::kRead);
  EXPECT_FALSE(access_.NoteChange(other, kStart + 16 * kMinute));
}

TEST_F(AccessControlTest, SessionEndsAfterFifteenIdleMinutes) {
  const std::string idle = LoginOk(kStart);
  const std::string used = LoginOk(kStart);
  EXPECT_EQ(access_.Lookup(used, kStart + 15 * kMinute - 1), AccessLevel::kRead);
  EXPECT_EQ(access_.session_count(kStart + 15 * kMinute - 1), 2U);
  EXPECT_EQ(access_.session_count(kStart + 15 * kMinute), 1U);
  EXPECT_EQ(access_.Lookup(idle, kStart + 15 * kMinute), AccessLevel::kNone);
  EXPECT_EQ(access_.Lookup(idle, kStart + 15 * kMinute - 1), AccessLevel::kNone);  // gone for good
  // Each use starts the 15 minutes again.
  EXPECT_EQ(access_.Lookup(used, kStart + 30 * kMinute - 2), AccessLevel::kRead);
  EXPECT_EQ(access_.Lookup(used, kStart + 45 * kMinute - 2), AccessLevel::kNone);
}

TEST_F(AccessControlTest, WriteSessionEndsWhenIdleToo) {
  const std::string session = LoginOk(kStart);
  ASSERT_EQ(access_.Elevate(session, "USER", kStart).outcome, AccessOutcome::kOk);
  EXPECT_EQ(access_.Lookup(session, kStart + 15 * kMinute), AccessLevel::kNone);
  EXPECT_FALSE(access_.NoteChange(session, kStart + 15 * kMinute));
}

TEST_F(AccessControlTest, NinthLoginEvictsTheLeastRecentlyUsed) {
  std::vector<std::string> sessions;
  for (std::size_t i = 0; i < kMaxSessions; ++i) sessions.push_back(LoginOk(kStart + i * kMicrosPerSecond));
  EXPECT_EQ(access_.session_count(kStart + 8 * kMicrosPerSecond), 8U);
  // The first is used again: the second is now the oldest.
  EXPECT_EQ(access_.Lookup(sessions[0], kStart + 8 * kMicrosPerSecond), AccessLevel::kRead);
  const std::string ninth = LoginOk(kStart + 9 * kMicrosPerSecond);
  hal::Micros now = kStart + 10 * kMicrosPerSecond;
  EXPECT_EQ(access_.Lookup(sessions[1], now), AccessLevel::kNone);
  EXPECT_EQ(access_.Lookup(sessions[0], ++now), AccessLevel::kRead);
  for (std::size_t i = 2; i < kMaxSessions; ++i) EXPECT_EQ(access_.Lookup(sessions[i], ++now), AccessLevel::kRead) << i;
  EXPECT_EQ(access_.Lookup(ninth, ++now), AccessLevel::kRead);
  EXPECT_EQ(access_.session_count(now), 8U);
  // Used in the order 0, 2..7, ninth: the next login takes the place of sessions[0].
  const std::string tenth = LoginOk(++now);
  EXPECT_EQ(access_.Lookup(sessions[0], ++now), AccessLevel::kNone);
  EXPECT_EQ(access_.Lookup(sessions[2], now), AccessLevel::kRead);
  EXPECT_EQ(access_.Lookup(tenth, now), AccessLevel::kRead);
  // Evicting is not refusing: a login always gets a session.
  EXPECT_EQ(access_.evictions(), 2U);
  EXPECT_EQ(access_.session_pool(now), (base::PoolStats{kMaxSessions, kMaxSessions, kMaxSessions, 0}));
  // Fifteen idle minutes later every slot is free again.
  EXPECT_EQ(access_.session_pool(now + kSessionIdle), (base::PoolStats{0, kMaxSessions, kMaxSessions, 0}));
}

TEST_F(AccessControlTest, ALoggedOutSlotIsReusedBeforeEvicting) {
  std::vector<std::string> sessions;
  for (std::size_t i = 0; i < kMaxSessions; ++i) sessions.push_back(LoginOk(kStart + i));
  EXPECT_TRUE(access_.Logout(sessions[5], kStart + 10));
  EXPECT_FALSE(access_.Logout(sessions[5], kStart + 10));
  EXPECT_EQ(access_.Lookup(sessions[5], kStart + 10), AccessLevel::kNone);
  EXPECT_EQ(access_.session_count(kStart + 10), 7U);
  LoginOk(kStart + 11);
  for (std::size_t i = 0; i < kMaxSessions; ++i) {
    const AccessLevel expected = i == 5 ? AccessLevel::kNone : AccessLevel::kRead;
    EXPECT_EQ(access_.Lookup(sessions[i], kStart + 12), expected) << i;
  }
  EXPECT_EQ(access_.session_count(kStart + 12), 8U);
  EXPECT_EQ(access_.evictions(), 0U);  // the logged-out slot was free
}

TEST_F(AccessControlTest, CsrfTokenBelongsToItsSession) {
  const LoginResult first = access_.Login("USER", kStart);
  const LoginResult second = access_.Login("USER", kStart);
  const std::string_view session = first.session.text();
  EXPECT_TRUE(access_.CheckCsrf(session, first.csrf.text(), kStart));
  EXPECT_FALSE(access_.CheckCsrf(session, second.csrf.text(), kStart));
  EXPECT_FALSE(access_.CheckCsrf(session, session, kStart));
  EXPECT_FALSE(access_.CheckCsrf(session, "", kStart));
  EXPECT_FALSE(access_.CheckCsrf(session, "303132333435363738393A3B3C3D3E3F", kStart));  // upper case
  std::string changed(first.csrf.text());
  changed.back() = 'e';
  EXPECT_FALSE(access_.CheckCsrf(session, changed, kStart));
  EXPECT_FALSE(access_.CheckCsrf(first.csrf.text(), first.csrf.text(), kStart));  // no such session
  EXPECT_FALSE(access_.CheckCsrf(session, first.csrf.text(), kStart + 15 * kMinute));  // session ended
}

TEST_F(AccessControlTest, PasswordChangesAndDefaults) {
  EXPECT_TRUE(access_.defaults());
  EXPECT_EQ(access_.ChangePassword(PasswordKind::kRead, ""), base::OutOfRange());
  EXPECT_EQ(access_.ChangePassword(PasswordKind::kRead, std::string(33, 'p')), base::OutOfRange());
  EXPECT_EQ(access_.ChangePassword(PasswordKind::kRead, "\x01"), base::InvalidArgument());
  const std::string session = LoginOk(kStart);
  ASSERT_TRUE(access_.ChangePassword(PasswordKind::kRead, std::string(32, 'p')).ok());
  EXPECT_TRUE(access_.defaults());
  ASSERT_TRUE(access_.ChangePassword(PasswordKind::kWrite, "w").ok());
  EXPECT_FALSE(access_.defaults());
  EXPECT_EQ(access_.Lookup(session, kStart), AccessLevel::kRead);  // sessions stay
  EXPECT_EQ(access_.Login("USER", kStart).outcome, AccessOutcome::kWrongPassword);
  EXPECT_EQ(access_.Login(std::string(32, 'p'), kStart).outcome, AccessOutcome::kOk);
}

TEST(SessionCookieTest, FindsTheCookieAmongOthers) {
  EXPECT_EQ(SessionCookie("ipe_session=abc"), std::optional<std::string_view>("abc"));
  EXPECT_EQ(SessionCookie("a=1; ipe_session=abc; b=2"), std::optional<std::string_view>("abc"));
  EXPECT_EQ(SessionCookie("a=1;ipe_session=abc"), std::optional<std::string_view>("abc"));
  EXPECT_EQ(SessionCookie("  ipe_session = abc  ;"), std::optional<std::string_view>("abc"));
  EXPECT_EQ(SessionCookie("ipe_session=\"abc\""), std::optional<std::string_view>("abc"));
  EXPECT_EQ(SessionCookie("ipe_session=\""), std::optional<std::string_view>("\""));
  EXPECT_EQ(SessionCookie("ipe_session=a=b"), std::optional<std::string_view>("a=b"));
  EXPECT_EQ(SessionCookie("ipe_session="), std::optional<std::string_view>(""));
  EXPECT_EQ(SessionCookie("ipe_session=first; ipe_session=second"), std::optional<std::string_view>("first"));
  EXPECT_EQ(SessionCookie("x=ipe_session=1; ipe_session=2"), std::optional<std::string_view>("2"));
}

TEST(SessionCookieTest, AbsentOrOtherNames) {
  EXPECT_FALSE(SessionCookie(""));
  EXPECT_FALSE(SessionCookie(";;; ;"));
  EXPECT_FALSE(SessionCookie("ipe_session"));
  EXPECT_FALSE(SessionCookie("ipe_sessions=1"));
  EXPECT_FALSE(SessionCookie("xipe_session=1"));
  EXPECT_FALSE(SessionCookie("IPE_SESSION=1"));
  EXPECT_FALSE(SessionCookie("a=1; b=2"));
}

TEST(SessionTokenTest, OnlyThirtyTwoLowercaseHexDigits) {
  const auto bytes = ParseToken("00ff10a0b1c2d3e4f5a6b7c8d9eafb0c");
  ASSERT_TRUE(bytes);
  EXPECT_EQ((*bytes)[0], 0x00);
  EXPECT_EQ((*bytes)[1], 0xff);
  EXPECT_EQ((*bytes)[15], 0x0c);
  EXPECT_FALSE(ParseToken("00ff10a0b1c2d3e4f5a6b7c8d9eafb0"));
  EXPECT_FALSE(ParseToken("00ff10a0b1c2d3e4f5a6b7c8d9eafb0c0"));
  EXPECT_FALSE(ParseToken("00FF10a0b1c2d3e4f5a6b7c8d9eafb0c"));
  EXPECT_FALSE(ParseToken("00ff10a0b1c2d3e4f5a6b7c8d9eafb0g"));
  EXPECT_FALSE(ParseToken(std::string_view("00ff10a0b1c2d3e4f5a6b7c8d9eafb\0c", 32)));
}

}  // namespace
}  // namespace web
