#include "web/http_response.h"

#include <algorithm>
#include <array>
#include <cstring>

namespace web {

const char* ReasonPhrase(HttpStatus status) {
  switch (status) {
    case HttpStatus::kOk: return "OK";
    case HttpStatus::kAccepted: return "Accepted";
    case HttpStatus::kNoContent: return "No Content";
    case HttpStatus::kNotModified: return "Not Modified";
    case HttpStatus::kBadRequest: return "Bad Request";
    case HttpStatus::kUnauthorized: return "Unauthorized";
    case HttpStatus::kForbidden: return "Forbidden";
    case HttpStatus::kNotFound: return "Not Found";
    case HttpStatus::kMethodNotAllowed: return "Method Not Allowed";
    case HttpStatus::kNotAcceptable: return "Not Acceptable";
    case HttpStatus::kRequestTimeout: return "Request Timeout";
    case HttpStatus::kConflict: return "Conflict";
    case HttpStatus::kLengthRequired: return "Length Required";
    case HttpStatus::kPayloadTooLarge: return "Content Too Large";
    case HttpStatus::kUriTooLong: return "URI Too Long";
    case HttpStatus::kUnsupportedMediaType: return "Unsupported Media Type";
    case HttpStatus::kUnprocessable: return "Unprocessable Content";
    case HttpStatus::kTooManyRequests: return "Too Many Requests";
    case HttpStatus::kHeaderFieldsTooLarge: return "Request Header Fields Too Large";
    case HttpStatus::kInternalError: return "Internal Server Error";
    case HttpStatus::kNotImplemented: return "Not Implemented";
    case HttpStatus::kServiceUnavailable: return "Service Unavailable";
    case HttpStatus::kGatewayTimeout: return "Gateway Timeout";
    case HttpStatus::kVersionNotSupported: return "HTTP Version Not Supported";
  }
  return "Unknown";
}

namespace {

// Decimal digits of `value` into `out` (at least 10 bytes); returns the count.
std::size_t FormatDecimal(std::uint32_t value, char* out) {
  char reversed[10];
  std::size_t count = 0;
  do {
    reversed[count++] = static_cast<char>('0' + value % 10);
    value /= 10;
  } while (value != 0);
  for (std::size_t i = 0; i < count; ++i) out[i] = reversed[count - 1 - i];
  return count;
}

// Statuses after which a body is never sent (RFC 9110 §6.4.1).
bool HasNoBody(HttpStatus status) { return status == HttpStatus::kNoContent || status == HttpStatus::kNotModified; }

}  // namespace

void HttpResponseWriter::Append(std::string_view text) {
  if (overflow_) return;
  if (text.size() > buffer_.size() - used_) {
    overflow_ = true;
    return;
  }
  std::memcpy(buffer_.data() + used_, text.data(), text.size());
  used_ += text.size();
}

void HttpResponseWriter::AppendNumber(std::uint32_t value) {
  char digits[10];
  Append(std::string_view(digits, FormatDecimal(value, digits)));
}

void HttpResponseWriter::Start(HttpStatus status) {
  status_ = status;
  used_ = 0;
  header_end_ = 0;
  body_length_ = 0;
  body_started_ = false;
  external_ = {};
  streamed_ = nullptr;
  overflow_ = false;
  Append("HTTP/1.1 ");
  AppendNumber(static_cast<std::uint32_t>(status));
  Append(" ");
  Append(ReasonPhrase(status));
  Append("\r\n");
}

void HttpResponseWriter::Header(std::string_view name, std::string_view value) {
  Append(name);
  Append(": ");
  Append(value);
  Append("\r\n");
}

void HttpResponseWriter::Header(std::string_view name, std::uint32_t value) {
  Append(name);
  Append(": ");
  AppendNumber(value);
  Append("\r\n");
}

std::span<std::uint8_t> HttpResponseWriter::BeginBody() {
  body_started_ = true;
  header_end_ = used_;
  if (overflow_) return {};
  return buffer_.subspan(used_);
}

void HttpResponseWriter::CommitBody(std::size_t length) {
  if (overflow_) return;
  if (length > buffer_.size() - used_) {
    overflow_ = true;
    return;
  }
  used_ += length;
  body_length_ += length;
}

void HttpResponseWriter::BodyText(std::string_view text) {
  if (!body_started_) BeginBody();
  Append(text);
  if (!overflow_) body_length_ += text.size();
}

void HttpResponseWriter::Finish(bool head, bool keep_alive) {
  if (!body_started_) header_end_ = used_;
  // The headers that depend on the body go between the caller's headers and the body.
  std::array<char, 64> tail{};
  std::size_t tail_length = 0;
  const auto add = [&](std::string_view text) {
    std::memcpy(tail.data() + tail_length, text.data(), text.size());
    tail_length += text.size();
  };
  if (!HasNoBody(status_)) {
    add("Content-Length: ");
    const std::size_t length =
        streamed_ != nullptr ? streamed_->Size() : (external_.empty() ? body_length_ : external_.size());
    tail_length += FormatDecimal(static_cast<std::uint32_t>(length), tail.data() + tail_length);
    add("\r\n");
  }
  add(keep_alive ? "Connection: keep-alive\r\n\r\n" : "Connection: close\r\n\r\n");
  if (!overflow_ && tail_length <= buffer_.size() - used_) {
    std::memmove(buffer_.data() + header_end_ + tail_length, buffer_.data() + header_end_, body_length_);
    std::memcpy(buffer_.data() + header_end_, tail.data(), tail_length);
    used_ += tail_length;
    if (head || HasNoBody(status_)) {
      used_ = header_end_ + tail_length;
      external_ = {};
      streamed_ = nullptr;
    }
    return;
  }
  // Too large for the buffer: a bodiless 500 instead (the buffer always holds one), and the connection
  // closes, so a client never sees half an answer.
  overflow_ = false;
  Start(HttpStatus::kInternalError);
  Append("Content-Length: 0\r\nConnection: close\r\n\r\n");
  overflow_ = true;
}

}  // namespace web
