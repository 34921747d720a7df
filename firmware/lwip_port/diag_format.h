// printf-style formatting into a fixed buffer, for lwIP's LWIP_PLATFORM_DIAG messages, without the C
// library's stdio (on the board, newlib's vsnprintf would pull in malloc through its string streams).
//
// What it understands is what lwIP's format macros produce (lwip/arch.h: U16_F, S32_F, X32_F, SZT_F
// from <inttypes.h>): the conversions d i u x X o c s p %, the flags - 0 + space #, a field width and a
// precision (digits or *), and the length modifiers hh h l ll z j t. Anything else is copied as it
// stands. The output is cut at the buffer's end (never past it) and is not NUL-terminated.
#pragma once

#include <cstdarg>
#include <cstddef>
#include <span>

namespace firmware {

// Formats `format` with `args` into `out`; returns the number of characters written (<= out.size()).
std::size_t FormatDiagnostic(std::span<char> out, const char* format, std::va_list args);

}  // namespace firmware
