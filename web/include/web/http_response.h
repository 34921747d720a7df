// An HTTP/1.1 response being built into a fixed buffer (docs/web.md "Responses"): the status line and
// headers, then either a body written into the same buffer (JSON, short texts) or a body that stays where
// it is (an embedded asset in flash: sent from there, never copied).
//
// The writer never writes past its buffer: a response that does not fit is replaced by a 500 when it is
// finished (overflowed() tells), so a client always gets a well-formed answer.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>

#include "web/http_request.h"

namespace web {

const char* ReasonPhrase(HttpStatus status);

// A body read piece by piece as the transport takes it (a file that is neither in the response buffer
// nor one span in flash: the EDS). The server never holds more of it than one chunk.
class HttpBodySource {
 public:
  virtual std::uint32_t Size() const = 0;
  // Copies the bytes from `offset` on into `out`; returns the count (fewer than out.size() only at the end).
  virtual std::size_t ReadAt(std::uint32_t offset, std::span<std::uint8_t> out) const = 0;

 protected:
  ~HttpBodySource() = default;
};

// The order of use: Start, any Header calls, then either Body / BodyText (a body in the buffer), or
// ExternalBody (a body elsewhere), or StreamedBody (a body read in chunks), or nothing (no body), then
// Finish.
class HttpResponseWriter {
 public:
  explicit HttpResponseWriter(std::span<std::uint8_t> buffer) : buffer_(buffer) {}

  void Start(HttpStatus status);
  void Header(std::string_view name, std::string_view value);
  void Header(std::string_view name, std::uint32_t value);
  // Reserve the rest of the buffer for a body written in place: after the headers, the caller writes at
  // most body_room() bytes into body_space() and then calls CommitBody with the count.
  std::span<std::uint8_t> BeginBody();
  void CommitBody(std::size_t length);
  void BodyText(std::string_view text);
  // A body the caller keeps valid until the response has been sent (Content-Length set from it).
  void ExternalBody(std::span<const std::uint8_t> body) { external_ = body; }
  // A body the server reads from `source` chunk by chunk while it is sent (Content-Length = Size()). The
  // source must stay valid for as long as the program runs.
  void StreamedBody(const HttpBodySource& source) { streamed_ = &source; }
  // `head`: HEAD request, headers only (Content-Length of the body that GET would have carried).
  // `keep_alive`: whether the connection stays open ("Connection: close" otherwise).
  void Finish(bool head, bool keep_alive);

  bool overflowed() const { return overflow_; }
  HttpStatus status() const { return status_; }
  // After Finish: the bytes in the buffer (head and in-buffer body), then the external body.
  std::span<const std::uint8_t> head() const { return std::span<const std::uint8_t>(buffer_.data(), used_); }
  std::span<const std::uint8_t> external_body() const { return external_; }
  // After Finish: the streamed body, null when there is none (or the request was HEAD).
  const HttpBodySource* streamed_body() const { return streamed_; }

 private:
  void Append(std::string_view text);
  void AppendNumber(std::uint32_t value);

  std::span<std::uint8_t> buffer_;
  std::size_t used_ = 0;
  std::size_t header_end_ = 0;     // where the in-buffer body starts (moved by Finish)
  std::size_t body_length_ = 0;    // in-buffer body
  bool body_started_ = false;
  std::span<const std::uint8_t> external_;
  const HttpBodySource* streamed_ = nullptr;
  HttpStatus status_ = HttpStatus::kOk;
  bool overflow_ = false;
};

}  // namespace web
