#include "web/json.h"

#include <cstring>

namespace web {

// --- Writer -------------------------------------------------------------------------------------------

void JsonWriter::RawChar(char c) {
  if (overflow_) return;
  if (used_ == buffer_.size()) {
    overflow_ = true;
    return;
  }
  buffer_[used_++] = static_cast<std::uint8_t>(c);
}

void JsonWriter::Raw(std::string_view text) {
  for (char c : text) RawChar(c);
}

void JsonWriter::Separator() {
  if (need_comma_) RawChar(',');
  need_comma_ = true;
}

JsonWriter& JsonWriter::BeginObject() {
  Separator();
  RawChar('{');
  need_comma_ = false;
  return *this;
}

JsonWriter& JsonWriter::EndObject() {
  RawChar('}');
  need_comma_ = true;
  return *this;
}

JsonWriter& JsonWriter::BeginArray() {
  Separator();
  RawChar('[');
  need_comma_ = false;
  return *this;
}

JsonWriter& JsonWriter::EndArray() {
  RawChar(']');
  need_comma_ = true;
  return *this;
}

JsonWriter& JsonWriter::Key(std::string_view key) {
  String(key);
  RawChar(':');
  need_comma_ = false;
  return *this;
}

JsonWriter& JsonWriter::String(std::string_view text) {
  static constexpr char kHex[] = "0123456789abcdef";
  Separator();
  RawChar('"');
  for (char c : text) {
    const auto byte = static_cast<unsigned char>(c);
    if (c == '"' || c == '\\') {
      RawChar('\\');
      RawChar(c);
    } else if (byte < 0x20) {
      Raw("\\u00");
      RawChar(kHex[byte >> 4]);
      RawChar(kHex[byte & 0xF]);
    } else {
      RawChar(c);
    }
  }
  RawChar('"');
  return *this;
}

JsonWriter& JsonWriter::Number(std::int64_t value) {
  Separator();
  char digits[20];
  std::size_t count = 0;
  // Negate through unsigned: the most negative value has no positive counterpart.
  std::uint64_t magnitude = value < 0 ? 0 - static_cast<std::uint64_t>(value) : static_cast<std::uint64_t>(value);
  do {
    digits[count++] = static_cast<char>('0' + magnitude % 10);
    magnitude /= 10;
  } while (magnitude != 0);
  if (value < 0) RawChar('-');
  while (count > 0) RawChar(digits[--count]);
  return *this;
}

JsonWriter& JsonWriter::Bool(bool value) {
  Separator();
  Raw(value ? "true" : "false");
  return *this;
}

JsonWriter& JsonWriter::Null() {
  Separator();
  Raw("null");
  return *this;
}

JsonWriter& JsonWriter::Hex4(std::uint16_t value) {
  static constexpr char kHex[] = "0123456789ABCDEF";
  const char text[4] = {kHex[value >> 12], kHex[(value >> 8) & 0xF], kHex[(value >> 4) & 0xF], kHex[value & 0xF]};
  return String(std::string_view(text, 4));
}

// --- Reader -------------------------------------------------------------------------------------------

const JsonMember* JsonObject::Find(std::string_view key) const {
  for (std::size_t i = 0; i < count; ++i) {
    if (members[i].key == key) return &members[i];
  }
  return nullptr;
}

std::optional<std::string_view> JsonObject::StringOf(std::string_view key) const {
  const JsonMember* m = Find(key);
  if (m == nullptr || m->kind != JsonMember::Kind::kString) return std::nullopt;
  return m->text;
}

std::optional<std::int64_t> JsonObject::IntegerOf(std::string_view key) const {
  const JsonMember* m = Find(key);
  if (m == nullptr || m->kind != JsonMember::Kind::kInteger) return std::nullopt;
  return m->integer;
}

std::optional<bool> JsonObject::BoolOf(std::string_view key) const {
  const JsonMember* m = Find(key);
  if (m == nullptr || m->kind != JsonMember::Kind::kBool) return std::nullopt;
  return m->boolean;
}

namespace {

// A cursor over the body that cannot move past its end.
class Cursor {
 public:
  explicit Cursor(std::span<const std::uint8_t> input)
      : text_(reinterpret_cast<const char*>(input.data()), input.size()) {}

