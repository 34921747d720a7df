#include "diag_format.h"

#include <cstdint>
#include <string_view>

namespace firmware {
namespace {

class Output {
 public:
  explicit Output(std::span<char> out) : out_(out) {}
  void Put(char c) {
    if (length_ < out_.size()) out_[length_++] = c;
  }
  void Repeat(char c, std::size_t count) {
    for (std::size_t i = 0; i < count; ++i) Put(c);
  }
  std::size_t length() const { return length_; }

 private:
  std::span<char> out_;
  std::size_t length_ = 0;
};

enum class Length { kInt, kChar, kShort, kLong, kLongLong, kSize, kMax, kPtrdiff };

struct Spec {
  bool left = false;
  bool zero = false;
  bool plus = false;
  bool space = false;
  bool alternate = false;
  std::size_t width = 0;
  bool has_precision = false;
  std::size_t precision = 0;
  Length length = Length::kInt;
};

std::uintmax_t UnsignedArgument(Length length, std::va_list& args) {
  switch (length) {
    case Length::kChar: return static_cast<unsigned char>(va_arg(args, unsigned int));
    case Length::kShort: return static_cast<unsigned short>(va_arg(args, unsigned int));
    case Length::kLong: return va_arg(args, unsigned long);
    case Length::kLongLong: return va_arg(args, unsigned long long);
    case Length::kSize: return va_arg(args, std::size_t);
    case Length::kMax: return va_arg(args, std::uintmax_t);
    case Length::kPtrdiff: return static_cast<std::uintmax_t>(va_arg(args, std::ptrdiff_t));
    case Length::kInt: break;
  }
  return va_arg(args, unsigned int);
}

std::intmax_t SignedArgument(Length length, std::va_list& args) {
  switch (length) {
    case Length::kChar: return static_cast<signed char>(va_arg(args, int));
    case Length::kShort: return static_cast<short>(va_arg(args, int));
    case Length::kLong: return va_arg(args, long);
    case Length::kLongLong: return va_arg(args, long long);
    case Length::kSize: return static_cast<std::intmax_t>(va_arg(args, std::size_t));
    case Length::kMax: return va_arg(args, std::intmax_t);
    case Length::kPtrdiff: return va_arg(args, std::ptrdiff_t);
    case Length::kInt: break;
  }
  return va_arg(args, int);
}

// Digits of `value` in `base`, most significant first, into `digits`; returns how many.
std::size_t Digits(std::uintmax_t value, unsigned base, bool upper, char (&digits)[24]) {
  const char* symbols = upper ? "0123456789ABCDEF" : "0123456789abcdef";
  char reversed[24];
  std::size_t count = 0;
  do {
    reversed[count++] = symbols[value % base];
    value /= base;
  } while (value != 0);
  for (std::size_t i = 0; i < count; ++i) digits[i] = reversed[count - 1 - i];
  return count;
}

void PutNumber(Output& out, const Spec& spec, std::uintmax_t magnitude, bool negative, unsigned base, bool upper,
               std::string_view prefix) {
  char digits[24];
  std::size_t count = Digits(magnitude, base, upper, digits);
  // "%.0d" of zero prints no digits at all.
  if (spec.has_precision && spec.precision == 0 && magnitude == 0) count = 0;
  const std::size_t precision_zeros = spec.has_precision && spec.precision > count ? spec.precision - count : 0;
  const char sign = negative ? '-' : spec.plus ? '+' : spec.space ? ' ' : '\0';
  const std::size_t body = (sign != '\0' ? 1 : 0) + prefix.size() + precision_zeros + count;
  const std::size_t pad = spec.width > body ? spec.width - body : 0;
  const bool zero_pad = spec.zero && !spec.left && !spec.has_precision;
  if (!spec.left && !zero_pad) out.Repeat(' ', pad);
  if (sign != '\0') out.Put(sign);
  for (const char c : prefix) out.Put(c);
  if (zero_pad) out.Repeat('0', pad);
  out.Repeat('0', precision_zeros);
  for (std::size_t i = 0; i < count; ++i) out.Put(digits[i]);
  if (spec.left) out.Repeat(' ', pad);
}

void PutText(Output& out, const Spec& spec, std::string_view text) {
  if (spec.has_precision && text.size() > spec.precision) text = text.substr(0, spec.precision);
  const std::size_t pad = spec.width > text.size() ? spec.width - text.size() : 0;
  if (!spec.left) out.Repeat(' ', pad);
  for (const char c : text) out.Put(c);
  if (spec.left) out.Repeat(' ', pad);
}

std::size_t ReadNumber(const char*& p) {
  std::size_t value = 0;
  while (*p >= '0' && *p <= '9') {
    if (value < 100000) value = value * 10 + static_cast<std::size_t>(*p - '0');
    ++p;
  }
  return value;
}

Length ReadLength(const char*& p) {
  switch (*p) {
    case 'h':
      ++p;
      if (*p != 'h') return Length::kShort;
      ++p;
      return Length::kChar;
    case 'l':
      ++p;
      if (*p != 'l') return Length::kLong;
      ++p;
      return Length::kLongLong;
    case 'z':
      ++p;
      return Length::kSize;
    case 'j':
      ++p;
      return Length::kMax;
    case 't':
      ++p;
      return Length::kPtrdiff;
    default:
      return Length::kInt;
  }
}

}  // namespace

std::size_t FormatDiagnostic(std::span<char> out_buffer, const char* format, std::va_list args_in) {
  Output out(out_buffer);
  if (format == nullptr) return 0;
  std::va_list args;
  va_copy(args, args_in);
  const char* p = format;
  while (*p != '\0') {
    if (*p != '%') {
      out.Put(*p++);
      continue;
    }
    const char* start = p++;
    Spec spec;
    for (bool flag = true; flag;) {
      switch (*p) {
        case '-': spec.left = true; ++p; break;
        case '0': spec.zero = true; ++p; break;
        case '+': spec.plus = true; ++p; break;
        case ' ': spec.space = true; ++p; break;
        case '#': spec.alternate = true; ++p; break;
        default: flag = false; break;
      }
    }
    if (*p == '*') {
      const int width = va_arg(args, int);
      if (width < 0) spec.left = true;
      spec.width = static_cast<std::size_t>(width < 0 ? -static_cast<long>(width) : width);
      ++p;
    } else {
      spec.width = ReadNumber(p);
    }
    if (*p == '.') {
      ++p;
      spec.has_precision = true;
      if (*p == '*') {
        const int precision = va_arg(args, int);
        spec.has_precision = precision >= 0;
        spec.precision = precision >= 0 ? static_cast<std::size_t>(precision) : 0;
        ++p;
      } else {
        spec.precision = ReadNumber(p);
      }
    }
    spec.length = ReadLength(p);
    const char conversion = *p;
    if (conversion == '\0') {
      // A lone '%' (or an unfinished specification) at the end: copied as it stands.
      for (const char* c = start; c != p; ++c) out.Put(*c);
      break;
    }
    ++p;
    switch (conversion) {
      case 'd':
      case 'i': {
        const std::intmax_t value = SignedArgument(spec.length, args);
        const std::uintmax_t magnitude =
            value < 0 ? static_cast<std::uintmax_t>(-(value + 1)) + 1 : static_cast<std::uintmax_t>(value);
        PutNumber(out, spec, magnitude, value < 0, 10, false, {});
        break;
      }
      case 'u': PutNumber(out, spec, UnsignedArgument(spec.length, args), false, 10, false, {}); break;
      case 'o': {
        const std::uintmax_t value = UnsignedArgument(spec.length, args);
        PutNumber(out, spec, value, false, 8, false, spec.alternate && value != 0 ? "0" : "");
        break;
      }
      case 'x':
      case 'X': {
        const std::uintmax_t value = UnsignedArgument(spec.length, args);
        const bool upper = conversion == 'X';
        PutNumber(out, spec, value, false, 16, upper, spec.alternate && value != 0 ? (upper ? "0X" : "0x") : "");
        break;
      }
      case 'p': {
        const auto value = reinterpret_cast<std::uintptr_t>(va_arg(args, void*));
        PutNumber(out, spec, value, false, 16, false, "0x");
        break;
      }
      case 'c': {
        const char c = static_cast<char>(va_arg(args, int));
        PutText(out, spec, std::string_view(&c, 1));
        break;
      }
      case 's': {
        const char* text = va_arg(args, const char*);
        if (text == nullptr) text = "(null)";
        std::size_t length = 0;
        // Never reads past the precision: "%.4s" may be given an unterminated array.
        while ((!spec.has_precision || length < spec.precision) && text[length] != '\0') ++length;
        PutText(out, spec, std::string_view(text, length));
        break;
      }
      case '%': out.Put('%'); break;
      default:
        // Not a conversion this formatter knows (%f, %n): copied as it stands, no argument taken.
        for (const char* c = start; c != p; ++c) out.Put(*c);
        break;
    }
  }
  va_end(args);
  return out.length();
}

}  // namespace firmware
