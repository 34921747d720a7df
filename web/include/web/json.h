// JSON for the web API (docs/web.md "JSON API"): a writer into a fixed buffer for answers, and a reader
// for request bodies, which in this API are always one flat object of strings, integers and booleans
// ({"number":"0009","value":100}). Anything richer in a request is refused (400): the reader is small
// enough to check by eye and cannot be walked into deep nesting.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>

namespace web {

// Writes compact JSON. Commas are placed by the writer; the caller only nests correctly. Strings are
// escaped ("\"", "\\", control characters as \u00XX); bytes >= 0x80 pass unchanged (the card's texts are
// ASCII). Past the end of the buffer the writer stops and overflowed() is set: the caller answers 500.
class JsonWriter {
 public:
  explicit JsonWriter(std::span<std::uint8_t> buffer) : buffer_(buffer) {}

  JsonWriter& BeginObject();
  JsonWriter& EndObject();
  JsonWriter& BeginArray();
  JsonWriter& EndArray();
  JsonWriter& Key(std::string_view key);
  JsonWriter& String(std::string_view text);
  JsonWriter& Number(std::int64_t value);
  JsonWriter& Bool(bool value);
  JsonWriter& Null();
  // A communication number as 4 upper-case hex digits ("C500").
  JsonWriter& Hex4(std::uint16_t value);

  std::size_t size() const { return used_; }
  bool overflowed() const { return overflow_; }

 private:
  void Separator();
  void Raw(std::string_view text);
  void RawChar(char c);

  std::span<std::uint8_t> buffer_;
  std::size_t used_ = 0;
  bool overflow_ = false;
  bool need_comma_ = false;  // a value was written at this level: the next one needs a comma
};

// One member of a flat request object. `text` is the string's raw contents (escapes not decoded); the
// API's strings (passwords, numbers, names) are checked by their users, and an escape in one is refused.
struct JsonMember {
  enum class Kind : std::uint8_t { kString, kInteger, kBool, kNull };
  std::string_view key;
  Kind kind = Kind::kNull;
  std::string_view text;
  std::int64_t integer = 0;
  bool boolean = false;
};

inline constexpr std::size_t kMaxJsonMembers = 8;
inline constexpr std::size_t kMaxJsonString = 64;

struct JsonObject {
  std::array<JsonMember, kMaxJsonMembers> members{};
  std::size_t count = 0;

  const JsonMember* Find(std::string_view key) const;
  // The member as that kind, or nothing (absent or of another kind).
  std::optional<std::string_view> StringOf(std::string_view key) const;
  std::optional<std::int64_t> IntegerOf(std::string_view key) const;
  std::optional<bool> BoolOf(std::string_view key) const;
};

// Parses `{ "key": value, ... }` with whitespace. Refused (false): nesting, fractions or exponents,
// integers beyond +-2^53, strings with escapes or longer than kMaxJsonString, control characters, more
// than kMaxJsonMembers members, a repeated key, anything after the closing brace but whitespace.
bool ParseFlatJsonObject(std::span<const std::uint8_t> input, JsonObject& object);

}  // namespace web