  void SkipSpace() {
    while (pos_ < text_.size() && (text_[pos_] == ' ' || text_[pos_] == '\t' || text_[pos_] == '\r' || text_[pos_] == '\n')) ++pos_;
  }
  bool AtEnd() const { return pos_ >= text_.size(); }
  char Peek() const { return AtEnd() ? '\0' : text_[pos_]; }
  bool Take(char c) {
    if (Peek() != c || AtEnd()) return false;
    ++pos_;
    return true;
  }
  bool TakeWord(std::string_view word) {
    if (text_.substr(pos_, word.size()) != word) return false;
    pos_ += word.size();
    return true;
  }

  bool String(std::string_view& out) {
    if (!Take('"')) return false;
    const std::size_t start = pos_;
    while (pos_ < text_.size() && text_[pos_] != '"') {
      const auto byte = static_cast<unsigned char>(text_[pos_]);
      if (byte < 0x20 || byte == '\\') return false;
      ++pos_;
    }
    if (AtEnd() || pos_ - start > kMaxJsonString) return false;
    out = text_.substr(start, pos_ - start);
    ++pos_;  // the closing quote
    return true;
  }

  bool Integer(std::int64_t& out) {
    static constexpr std::int64_t kLimit = std::int64_t{1} << 53;  // what a JavaScript number holds exactly
    const bool negative = Take('-');
    if (Peek() < '0' || Peek() > '9') return false;
    if (Peek() == '0' && pos_ + 1 < text_.size() && text_[pos_ + 1] >= '0' && text_[pos_ + 1] <= '9') return false;
    std::int64_t value = 0;
    while (Peek() >= '0' && Peek() <= '9') {
      value = value * 10 + (text_[pos_] - '0');
      if (value > kLimit) return false;
      ++pos_;
    }
    if (Peek() == '.' || Peek() == 'e' || Peek() == 'E') return false;
    out = negative ? -value : value;
    return true;
  }

 private:
  std::string_view text_;
  std::size_t pos_ = 0;
};

bool ParseValue(Cursor& in, JsonMember& member) {
  switch (in.Peek()) {
    case '"':
      member.kind = JsonMember::Kind::kString;
      return in.String(member.text);
    case 't':
      member.kind = JsonMember::Kind::kBool;
      member.boolean = true;
      return in.TakeWord("true");
    case 'f':
      member.kind = JsonMember::Kind::kBool;
      member.boolean = false;
      return in.TakeWord("false");
    case 'n':
      member.kind = JsonMember::Kind::kNull;
      return in.TakeWord("null");
    default:
      member.kind = JsonMember::Kind::kInteger;
      return in.Integer(member.integer);
  }
}

}  // namespace

bool ParseFlatJsonObject(std::span<const std::uint8_t> input, JsonObject& object) {
  object.count = 0;
  Cursor in(input);
  in.SkipSpace();
  if (!in.Take('{')) return false;
  in.SkipSpace();
  if (!in.Take('}')) {
    while (true) {
      if (object.count == kMaxJsonMembers) return false;
      JsonMember member;
      in.SkipSpace();
      if (!in.String(member.key)) return false;
      if (object.Find(member.key) != nullptr) return false;
      in.SkipSpace();
      if (!in.Take(':')) return false;
      in.SkipSpace();
      if (!ParseValue(in, member)) return false;
      object.members[object.count++] = member;
      in.SkipSpace();
      if (in.Take('}')) break;
      if (!in.Take(',')) return false;
    }
  }
  in.SkipSpace();
  return in.AtEnd();
}

}  // namespace web
