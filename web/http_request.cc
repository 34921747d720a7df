#include "web/http_request.h"

#include <algorithm>

namespace web {
namespace {

constexpr std::string_view kCrlf = "\r\n";
constexpr std::string_view kBlockEnd = "\r\n\r\n";

// RFC 9110 §5.6.2 token characters.
bool IsTokenChar(char c) {
  if ((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9')) return true;
  return std::string_view("!#$%&'*+-.^_`|~").find(c) != std::string_view::npos;
}

bool IsToken(std::string_view text) { return !text.empty() && std::all_of(text.begin(), text.end(), IsTokenChar); }

// A header value: visible characters, spaces, tabs and obs-text; no other control character.
bool IsFieldValue(std::string_view text) {
  return std::all_of(text.begin(), text.end(), [](char c) {
    const auto byte = static_cast<unsigned char>(c);
    return byte == '\t' || byte >= 0x20 ? byte != 0x7F : false;
  });
}

bool IsTargetChar(char c) {
  const auto byte = static_cast<unsigned char>(c);
  return byte > 0x20 && byte < 0x7F;
}

std::string_view Trim(std::string_view text) {
  while (!text.empty() && (text.front() == ' ' || text.front() == '\t')) text.remove_prefix(1);
  while (!text.empty() && (text.back() == ' ' || text.back() == '\t')) text.remove_suffix(1);
  return text;
}

char Lower(char c) { return c >= 'A' && c <= 'Z' ? static_cast<char>(c - 'A' + 'a') : c; }

bool HasToken(std::string_view list, std::string_view wanted) {
  while (!list.empty()) {
    const std::size_t comma = list.find(',');
    if (HeaderNameIs(Trim(list.substr(0, comma)), wanted)) return true;
    if (comma == std::string_view::npos) break;
    list.remove_prefix(comma + 1);
  }
  return false;
}

ParseResult Error(HttpStatus status) { return ParseResult{ParseState::kError, 0, status}; }

bool IsDigits(std::string_view text) {
  return !text.empty() && std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; });
}

// Content-Length: 1*DIGIT (400 otherwise), at most kMaxBody (413 otherwise).
ParseResult ParseLength(std::string_view text, std::size_t& length) {
  if (!IsDigits(text)) return Error(HttpStatus::kBadRequest);
  length = 0;
  for (char c : text) {
    length = length * 10 + static_cast<std::size_t>(c - '0');
    if (length > kMaxBody) return Error(HttpStatus::kPayloadTooLarge);
  }
  return ParseResult{ParseState::kComplete, 0, HttpStatus::kOk};
}

// A line feed without its carriage return: RFC 9112 §2.2 lets a server refuse it, and this one does
// (one line ending means one way to frame, nothing for a proxy in front to read differently).
bool HasBareLf(std::string_view text) {
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] == '\n' && (i == 0 || text[i - 1] != '\r')) return true;
  }
  return false;
}

ParseResult ParseRequestLine(std::string_view line, HttpRequest& request) {
  const std::size_t first = line.find(' ');
  const std::size_t last = line.rfind(' ');
  if (first == std::string_view::npos || first == last) return Error(HttpStatus::kBadRequest);
  request.method = line.substr(0, first);
  request.target = line.substr(first + 1, last - first - 1);
  const std::string_view version = line.substr(last + 1);
  if (!IsToken(request.method)) return Error(HttpStatus::kBadRequest);
  if (request.target.empty() || request.target.front() != '/' ||
      !std::all_of(request.target.begin(), request.target.end(), IsTargetChar)) {
    return Error(HttpStatus::kBadRequest);
  }
  if (version == "HTTP/1.1") {
    request.version_minor = 1;
  } else if (version == "HTTP/1.0") {
    request.version_minor = 0;
  } else if (version.size() == 8 && version.substr(0, 5) == "HTTP/" && version[5] >= '0' && version[5] <= '9' &&
             version[6] == '.' && version[7] >= '0' && version[7] <= '9') {
    return Error(HttpStatus::kVersionNotSupported);
  } else {
    return Error(HttpStatus::kBadRequest);
  }
  const std::size_t question = request.target.find('?');
  request.path = request.target.substr(0, question);
  request.query = question == std::string_view::npos ? std::string_view() : request.target.substr(question + 1);
  return ParseResult{ParseState::kComplete, 0, HttpStatus::kOk};
}

}  // namespace

