// libFuzzer target for the web server's HTTP request parser (web/http_request.h).
// Oracles: nothing is read outside the input (ASan); a complete request consumes at most the input,
// its fields and body lie inside the consumed bytes, its header count is within the limit; parsing just
// the consumed bytes gives the same request; an error names a 4xx/5xx status.
#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>

#include "web/http_request.h"

namespace {

void Require(bool condition) {
  if (!condition) __builtin_trap();
}

bool Inside(std::string_view part, std::span<const std::uint8_t> whole) {
  if (part.empty()) return true;
  const auto* begin = reinterpret_cast<const char*>(whole.data());
  return part.data() >= begin && part.data() + part.size() <= begin + whole.size();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::span<const std::uint8_t> input(data, size);
  web::HttpRequest request;
  const web::ParseResult result = web::ParseHttpRequest(input, request);
  if (result.state == web::ParseState::kError) {
    const auto code = static_cast<std::uint16_t>(result.error);
    Require(code >= 400 && code < 600);
    return 0;
  }
  if (result.state == web::ParseState::kIncomplete) return 0;
  Require(result.consumed > 0 && result.consumed <= size);
  const std::span<const std::uint8_t> used = input.first(result.consumed);
  Require(request.header_count <= web::kMaxHeaders);
  Require(Inside(request.method, used) && Inside(request.target, used) && Inside(request.path, used) &&
          Inside(request.query, used));
  for (std::size_t i = 0; i < request.header_count; ++i) {
    Require(Inside(request.headers[i].name, used) && Inside(request.headers[i].value, used));
  }
  Require(request.body.size() <= web::kMaxBody);
  Require(request.body.empty() || (request.body.data() >= used.data() &&
                                   request.body.data() + request.body.size() == used.data() + used.size()));
  web::HttpRequest again;
  const web::ParseResult repeat = web::ParseHttpRequest(used, again);
  Require(repeat.state == web::ParseState::kComplete && repeat.consumed == result.consumed);
  Require(again.target == request.target && again.header_count == request.header_count &&
          again.body.size() == request.body.size() && again.keep_alive == request.keep_alive);
  return 0;
}
