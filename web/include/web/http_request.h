// The web server's HTTP/1.1 request parser (docs/web.md "Requests"): a pure function on the bytes a
// connection has received so far. It never reads past the span, never allocates, and bounds everything
// a client controls: the request line, the header block, the number of headers and the body.
//
// The parser is called again with the whole buffer each time more bytes arrive; it answers "incomplete"
// until the header block and the whole body are there, then the parsed request and how many bytes it
// used (the next request of a keep-alive connection starts after them). A malformed or oversized request
// gets the status to answer with (the connection then closes: its framing can no longer be trusted).
//
// Supported: methods of any name (the server decides which it implements: 501 otherwise), origin-form
// targets ("/path?query"), HTTP/1.0 and 1.1, Content-Length bodies. Refused: chunked transfer coding
// (411: the card asks for a length), obs-fold header continuations and whitespace before the colon (400,
// RFC 9112 §5), conflicting or repeated Content-Length (400), HTTP/2 or other versions (505).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>

namespace web {

// Limits (docs/web.md "Requests"), sized to what the page and the JSON API send, with room to spare: the
// longest request line is a 32-register read (about 200 bytes), a browser's API request with its cookie
// and CSRF token about 900 bytes of request line and headers, the largest API body (a password change)
// about 60 bytes. They make up the receive buffer of each connection (kHttpReceiveBufferBytes).
inline constexpr std::size_t kMaxRequestLine = 512;    // 414 beyond
inline constexpr std::size_t kMaxHeaderBlock = 2048;   // request line + headers + blank line; 431 beyond
inline constexpr std::size_t kMaxHeaders = 24;         // 431 beyond
inline constexpr std::size_t kMaxBody = 512;           // 413 beyond

enum class HttpStatus : std::uint16_t {
  kOk = 200,
  kAccepted = 202,
  kNoContent = 204,
  kNotModified = 304,
  kBadRequest = 400,
  kUnauthorized = 401,
  kForbidden = 403,
  kNotFound = 404,
  kMethodNotAllowed = 405,
  kNotAcceptable = 406,
  kRequestTimeout = 408,
  kConflict = 409,
  kLengthRequired = 411,
  kPayloadTooLarge = 413,
  kUriTooLong = 414,
  kUnsupportedMediaType = 415,
  kUnprocessable = 422,
  kTooManyRequests = 429,
  kHeaderFieldsTooLarge = 431,
  kInternalError = 500,
  kNotImplemented = 501,
  kServiceUnavailable = 503,
  kGatewayTimeout = 504,
  kVersionNotSupported = 505,
};

struct HttpHeader {
  std::string_view name;   // as sent (compare with HeaderNameIs: names are case-insensitive)
  std::string_view value;  // leading and trailing spaces and tabs removed
};

struct HttpRequest {
  std::string_view method;
  std::string_view target;  // as sent: path and query
  std::string_view path;    // the target up to '?'
  std::string_view query;   // after '?', empty when none
  std::uint8_t version_minor = 1;  // HTTP/1.x
  std::array<HttpHeader, kMaxHeaders> headers{};
  std::size_t header_count = 0;
  std::span<const std::uint8_t> body;
  // HTTP/1.1 unless "Connection: close"; HTTP/1.0 only with "Connection: keep-alive".
  bool keep_alive = true;

  // The first header with this name (case-insensitive), if any.
  std::optional<std::string_view> Header(std::string_view name) const;
};

enum class ParseState : std::uint8_t {
  kIncomplete,  // more bytes needed (nothing is wrong so far, and the limits still allow them)
  kComplete,    // `request` is valid; `consumed` bytes belong to it
  kError,       // answer `error` and close
};

struct ParseResult {
  ParseState state = ParseState::kIncomplete;
  std::size_t consumed = 0;
  HttpStatus error = HttpStatus::kBadRequest;
};

// `request` refers into `input`: valid as long as those bytes are.
ParseResult ParseHttpRequest(std::span<const std::uint8_t> input, HttpRequest& request);

bool HeaderNameIs(std::string_view name, std::string_view wanted);

}  // namespace web
