// libFuzzer target for the web server's connection core and its JSON reader (web/http_server.h,
// web/json.h): the input is a byte stream cut into receive chunks (first byte: chunk size) for one
// connection whose handler parses every body as a flat JSON object, echoes its members through the JSON
// writer and answers some requests only on a later pass.
// Oracles: nothing is read or written outside the buffers (ASan); every answer begins with a status
// line; a connection that must close stays closed to new requests; the window accounting never
// releases more than was received; a streamed body arrives as exactly its pattern, no more than its
// Content-Length, in chunks no larger than the room offered.
#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>

#include "web/http_server.h"
#include "web/json.h"

namespace {

void Require(bool condition) {
  if (!condition) __builtin_trap();
}

class EchoHandler final : public web::HttpHandler {
 public:
  web::HandlerResult Handle(web::HttpClientId, const web::HttpRequest& request, web::HttpResponseWriter& response,
                            hal::Micros) override {
    if (request.path == "/later" && (++calls_ % 3) != 0) return web::HandlerResult::kPending;
    if (request.path == "/stream") {
      response.Start(web::HttpStatus::kOk);
      source_.size = static_cast<std::uint32_t>(1 + request.body.size() * 97);
      response.StreamedBody(source_);
      stream_answered = request.method != "HEAD";
      return web::HandlerResult::kDone;
    }
    web::JsonObject object;
    if (!web::ParseFlatJsonObject(request.body, object)) {
      response.Start(web::HttpStatus::kBadRequest);
      return web::HandlerResult::kDone;
    }
    response.Start(web::HttpStatus::kOk);
    const std::span<std::uint8_t> space = response.BeginBody();
    web::JsonWriter json(space);
    json.BeginObject();
    for (std::size_t i = 0; i < object.count; ++i) {
      const web::JsonMember& m = object.members[i];
      json.Key(m.key);
      if (m.kind == web::JsonMember::Kind::kString) json.String(m.text);
      if (m.kind == web::JsonMember::Kind::kInteger) json.Number(m.integer);
      if (m.kind == web::JsonMember::Kind::kBool) json.Bool(m.boolean);
      if (m.kind == web::JsonMember::Kind::kNull) json.Null();
    }
    json.EndObject();
    response.CommitBody(json.overflowed() ? space.size() + 1 : json.size());
    return web::HandlerResult::kDone;
  }
  void OnClientClosed(web::HttpClientId) override {}
  hal::Micros NextDeadline() const override { return 0; }

  // Byte i of a streamed body is i mod 251.
  class PatternSource final : public web::HttpBodySource {
   public:
    std::uint32_t Size() const override { return size; }
    std::size_t ReadAt(std::uint32_t offset, std::span<std::uint8_t> out) const override {
      std::size_t count = 0;
      for (; count < out.size() && offset + count < size; ++count) out[count] = static_cast<std::uint8_t>((offset + count) % 251);
      return count;
    }
    std::uint32_t size = 0;
  };
  const PatternSource& source() const { return source_; }
  bool stream_answered = false;  // the last answer carries a streamed body (not HEAD)

 private:
  unsigned calls_ = 0;
  PatternSource source_;
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  EchoHandler handler;
  web::HttpServer server(handler);
  hal::Micros now = 1000;
  const auto opened = server.Open(now);
  Require(opened.ok());
  const web::HttpClientId id = *opened;
  std::size_t received = 0;
  std::size_t released = 0;
  std::size_t at = 0;
  std::size_t stream_left = 0;  // of the streamed body being sent
  std::size_t stream_at = 0;
  while (at < size && !server.MustClose(id)) {
    const std::size_t chunk = std::min<std::size_t>(1 + data[at] % 64, size - at - 1);
    ++at;
    received += server.Receive(id, std::span<const std::uint8_t>(data + at, chunk), now);
    at += chunk;
    for (int pass = 0; pass < 4; ++pass) {
      now += 1000;
      server.Poll(now);
      const std::size_t room = 1 + static_cast<std::size_t>(data[at - 1 - chunk]) * 37;
      server.LoadStreamChunk(id, room, now);
      for (auto out = server.PendingOutput(id); !out.empty(); out = server.PendingOutput(id)) {
        const bool head = std::string_view(reinterpret_cast<const char*>(out.data()), std::min<std::size_t>(out.size(), 9)) ==
                          std::string_view("HTTP/1.1 ").substr(0, std::min<std::size_t>(out.size(), 9));
        if (stream_left > 0) {
          // Until the streamed body is complete, every output is its next chunk: the pattern at its place,
          // within the room offered and the length announced.
          Require(!server.PendingOutputIsStatic(id) && out.size() <= room && out.size() <= stream_left);
          for (std::size_t i = 0; i < out.size(); ++i) Require(out[i] == (stream_at + i) % 251);
          stream_at += out.size();
          stream_left -= out.size();
        } else {
          Require(head || server.PendingOutputIsStatic(id));
          if (head && handler.stream_answered) {
            handler.stream_answered = false;
            stream_left = handler.source().Size();
            stream_at = 0;
          }
        }
        server.ConsumeOutput(id, out.size(), now);
        server.LoadStreamChunk(id, room, now);
      }
    }
    released += server.TakeReleasedInput(id, 536);  // lwIP's TCP_WND
    Require(released <= received);
  }
  server.Close(id);
  return 0;
}