bool HeaderNameIs(std::string_view name, std::string_view wanted) {
  return name.size() == wanted.size() &&
         std::equal(name.begin(), name.end(), wanted.begin(), [](char a, char b) { return Lower(a) == Lower(b); });
}

std::optional<std::string_view> HttpRequest::Header(std::string_view name) const {
  for (std::size_t i = 0; i < header_count; ++i) {
    if (HeaderNameIs(headers[i].name, name)) return headers[i].value;
  }
  return std::nullopt;
}

ParseResult ParseHttpRequest(std::span<const std::uint8_t> input, HttpRequest& request) {
  request = HttpRequest{};
  const std::string_view text(reinterpret_cast<const char*>(input.data()), input.size());

  // The request line first: its limit is tighter than the block's.
  const std::size_t line_end = text.find(kCrlf);
  if (line_end == std::string_view::npos || line_end > kMaxRequestLine) {
    if (line_end != std::string_view::npos || text.size() > kMaxRequestLine) return Error(HttpStatus::kUriTooLong);
    return HasBareLf(text) ? Error(HttpStatus::kBadRequest) : ParseResult{};
  }
  const std::size_t block_end = text.find(kBlockEnd);
  const std::size_t searched = block_end == std::string_view::npos ? text.size() : block_end;
  if (HasBareLf(text.substr(0, std::min(searched, kMaxHeaderBlock)))) return Error(HttpStatus::kBadRequest);
  if (block_end == std::string_view::npos || block_end + kBlockEnd.size() > kMaxHeaderBlock) {
    if (text.size() >= kMaxHeaderBlock) return Error(HttpStatus::kHeaderFieldsTooLarge);
    return ParseResult{};
  }
  if (ParseResult line = ParseRequestLine(text.substr(0, line_end), request); line.state == ParseState::kError) {
    return line;
  }

  // Header lines between the request line and the blank line.
  std::string_view rest = text.substr(line_end + kCrlf.size(), block_end - line_end);
  std::optional<std::size_t> content_length;
  bool has_host = false;
  while (!rest.empty()) {
    const std::size_t end = rest.find(kCrlf);
    const std::string_view line = rest.substr(0, end);
    rest.remove_prefix(end == std::string_view::npos ? rest.size() : end + kCrlf.size());
    if (line.empty()) break;
    if (line.find('\r') != std::string_view::npos) return Error(HttpStatus::kBadRequest);
    const std::size_t colon = line.find(':');
    if (colon == std::string_view::npos) return Error(HttpStatus::kBadRequest);
    const std::string_view name = line.substr(0, colon);
    const std::string_view value = Trim(line.substr(colon + 1));
    // Whitespace before the colon or a continuation line (obs-fold) makes the name no token: 400.
    if (!IsToken(name) || !IsFieldValue(value)) return Error(HttpStatus::kBadRequest);
    if (request.header_count == kMaxHeaders) return Error(HttpStatus::kHeaderFieldsTooLarge);
    request.headers[request.header_count++] = HttpHeader{name, value};
    if (HeaderNameIs(name, "Content-Length")) {
      if (content_length) return Error(HttpStatus::kBadRequest);
      std::size_t length = 0;
      if (ParseResult parsed = ParseLength(value, length); parsed.state == ParseState::kError) return parsed;
      content_length = length;
    } else if (HeaderNameIs(name, "Transfer-Encoding")) {
      return Error(HasToken(value, "chunked") ? HttpStatus::kLengthRequired : HttpStatus::kNotImplemented);
    } else if (HeaderNameIs(name, "Host")) {
      if (has_host) return Error(HttpStatus::kBadRequest);
      has_host = true;
    }
  }
  if (request.version_minor == 1 && !has_host) return Error(HttpStatus::kBadRequest);  // RFC 9112 §3.2

  const std::optional<std::string_view> connection = request.Header("Connection");
  request.keep_alive = request.version_minor == 1 ? !(connection && HasToken(*connection, "close"))
                                                  : connection && HasToken(*connection, "keep-alive");

  const std::size_t body_start = block_end + kBlockEnd.size();
  const std::size_t body_size = content_length.value_or(0);
  if (input.size() - body_start < body_size) return ParseResult{};
  request.body = input.subspan(body_start, body_size);
  return ParseResult{ParseState::kComplete, body_start + body_size, HttpStatus::kOk};
}

}  // namespace web
