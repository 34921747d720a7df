// libFuzzer target for the parsers in front of the web server's access control: the password NV record
// (web/password_store.h) and the session cookie and token (web/access_control.h). Every input goes
// through all three.
// Oracles: nothing is read outside the input (ASan); an accepted NV record is exactly kPasswordNvBytes
// long, its iteration counts are within the limits, and encoding it again gives the input byte for byte
// (the layout has one spelling per value); a cookie value lies inside the header and holds no ';'; a
// token that parses prints back as the same 32 lowercase hex digits.
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>

#include "web/access_control.h"
#include "web/password_store.h"

namespace {

void Require(bool condition) {
  if (!condition) __builtin_trap();
}

void CheckRecord(std::span<const std::uint8_t> input) {
  const base::Result<web::PasswordRecords> parsed = web::ParsePasswordRecords(input);
  if (!parsed.ok()) return;
  Require(input.size() == web::kPasswordNvBytes);
  for (const web::PasswordRecord& record : *parsed) {
    Require(record.iterations >= 1 && record.iterations <= web::kMaxPasswordIterations);
  }
  std::array<std::uint8_t, web::kPasswordNvBytes> again{};
  web::EncodePasswordRecords(*parsed, again);
  for (std::size_t i = 0; i < again.size(); ++i) Require(again[i] == input[i]);
}

void CheckToken(std::string_view text) {
  static constexpr char kDigits[] = "0123456789abcdef";
  const auto token = web::ParseToken(text);
  if (!token) return;
  Require(text.size() == web::kTokenHexChars);
  for (std::size_t i = 0; i < token->size(); ++i) {
    Require(text[2 * i] == kDigits[(*token)[i] >> 4] && text[2 * i + 1] == kDigits[(*token)[i] & 0x0F]);
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::span<const std::uint8_t> input(data, size);
  CheckRecord(input);
  const std::string_view header(reinterpret_cast<const char*>(data), size);
  CheckToken(header);
  const std::optional<std::string_view> cookie = web::SessionCookie(header);
  if (cookie) {
    Require(cookie->empty() || (cookie->data() >= header.data() &&
                                cookie->data() + cookie->size() <= header.data() + header.size()));
    Require(cookie->find(';') == std::string_view::npos);
    CheckToken(*cookie);
  }
  return 0;
}
