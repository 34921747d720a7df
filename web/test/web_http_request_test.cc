// The web server's HTTP/1.1 request parser: complete requests with exact fields, incremental input,
// keep-alive rules, and every refusal with its status (docs/web.md "Requests").
#include "web/http_request.h"

#include <gtest/gtest.h>

#include <string>
#include <string_view>

namespace web {
namespace {

std::span<const std::uint8_t> Bytes(std::string_view text) {
  return {reinterpret_cast<const std::uint8_t*>(text.data()), text.size()};
}

ParseResult Parse(std::string_view text, HttpRequest& request) { return ParseHttpRequest(Bytes(text), request); }

HttpStatus ErrorOf(std::string_view text) {
  HttpRequest request;
  const ParseResult result = Parse(text, request);
  EXPECT_EQ(result.state, ParseState::kError) << text;
  return result.error;
}

TEST(WebHttpRequestTest, GetWithQueryAndHeaders) {
  const std::string_view text =
      "GET /api/monitor?fields=fd00,fd03 HTTP/1.1\r\nHost: 10.0.0.2\r\nAccept:  application/json \r\n\r\n";
  HttpRequest request;
  const ParseResult result = Parse(text, request);
  ASSERT_EQ(result.state, ParseState::kComplete);
  EXPECT_EQ(result.consumed, text.size());
  EXPECT_EQ(request.method, "GET");
  EXPECT_EQ(request.target, "/api/monitor?fields=fd00,fd03");
  EXPECT_EQ(request.path, "/api/monitor");
  EXPECT_EQ(request.query, "fields=fd00,fd03");
  EXPECT_EQ(request.version_minor, 1);
  ASSERT_EQ(request.header_count, 2U);
  EXPECT_EQ(request.Header("accept"), std::optional<std::string_view>("application/json"));
  EXPECT_EQ(request.Header("HOST"), std::optional<std::string_view>("10.0.0.2"));
  EXPECT_FALSE(request.Header("Cookie").has_value());
  EXPECT_TRUE(request.keep_alive);
  EXPECT_TRUE(request.body.empty());
}

TEST(WebHttpRequestTest, PostBodyArrivesInPiecesAndTheNextRequestIsNotTaken) {
  const std::string text =
      "POST /api/parameters/0x0009 HTTP/1.1\r\nHost: card\r\nContent-Length: 11\r\n\r\n{\"value\":5}"
      "GET / HTTP/1.1\r\nHost: card\r\n\r\n";
  const std::size_t first = text.find("GET");
  HttpRequest request;
  for (std::size_t cut = 0; cut < first; ++cut) {
    EXPECT_EQ(Parse(std::string_view(text).substr(0, cut), request).state, ParseState::kIncomplete) << cut;
  }
  const ParseResult result = Parse(text, request);
  ASSERT_EQ(result.state, ParseState::kComplete);
  EXPECT_EQ(result.consumed, first);
  EXPECT_EQ(std::string_view(reinterpret_cast<const char*>(request.body.data()), request.body.size()),
            "{\"value\":5}");
  const ParseResult next = Parse(std::string_view(text).substr(first), request);
  ASSERT_EQ(next.state, ParseState::kComplete);
  EXPECT_EQ(request.path, "/");
}

TEST(WebHttpRequestTest, KeepAliveRules) {
  HttpRequest request;
  ASSERT_EQ(Parse("GET / HTTP/1.1\r\nHost: a\r\nConnection: close\r\n\r\n", request).state, ParseState::kComplete);
  EXPECT_FALSE(request.keep_alive);
  ASSERT_EQ(Parse("GET / HTTP/1.1\r\nHost: a\r\nConnection: Upgrade, CLOSE\r\n\r\n", request).state,
            ParseState::kComplete);
  EXPECT_FALSE(request.keep_alive);
  ASSERT_EQ(Parse("GET / HTTP/1.0\r\n\r\n", request).state, ParseState::kComplete);
  EXPECT_FALSE(request.keep_alive);
  EXPECT_EQ(request.version_minor, 0);
  ASSERT_EQ(Parse("GET / HTTP/1.0\r\nConnection: keep-alive\r\n\r\n", request).state, ParseState::kComplete);
  EXPECT_TRUE(request.keep_alive);
}

TEST(WebHttpRequestTest, MalformedRequestsAreBadRequests) {
  EXPECT_EQ(ErrorOf("GET / HTTP/1.1\r\n\r\n"), HttpStatus::kBadRequest);                       // no Host
  EXPECT_EQ(ErrorOf("GET  / HTTP/1.1\r\nHost: a\r\n\r\n"), HttpStatus::kBadRequest);           // two spaces
  EXPECT_EQ(ErrorOf("GET http://a/ HTTP/1.1\r\nHost: a\r\n\r\n"), HttpStatus::kBadRequest);    // absolute form
  EXPECT_EQ(ErrorOf("GE(T / HTTP/1.1\r\nHost: a\r\n\r\n"), HttpStatus::kBadRequest);           // method no token
  EXPECT_EQ(ErrorOf("GET / HTTP/1.1\r\nHost : a\r\n\r\n"), HttpStatus::kBadRequest);           // space before ':'
  EXPECT_EQ(ErrorOf("GET / HTTP/1.1\r\nHost: a\r\n folded\r\n\r\n"), HttpStatus::kBadRequest); // obs-fold
  EXPECT_EQ(ErrorOf("GET / HTTP/1.1\r\nHost a\r\n\r\n"), HttpStatus::kBadRequest);             // no colon
  EXPECT_EQ(ErrorOf("GET / HTTP/1.1\r\nHost: a\r\nX: a\x01" "b\r\n\r\n"), HttpStatus::kBadRequest);  // control
  EXPECT_EQ(ErrorOf("GET / HTTP/1.1\nHost: a\n\n"), HttpStatus::kBadRequest);                  // bare LF
  EXPECT_EQ(ErrorOf("GET / HTTP/1.1\r\nHost: a\nX: b\r\n\r\n"), HttpStatus::kBadRequest);      // bare LF inside
  EXPECT_EQ(ErrorOf("GET / HTTP/1.1\r\nHost: a\r\nHost: b\r\n\r\n"), HttpStatus::kBadRequest); // two Hosts
  EXPECT_EQ(ErrorOf("GET / HTTP/1.1\r\nHost: a\r\nContent-Length: 1\r\nContent-Length: 1\r\n\r\nx"),
            HttpStatus::kBadRequest);
  EXPECT_EQ(ErrorOf("POST / HTTP/1.1\r\nHost: a\r\nContent-Length: -1\r\n\r\n"), HttpStatus::kBadRequest);
  EXPECT_EQ(ErrorOf("POST / HTTP/1.1\r\nHost: a\r\nContent-Length: 1 2\r\n\r\n"), HttpStatus::kBadRequest);
  EXPECT_EQ(ErrorOf("GET / HTTX/1.1\r\nHost: a\r\n\r\n"), HttpStatus::kBadRequest);
}

TEST(WebHttpRequestTest, LimitsAndUnsupportedFeatures) {
  EXPECT_EQ(ErrorOf("GET / HTTP/2.0\r\nHost: a\r\n\r\n"), HttpStatus::kVersionNotSupported);
  EXPECT_EQ(ErrorOf("POST / HTTP/1.1\r\nHost: a\r\nTransfer-Encoding: chunked\r\n\r\n"), HttpStatus::kLengthRequired);
  EXPECT_EQ(ErrorOf("POST / HTTP/1.1\r\nHost: a\r\nTransfer-Encoding: gzip\r\n\r\n"), HttpStatus::kNotImplemented);
  EXPECT_EQ(ErrorOf("POST / HTTP/1.1\r\nHost: a\r\nContent-Length: 4097\r\n\r\n"), HttpStatus::kPayloadTooLarge);
  EXPECT_EQ(ErrorOf("POST / HTTP/1.1\r\nHost: a\r\nContent-Length: 99999999999999999999\r\n\r\n"),
            HttpStatus::kPayloadTooLarge);

  // The request line: kMaxRequestLine bytes are fine, one more is 414, even before its end arrives.
  const std::string path(kMaxRequestLine - std::string_view("GET  HTTP/1.1").size(), 'a');
  HttpRequest request;
  const std::string longest = "GET /" + path.substr(1) + " HTTP/1.1\r\nHost: a\r\n\r\n";
  EXPECT_EQ(Parse(longest, request).state, ParseState::kComplete);
  EXPECT_EQ(ErrorOf("GET /" + path + " HTTP/1.1\r\nHost: a\r\n\r\n"), HttpStatus::kUriTooLong);
  EXPECT_EQ(ErrorOf("GET /" + std::string(kMaxRequestLine, 'a')), HttpStatus::kUriTooLong);

  // The header block and the number of headers: 431.
  std::string many = "GET / HTTP/1.1\r\nHost: a\r\n";
  for (std::size_t i = 1; i < kMaxHeaders; ++i) many += "X-" + std::to_string(i) + ": v\r\n";
  EXPECT_EQ(Parse(many + "\r\n", request).state, ParseState::kComplete);
  EXPECT_EQ(ErrorOf(many + "X-last: v\r\n\r\n"), HttpStatus::kHeaderFieldsTooLarge);
  const std::string big = "GET / HTTP/1.1\r\nHost: a\r\nX: " + std::string(kMaxHeaderBlock, 'v');
  EXPECT_EQ(ErrorOf(big), HttpStatus::kHeaderFieldsTooLarge);
  // Below the limits an unfinished block is just incomplete.
  EXPECT_EQ(Parse("GET / HTTP/1.1\r\nHost: a\r\nX: vvv", request).state, ParseState::kIncomplete);
}

TEST(WebHttpRequestTest, BodyAndHeaderBlockAtTheirExactLimits) {
  HttpRequest request;
  // A body of kMaxBody (512) bytes is taken; one more byte is 413, as soon as the header says so.
  const std::string body(kMaxBody, 'b');
  const std::string post = "POST /api/x HTTP/1.1\r\nHost: a\r\nContent-Length: 512\r\n\r\n" + body;
  const ParseResult largest = Parse(post, request);
  ASSERT_EQ(largest.state, ParseState::kComplete);
  EXPECT_EQ(request.body.size(), 512U);
  EXPECT_EQ(largest.consumed, post.size());
  EXPECT_EQ(ErrorOf("POST /api/x HTTP/1.1\r\nHost: a\r\nContent-Length: 513\r\n\r\n"), HttpStatus::kPayloadTooLarge);

  // A header block (request line, headers and the blank line) of exactly kMaxHeaderBlock (2048) bytes is
  // taken; one byte more is 431.
  const std::string prefix = "GET / HTTP/1.1\r\nHost: a\r\nX: ";
  const std::string at_limit = prefix + std::string(kMaxHeaderBlock - prefix.size() - 4, 'v') + "\r\n\r\n";
  ASSERT_EQ(at_limit.size(), 2048U);
  const ParseResult block = Parse(at_limit, request);
  ASSERT_EQ(block.state, ParseState::kComplete);
  EXPECT_EQ(block.consumed, 2048U);
  const std::string beyond = prefix + std::string(kMaxHeaderBlock - prefix.size() - 3, 'v') + "\r\n\r\n";
  EXPECT_EQ(ErrorOf(beyond), HttpStatus::kHeaderFieldsTooLarge);

  // The request line: 512 bytes (without its CRLF) are taken, 513 are 414.
  const std::string line = "GET /" + std::string(kMaxRequestLine - std::string_view("GET / HTTP/1.1").size(), 'p') +
                           " HTTP/1.1";
  ASSERT_EQ(line.size(), 512U);
  EXPECT_EQ(Parse(line + "\r\nHost: a\r\n\r\n", request).state, ParseState::kComplete);
  const std::string longer = "GET /" + std::string(kMaxRequestLine + 1 - std::string_view("GET / HTTP/1.1").size(), 'p') +
                             " HTTP/1.1";
  EXPECT_EQ(ErrorOf(longer + "\r\nHost: a\r\n\r\n"), HttpStatus::kUriTooLong);
}

}  // namespace
}  // namespace web
