// firmware::FormatDiagnostic: lwIP's printf-style diagnostics without stdio. Each case is checked
// against the exact text, and against the C library's snprintf where both must agree.
#include "diag_format.h"

#include <gtest/gtest.h>

#include <array>
#include <cinttypes>
#include <cstdarg>
#include <cstdio>
#include <string>

namespace firmware {
namespace {

std::string Format(std::size_t capacity, const char* format, ...) {
  std::array<char, 256> buffer{};
  va_list args;
  va_start(args, format);
  const std::size_t length = FormatDiagnostic(std::span(buffer).first(capacity), format, args);
  va_end(args);
  return std::string(buffer.data(), length);
}

std::string Reference(const char* format, ...) {
  std::array<char, 256> buffer{};
  va_list args;
  va_start(args, format);
  const int length = std::vsnprintf(buffer.data(), buffer.size(), format, args);
  va_end(args);
  return std::string(buffer.data(), static_cast<std::size_t>(length));
}

TEST(LwipDiagFormat, IntegersLikeSnprintf) {
  EXPECT_EQ(Format(256, "a=%d b=%i c=%u", -42, 7, 4000000000U), "a=-42 b=7 c=4000000000");
  EXPECT_EQ(Format(256, "%5d|%-5d|%05d|%+d|% d", 42, 42, -42, 42, 42), "   42|42   |-0042|+42| 42");
  EXPECT_EQ(Format(256, "%x %X %#x %o %#o", 0xBEEFU, 0xBEEFU, 255U, 8U, 8U), "beef BEEF 0xff 10 010");
  EXPECT_EQ(Format(256, "%.3d|%.0d|%8.3d", 5, 0, -5), "005||    -005");
  EXPECT_EQ(Format(256, "%hhu %hu %ld %lld %zu", 300, 70000, -5L, -6LL, std::size_t{9}), "44 4464 -5 -6 9");
  for (const char* format : {"%d", "%5d", "%-5d|", "%05d", "%+d", "% d", "%.3d", "%8.3d"}) {
    EXPECT_EQ(Format(256, format, -123), Reference(format, -123)) << format;
    EXPECT_EQ(Format(256, format, 123), Reference(format, 123)) << format;
  }
}

TEST(LwipDiagFormat, LwipFormatMacros) {
  // What lwIP's U16_F, S32_F, X32_F, U32_F and SZT_F expand to on this host.
  EXPECT_EQ(Format(256, "%" PRIu16 " %" PRId32 " %08" PRIx32 " %" PRIu32 " %" PRIuPTR, std::uint16_t{65535},
                   std::int32_t{-2147483647 - 1}, std::uint32_t{0xABC}, std::uint32_t{4294967295U},
                   std::uintptr_t{12}),
            "65535 -2147483648 00000abc 4294967295 12");
}

TEST(LwipDiagFormat, TextAndCharacters) {
  EXPECT_EQ(Format(256, "[%s] [%6s] [%-6s] [%.2s] [%c] [%%]", "tcp", "tcp", "tcp", "tcp", 'x'),
            "[tcp] [   tcp] [tcp   ] [tc] [x] [%]");
  EXPECT_EQ(Format(256, "%s", static_cast<const char*>(nullptr)), "(null)");
  EXPECT_EQ(Format(256, "%*d|%-*d|%.*s", 4, 1, 3, 2, 1, "ab"), "   1|2  |a");
  // A precision bounds the read: the array has no terminator.
  const char unterminated[3] = {'a', 'b', 'c'};
  EXPECT_EQ(Format(256, "%.3s", unterminated), "abc");
}

TEST(LwipDiagFormat, UnknownConversionsAreCopiedWithoutTakingAnArgument) {
  EXPECT_EQ(Format(256, "%f %d", 7), "%f 7");
  EXPECT_EQ(Format(256, "end %"), "end %");
  EXPECT_EQ(Format(256, "end %5l"), "end %5l");
}

TEST(LwipDiagFormat, CutAtTheBufferEnd) {
  EXPECT_EQ(Format(8, "netif %s is up", "en0"), "netif en");
  EXPECT_EQ(Format(3, "%05d", 42), "000");
  EXPECT_EQ(Format(0, "anything %d", 1), "");
}

}  // namespace
}  // namespace firmware
