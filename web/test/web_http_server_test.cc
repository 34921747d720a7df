// The web server's response writer, JSON writer/reader and connection core: exact answers on the wire,
// keep-alive and pipelining, deferred answers, slots and eviction, window accounting, timeouts
// (docs/web.md "Connections").
#include "web/http_server.h"

#include <gtest/gtest.h>

#include <string>
#include <string_view>

#include "web/json.h"

namespace web {
namespace {

std::span<const std::uint8_t> Bytes(std::string_view text) {
  return {reinterpret_cast<const std::uint8_t*>(text.data()), text.size()};
}

std::string Text(std::span<const std::uint8_t> bytes) { return std::string(bytes.begin(), bytes.end()); }

// --- HttpResponseWriter --------------------------------------------------------------------------------

TEST(WebHttpResponseTest, BodyInBufferGetsLengthAndConnection) {
  std::array<std::uint8_t, 256> buffer{};
  HttpResponseWriter writer(buffer);
  writer.Start(HttpStatus::kOk);
  writer.Header("Content-Type", "application/json");
  writer.BodyText("{\"a\":1}");
  writer.Finish(false, true);
  EXPECT_FALSE(writer.overflowed());
  EXPECT_EQ(Text(writer.head()),
            "HTTP/1.1 200 OK\r\nContent-Type: application/json\r\nContent-Length: 7\r\n"
            "Connection: keep-alive\r\n\r\n{\"a\":1}");
}

TEST(WebHttpResponseTest, ExternalBodyAndHead) {
  static constexpr std::uint8_t kAsset[] = {1, 2, 3, 4, 5};
  std::array<std::uint8_t, 256> buffer{};
  HttpResponseWriter writer(buffer);
  writer.Start(HttpStatus::kOk);
  writer.ExternalBody(kAsset);
  writer.Finish(false, false);
  EXPECT_EQ(Text(writer.head()), "HTTP/1.1 200 OK\r\nContent-Length: 5\r\nConnection: close\r\n\r\n");
  EXPECT_EQ(writer.external_body().size(), 5U);

  writer.Start(HttpStatus::kOk);
  writer.ExternalBody(kAsset);
  writer.Finish(true, true);  // HEAD: the length GET would carry, no body
  EXPECT_EQ(Text(writer.head()), "HTTP/1.1 200 OK\r\nContent-Length: 5\r\nConnection: keep-alive\r\n\r\n");
  EXPECT_TRUE(writer.external_body().empty());
}

TEST(WebHttpResponseTest, NoContentAndNotModifiedCarryNoLength) {
  std::array<std::uint8_t, 128> buffer{};
  HttpResponseWriter writer(buffer);
  writer.Start(HttpStatus::kNoContent);
  writer.Finish(false, true);
  EXPECT_EQ(Text(writer.head()), "HTTP/1.1 204 No Content\r\nConnection: keep-alive\r\n\r\n");
  writer.Start(HttpStatus::kNotModified);
  writer.Header("ETag", "\"abc\"");
  writer.Finish(false, true);
  EXPECT_EQ(Text(writer.head()), "HTTP/1.1 304 Not Modified\r\nETag: \"abc\"\r\nConnection: keep-alive\r\n\r\n");
}

TEST(WebHttpResponseTest, TooLargeBecomesBodiless500) {
  std::array<std::uint8_t, 96> buffer{};
  HttpResponseWriter writer(buffer);
  writer.Start(HttpStatus::kOk);
  writer.BodyText(std::string(200, 'x'));
  writer.Finish(false, true);
  EXPECT_TRUE(writer.overflowed());
  EXPECT_EQ(writer.status(), HttpStatus::kInternalError);
  EXPECT_EQ(Text(writer.head()),
            "HTTP/1.1 500 Internal Server Error\r\nContent-Length: 0\r\nConnection: close\r\n\r\n");
}

// --- JSON ---------------------------------------------------------------------------------------------

TEST(WebJsonTest, WriterPlacesCommasAndEscapes) {
  std::array<std::uint8_t, 128> buffer{};
  JsonWriter json(buffer);
  json.BeginObject().Key("n").Number(-42).Key("s").String("a\"b\\c\n").Key("l").BeginArray();
  json.Number(1).Bool(true).Null().Hex4(0xC500).EndArray().Key("o").BeginObject().EndObject().EndObject();
  ASSERT_FALSE(json.overflowed());
  EXPECT_EQ(std::string(buffer.begin(), buffer.begin() + static_cast<std::ptrdiff_t>(json.size())),
            R"({"n":-42,"s":"a\"b\\c\u000a","l":[1,true,null,"C500"],"o":{}})");
}

TEST(WebJsonTest, WriterStopsAtTheEnd) {
  std::array<std::uint8_t, 8> buffer{};
  JsonWriter json(buffer);
  json.BeginObject().Key("password").String("x").EndObject();
  EXPECT_TRUE(json.overflowed());
  EXPECT_EQ(json.size(), 8U);
}

TEST(WebJsonTest, ReaderTakesAFlatObject) {
  JsonObject object;
  ASSERT_TRUE(ParseFlatJsonObject(Bytes(R"( { "number" : "0009", "value":-100,"ok":true,"x":null } )"), object));
  EXPECT_EQ(object.count, 4U);
  EXPECT_EQ(object.StringOf("number"), std::optional<std::string_view>("0009"));
  EXPECT_EQ(object.IntegerOf("value"), std::optional<std::int64_t>(-100));
  EXPECT_EQ(object.BoolOf("ok"), std::optional<bool>(true));
  EXPECT_EQ(object.IntegerOf("number"), std::nullopt);  // wrong kind
  EXPECT_EQ(object.StringOf("missing"), std::nullopt);
  ASSERT_TRUE(ParseFlatJsonObject(Bytes("{}"), object));
  EXPECT_EQ(object.count, 0U);
}

TEST(WebJsonTest, ReaderRefusesWhatTheApiNeverSends) {
  const char* refused[] = {
      "",                                   // nothing
      "[1]",                                // not an object
      R"({"a":{"b":1}})",                   // nesting
      R"({"a":[1]})",                       // arrays
      R"({"a":1.5})",                       // fractions
      R"({"a":1e3})",                       // exponents
      R"({"a":01})",                        // leading zero
      R"({"a":9007199254740993})",          // beyond 2^53
      R"({"a":"x\"y"})",                    // escapes
      R"({"a":1,"a":2})",                   // repeated key
      R"({"a":1} x)",                       // trailing data
      R"({"a":1,})",                        // trailing comma
      R"({"a" 1})",                         // no colon
      R"({"a":tru})",                       // broken literal
      R"({"a":"unterminated)",              // no closing quote
      R"({"1":1,"2":2,"3":3,"4":4,"5":5,"6":6,"7":7,"8":8,"9":9})",  // more than 8 members
  };
  for (const char* text : refused) {
    JsonObject object;
    EXPECT_FALSE(ParseFlatJsonObject(Bytes(text), object)) << text;
  }
  JsonObject object;
  EXPECT_FALSE(ParseFlatJsonObject(Bytes("{\"a\":\"" + std::string(65, 'x') + "\"}"), object));
  EXPECT_TRUE(ParseFlatJsonObject(Bytes("{\"a\":\"" + std::string(64, 'x') + "\"}"), object));
}

// --- HttpServer ---------------------------------------------------------------------------------------

// Answers "/ok" with a JSON body, "/later" only after `release` is set, anything else 404.
class ScriptedHandler final : public HttpHandler {
 public:
  HandlerResult Handle(HttpClientId client, const HttpRequest& request, HttpResponseWriter& response,
                       hal::Micros) override {
    ++calls;
    if (request.path == "/later" && !release) return HandlerResult::kPending;
    if (request.path == "/ok" || request.path == "/later") {
      response.Start(HttpStatus::kOk);
      response.BodyText(std::string(request.path.substr(1)) + std::to_string(client));
      return HandlerResult::kDone;
    }
    if (request.path == "/big") {
      response.Start(HttpStatus::kOk);
      response.BodyText(std::string(kHttpResponseBufferBytes, 'x'));
      return HandlerResult::kDone;
    }
    if (request.path == "/fill") {
      // The whole response buffer, to the byte: `fill` body bytes after the head.
      response.Start(HttpStatus::kOk);
      response.BodyText(std::string(fill, 'f'));
      return HandlerResult::kDone;
    }
    if (request.path == "/stream") {
      response.Start(HttpStatus::kOk);
      response.StreamedBody(stream);
      return HandlerResult::kDone;
    }
    if (request.path == "/asset") {
      response.Start(HttpStatus::kOk);
      response.ExternalBody(std::span<const std::uint8_t>(kAsset.data(), kAsset.size()));
      return HandlerResult::kDone;
    }
    response.Start(HttpStatus::kNotFound);
    return HandlerResult::kDone;
  }
  void OnClientClosed(HttpClientId client) override { closed_pending = client; }
  hal::Micros NextDeadline() const override { return release ? 0 : hal::kNever; }

  // A body of `size` bytes, byte i = i mod 251, that ends early (returns nothing) from `ends_at` on.
  class PatternSource final : public HttpBodySource {
   public:
    std::uint32_t Size() const override { return size; }
    std::size_t ReadAt(std::uint32_t offset, std::span<std::uint8_t> out) const override {
      std::size_t count = 0;
      for (; count < out.size() && offset + count < std::min(size, ends_at); ++count) {
        out[count] = static_cast<std::uint8_t>((offset + count) % 251);
      }
      largest_read = std::max(largest_read, out.size());
      return count;
    }
    std::uint32_t size = 10000;
    std::uint32_t ends_at = 0xFFFFFFFF;
    mutable std::size_t largest_read = 0;
  };

  static constexpr std::array<std::uint8_t, 5> kAsset = {'a', 's', 's', 'e', 't'};
  PatternSource stream;
  int calls = 0;
  bool release = false;
  int closed_pending = -1;
  std::size_t fill = 0;
};

class WebHttpServerTest : public ::testing::Test {
 protected:
  // Everything the server has to send, as the transport would take it.
  std::string Drain(HttpClientId id) {
    std::string out;
    for (auto chunk = server.PendingOutput(id); !chunk.empty(); chunk = server.PendingOutput(id)) {
      out += Text(chunk);
      server.ConsumeOutput(id, chunk.size(), now);
    }
    return out;
  }
  HttpClientId OpenClient() {
    auto id = server.Open(now);
    EXPECT_TRUE(id.ok());
    return *id;
  }

  ScriptedHandler handler;
  HttpServer server{handler};
  hal::Micros now = 1'000'000;
};

TEST_F(WebHttpServerTest, KeepAliveServesPipelinedRequestsInOrder) {
  const HttpClientId id = OpenClient();
  const std::string two = "GET /ok HTTP/1.1\r\nHost: a\r\n\r\nGET /nope HTTP/1.1\r\nHost: a\r\n\r\n";
  EXPECT_EQ(server.Receive(id, Bytes(two), now), two.size());
  EXPECT_EQ(Drain(id),
            "HTTP/1.1 200 OK\r\nContent-Length: 3\r\nConnection: keep-alive\r\n\r\nok0"
            "HTTP/1.1 404 Not Found\r\nContent-Length: 0\r\nConnection: keep-alive\r\n\r\n");
  EXPECT_FALSE(server.MustClose(id));
  EXPECT_EQ(server.counters().requests, 2U);
  EXPECT_EQ(server.counters().responses_by_class[2], 1U);
  EXPECT_EQ(server.counters().responses_by_class[4], 1U);
}

TEST_F(WebHttpServerTest, ConnectionCloseClosesAfterTheAnswer) {
  const HttpClientId id = OpenClient();
  server.Receive(id, Bytes("GET /ok HTTP/1.1\r\nHost: a\r\nConnection: close\r\n\r\n"), now);
  EXPECT_FALSE(server.MustClose(id));  // the answer goes first
  EXPECT_EQ(Drain(id), "HTTP/1.1 200 OK\r\nContent-Length: 3\r\nConnection: close\r\n\r\nok0");
  EXPECT_TRUE(server.MustClose(id));
}

TEST_F(WebHttpServerTest, MalformedRequestGetsItsStatusAndCloses) {
  const HttpClientId id = OpenClient();
  server.Receive(id, Bytes("GET /ok HTTP/2.0\r\nHost: a\r\n\r\nGET /ok HTTP/1.1\r\nHost: a\r\n\r\n"), now);
  EXPECT_EQ(Drain(id),
            "HTTP/1.1 505 HTTP Version Not Supported\r\nContent-Type: application/json\r\nContent-Length: 38\r\n"
            "Connection: close\r\n\r\n{\"error\":\"HTTP Version Not Supported\"}");
  EXPECT_TRUE(server.MustClose(id));
  EXPECT_EQ(handler.calls, 0);  // the request behind it is never served
}

TEST_F(WebHttpServerTest, PendingAnswerWaitsAndHoldsTheNextRequest) {
  const HttpClientId id = OpenClient();
  server.Receive(id, Bytes("GET /later HTTP/1.1\r\nHost: a\r\n\r\nGET /ok HTTP/1.1\r\nHost: a\r\n\r\n"), now);
  EXPECT_TRUE(server.PendingOutput(id).empty());
  EXPECT_EQ(server.NextDeadline(), hal::kNever);  // the handler's deadline (nothing due), no timers apply
  server.Poll(now + 1);
  EXPECT_TRUE(server.PendingOutput(id).empty());
  handler.release = true;
  EXPECT_EQ(server.NextDeadline(), 0);
  server.Poll(now + 2);
  EXPECT_EQ(Drain(id),
            "HTTP/1.1 200 OK\r\nContent-Length: 6\r\nConnection: keep-alive\r\n\r\nlater0"
            "HTTP/1.1 200 OK\r\nContent-Length: 3\r\nConnection: keep-alive\r\n\r\nok0");
}

TEST_F(WebHttpServerTest, ClosingWithAPendingRequestTellsTheHandler) {
  const HttpClientId id = OpenClient();
  server.Receive(id, Bytes("GET /later HTTP/1.1\r\nHost: a\r\n\r\n"), now);
  server.Close(id);
  EXPECT_EQ(handler.closed_pending, id);
  EXPECT_FALSE(server.IsOpen(id));
}

TEST_F(WebHttpServerTest, AnAnswerTooLargeIs500AndCloses) {
  const HttpClientId id = OpenClient();
  server.Receive(id, Bytes("GET /big HTTP/1.1\r\nHost: a\r\n\r\n"), now);
  EXPECT_EQ(Drain(id), "HTTP/1.1 500 Internal Server Error\r\nContent-Length: 0\r\nConnection: close\r\n\r\n");
  EXPECT_TRUE(server.MustClose(id));
  EXPECT_EQ(server.counters().overflows, 1U);
}

TEST_F(WebHttpServerTest, SlotsAreLimitedAndTheLongestIdleIsEvictable) {
  std::array<HttpClientId, kMaxHttpClients> ids{};
  for (std::size_t i = 0; i < kMaxHttpClients; ++i) {
    now += 10;
    ids[i] = OpenClient();
  }
  EXPECT_EQ(server.Open(now).status().code(), base::StatusCode::kResourceExhausted);
  // Client 0 is busy with a partial request, client 1 is the longest idle one.
  server.Receive(ids[0], Bytes("GET /ok HT"), now);
  EXPECT_EQ(server.IdleClientToEvict(), std::optional<HttpClientId>(ids[1]));
  server.Close(ids[1]);
  EXPECT_EQ(*server.Open(now), ids[1]);
  EXPECT_EQ(server.open_clients(), kMaxHttpClients);
  EXPECT_EQ(server.client_pool(), (base::PoolStats{kMaxHttpClients, kMaxHttpClients, kMaxHttpClients, 1}));
  for (HttpClientId id : ids) server.Close(id);
  EXPECT_EQ(server.client_pool(), (base::PoolStats{0, kMaxHttpClients, kMaxHttpClients, 1}));
  EXPECT_EQ(Text(HttpServer::BusyResponse()),
            "HTTP/1.1 503 Service Unavailable\r\nContent-Type: application/json\r\nRetry-After: 1\r\n"
            "Content-Length: 23\r\nConnection: close\r\n\r\n{\"error\":\"server busy\"}");
}

TEST_F(WebHttpServerTest, SlowRequestTimesOutWith408AndIdleConnectionsClose) {
  const HttpClientId slow = OpenClient();
  const HttpClientId idle = OpenClient();
  server.Receive(slow, Bytes("GET / HTTP/1.1\r\n"), now);
  EXPECT_EQ(server.NextDeadline(), now + kRequestTimeout);
  server.Poll(now + kRequestTimeout - 1);
  EXPECT_TRUE(server.PendingOutput(slow).empty());
  server.Poll(now + kRequestTimeout);
  EXPECT_EQ(Drain(slow),
            "HTTP/1.1 408 Request Timeout\r\nContent-Type: application/json\r\nContent-Length: 27\r\n"
            "Connection: close\r\n\r\n{\"error\":\"Request Timeout\"}");
  EXPECT_TRUE(server.MustClose(slow));
  server.Poll(now + kIdleTimeout - 1);
  EXPECT_FALSE(server.MustClose(idle));
  server.Poll(now + kIdleTimeout);
  EXPECT_TRUE(server.MustClose(idle));
  EXPECT_EQ(server.counters().request_timeouts, 1U);
  EXPECT_EQ(server.counters().idle_closed, 1U);
}

TEST_F(WebHttpServerTest, WindowReopensWhileTheBufferCanStillTakeAWholeWindow) {
  constexpr std::size_t kWindow = 536;  // lwIP's TCP_WND
  const HttpClientId id = OpenClient();
  // A POST with a body at its limit (512 bytes): larger than one window with its head, so the window must
  // reopen before it is served.
  const std::string head = "POST /ok HTTP/1.1\r\nHost: a\r\nContent-Length: 512\r\n\r\n";
  const std::string body(kMaxBody, 'b');
  const std::string request = head + body;
  ASSERT_GT(request.size(), kWindow);
  server.Receive(id, Bytes(std::string_view(request).substr(0, kWindow)), now);
  EXPECT_EQ(server.TakeReleasedInput(id, kWindow), kWindow);  // 2832 - 536 free: a window still fits
  server.Receive(id, Bytes(std::string_view(request).substr(kWindow)), now);
  EXPECT_EQ(server.TakeReleasedInput(id, kWindow), request.size() - kWindow);
  EXPECT_EQ(Drain(id), "HTTP/1.1 200 OK\r\nContent-Length: 3\r\nConnection: keep-alive\r\n\r\nok0");
  EXPECT_EQ(server.TakeReleasedInput(id, kWindow), 0U);
}

TEST_F(WebHttpServerTest, WindowStaysShutWhenTheBufferIsNearlyFull) {
  constexpr std::size_t kWindow = 536;  // lwIP's TCP_WND
  const HttpClientId id = OpenClient();
  // Held: a pending request, and pipelined bytes behind it.
  const std::string later = "GET /later HTTP/1.1\r\nHost: a\r\nX: " + std::string(1500, 'y') + "\r\n\r\n";
  server.Receive(id, Bytes(later), now);
  EXPECT_EQ(server.TakeReleasedInput(id, kWindow), later.size());
  server.Receive(id, Bytes(std::string(1000, 'z')), now);
  // 2832 - 2537 free = 295 < a window: only what keeps a window's room may be released.
  const std::size_t free_space = kHttpReceiveBufferBytes - later.size() - 1000;
  ASSERT_EQ(free_space, 295U);
  EXPECT_EQ(server.TakeReleasedInput(id, kWindow), 1000 - (kWindow - free_space));
}

// --- Response buffers (shared by the connections) --------------------------------------------------

// The head of a 200 answer with a body of `body` bytes on a keep-alive connection.
std::string OkHead(std::size_t body) {
  return "HTTP/1.1 200 OK\r\nContent-Length: " + std::to_string(body) + "\r\nConnection: keep-alive\r\n\r\n";
}

TEST_F(WebHttpServerTest, AnAnswerFillingTheResponseBufferExactlyIsSentOneMoreByteIs500) {
  static_assert(kHttpResponseBuffers == 1);
  const std::size_t head = OkHead(4000).size();
  handler.fill = kHttpResponseBufferBytes - head;
  const HttpClientId id = OpenClient();
  server.Receive(id, Bytes("GET /fill HTTP/1.1\r\nHost: a\r\n\r\n"), now);
  const std::string answer = Drain(id);
  EXPECT_EQ(answer.size(), kHttpResponseBufferBytes);
  EXPECT_EQ(answer, OkHead(handler.fill) + std::string(handler.fill, 'f'));
  EXPECT_FALSE(server.MustClose(id));
  ++handler.fill;
  server.Receive(id, Bytes("GET /fill HTTP/1.1\r\nHost: a\r\n\r\n"), now);
  EXPECT_EQ(Drain(id), "HTTP/1.1 500 Internal Server Error\r\nContent-Length: 0\r\nConnection: close\r\n\r\n");
  EXPECT_TRUE(server.MustClose(id));
  EXPECT_EQ(server.counters().overflows, 1U);
}

TEST_F(WebHttpServerTest, AnAnswerWaitsWhileAnotherHoldsTheResponseBuffer) {
  handler.fill = 2000;
  const HttpClientId first = OpenClient();
  const HttpClientId second = OpenClient();
  server.Receive(first, Bytes("GET /fill HTTP/1.1\r\nHost: a\r\n\r\n"), now);
  ASSERT_FALSE(server.PendingOutput(first).empty());
  // The transport takes only part of the first answer (its send buffer is full): the buffer stays taken.
  server.ConsumeOutput(first, 1000, now);
  server.Receive(second, Bytes("GET /ok HTTP/1.1\r\nHost: a\r\n\r\n"), now);
  EXPECT_TRUE(server.PendingOutput(second).empty());
  EXPECT_EQ(server.counters().response_waits, 1U);
  EXPECT_EQ(server.response_pool(), (base::PoolStats{1, kHttpResponseBuffers, 1, 1}));
  EXPECT_EQ(server.NextDeadline(), now + kRequestTimeout);  // nothing to do until the first answer leaves
  server.Poll(now + 1);
  EXPECT_TRUE(server.PendingOutput(second).empty());
  EXPECT_EQ(server.counters().response_waits, 1U);  // counted once per answer
  // The rest of the first answer goes to TCP: the buffer is free and the second answer is due at once.
  const std::string rest = Drain(first);
  EXPECT_EQ(rest.size(), OkHead(2000).size() + 2000 - 1000);
  EXPECT_EQ(server.response_pool().used, 0U);
  EXPECT_EQ(server.NextDeadline(), 0);
  server.Poll(now + 2);
  EXPECT_EQ(Drain(second), OkHead(3) + "ok1");
  EXPECT_EQ(server.response_pool(), (base::PoolStats{0, kHttpResponseBuffers, 1, 1}));
}

TEST_F(WebHttpServerTest, AnAnswerLeftInTheBufferForTheRequestTimeoutClosesItsConnection) {
  handler.fill = 2000;
  const HttpClientId stuck = OpenClient();
  const HttpClientId other = OpenClient();
  server.Receive(stuck, Bytes("GET /fill HTTP/1.1\r\nHost: a\r\n\r\n"), now);
  server.Receive(other, Bytes("GET /ok HTTP/1.1\r\nHost: a\r\n\r\n"), now);
  EXPECT_TRUE(server.PendingOutput(other).empty());
  server.Poll(now + kRequestTimeout - 1);
  EXPECT_FALSE(server.MustClose(stuck));
  server.Poll(now + kRequestTimeout);
  EXPECT_TRUE(server.MustClose(stuck));
  EXPECT_EQ(server.counters().answer_timeouts, 1U);
  server.Close(stuck);  // what the transport does when MustClose says so
  EXPECT_EQ(server.NextDeadline(), 0);
  server.Poll(now + kRequestTimeout + 1);
  EXPECT_EQ(Drain(other), OkHead(3) + "ok1");
}

TEST_F(WebHttpServerTest, AnAssetHoldsTheResponseBufferOnlyForItsHead) {
  const HttpClientId asset = OpenClient();
  const HttpClientId other = OpenClient();
  server.Receive(asset, Bytes("GET /asset HTTP/1.1\r\nHost: a\r\n\r\n"), now);
  const std::span<const std::uint8_t> head = server.PendingOutput(asset);
  EXPECT_EQ(Text(head), OkHead(5));
  server.ConsumeOutput(asset, head.size(), now);
  // The body is sent from where it is: the buffer is free while it goes.
  EXPECT_TRUE(server.PendingOutputIsStatic(asset));
  EXPECT_EQ(server.response_pool().used, 0U);
  server.Receive(other, Bytes("GET /ok HTTP/1.1\r\nHost: a\r\n\r\n"), now);
  EXPECT_EQ(Drain(other), OkHead(3) + "ok1");
  EXPECT_EQ(Drain(asset), "asset");
  EXPECT_EQ(server.counters().response_waits, 0U);
}

TEST_F(WebHttpServerTest, AnErrorAnswerWaitsForTheResponseBufferToo) {
  handler.fill = 2000;
  const HttpClientId holder = OpenClient();
  const HttpClientId bad = OpenClient();
  server.Receive(holder, Bytes("GET /fill HTTP/1.1\r\nHost: a\r\n\r\n"), now);
  server.Receive(bad, Bytes("GET /ok HTTP/2.0\r\nHost: a\r\n\r\n"), now);
  EXPECT_TRUE(server.PendingOutput(bad).empty());
  EXPECT_EQ(server.counters().parse_errors, 0U);
  Drain(holder);
  server.Poll(now + 1);
  EXPECT_EQ(Drain(bad),
            "HTTP/1.1 505 HTTP Version Not Supported\r\nContent-Type: application/json\r\nContent-Length: 38\r\n"
            "Connection: close\r\n\r\n{\"error\":\"HTTP Version Not Supported\"}");
  EXPECT_EQ(server.counters().parse_errors, 1U);
  EXPECT_TRUE(server.MustClose(bad));
}

TEST_F(WebHttpServerTest, APendingAnswerHoldsNoResponseBuffer) {
  const HttpClientId later = OpenClient();
  const HttpClientId other = OpenClient();
  server.Receive(later, Bytes("GET /later HTTP/1.1\r\nHost: a\r\n\r\n"), now);
  EXPECT_EQ(server.response_pool().used, 0U);
  server.Receive(other, Bytes("GET /ok HTTP/1.1\r\nHost: a\r\n\r\n"), now);
  EXPECT_EQ(Drain(other), OkHead(3) + "ok1");
  handler.release = true;
  server.Poll(now + 1);
  EXPECT_EQ(Drain(later), OkHead(6) + "later0");
}

}  // namespace
}  // namespace web

namespace web {
namespace {

std::string Pattern(std::size_t size) {
  std::string text;
  for (std::size_t i = 0; i < size; ++i) text.push_back(static_cast<char>(i % 251));
  return text;
}

// Takes a streamed answer as a transport with `room` bytes of send buffer per write would.
std::string DrainStream(HttpServer& server, HttpClientId id, std::size_t room, hal::Micros now) {
  std::string out;
  for (;;) {
    server.LoadStreamChunk(id, room, now);
    const auto chunk = server.PendingOutput(id);
    if (chunk.empty()) break;
    const std::size_t count = std::min(chunk.size(), room);
    out.append(chunk.begin(), chunk.begin() + static_cast<std::ptrdiff_t>(count));
    server.ConsumeOutput(id, count, now);
  }
  return out;
}

TEST_F(WebHttpServerTest, StreamedBodyArrivesWholeInChunksOfTheRoomOffered) {
  const HttpClientId id = OpenClient();
  server.Receive(id, Bytes("GET /stream HTTP/1.1\r\nHost: a\r\n\r\n"), now);
  const std::string answer = DrainStream(server, id, 536, now);
  EXPECT_EQ(answer, "HTTP/1.1 200 OK\r\nContent-Length: 10000\r\nConnection: keep-alive\r\n\r\n" + Pattern(10000));
  EXPECT_EQ(handler.stream.largest_read, 536U);
  EXPECT_EQ(server.response_pool().used, 0U);
  // The connection serves its next request afterwards.
  server.Receive(id, Bytes("GET /ok HTTP/1.1\r\nHost: a\r\n\r\n"), now);
  EXPECT_EQ(Drain(id), OkHead(3) + "ok0");
}

TEST_F(WebHttpServerTest, StreamedBodyLetsOtherAnswersTakeTheBufferBetweenChunks) {
  const HttpClientId streaming = OpenClient();
  const HttpClientId other = OpenClient();
  server.Receive(streaming, Bytes("GET /stream HTTP/1.1\r\nHost: a\r\n\r\n"), now);
  const auto head = server.PendingOutput(streaming);
  server.ConsumeOutput(streaming, head.size(), now);
  server.LoadStreamChunk(streaming, 1000, now);
  ASSERT_EQ(server.PendingOutput(streaming).size(), 1000U);
  // While a chunk is in the buffer, another answer waits; once the chunk is with TCP it is served.
  server.Receive(other, Bytes("GET /ok HTTP/1.1\r\nHost: a\r\n\r\n"), now);
  EXPECT_TRUE(server.PendingOutput(other).empty());
  server.ConsumeOutput(streaming, 1000, now);
  server.Poll(now);
  const auto other_answer = server.PendingOutput(other);
  ASSERT_FALSE(other_answer.empty());
  // ... and the stream waits for the buffer in turn.
  server.LoadStreamChunk(streaming, 1000, now);
  EXPECT_TRUE(server.PendingOutput(streaming).empty());
  EXPECT_EQ(Drain(other), OkHead(3) + "ok1");
  EXPECT_EQ(DrainStream(server, streaming, 4096, now), Pattern(10000).substr(1000));
  EXPECT_EQ(server.counters().response_waits, 2U);
}

TEST_F(WebHttpServerTest, StreamedBodyOfHeadIsNotSentAndAShortSourceCloses) {
  const HttpClientId head = OpenClient();
  server.Receive(head, Bytes("HEAD /stream HTTP/1.1\r\nHost: a\r\n\r\n"), now);
  EXPECT_EQ(DrainStream(server, head, 4096, now), "HTTP/1.1 200 OK\r\nContent-Length: 10000\r\nConnection: keep-alive\r\n\r\n");
  handler.stream.ends_at = 40;
  const HttpClientId id = OpenClient();
  server.Receive(id, Bytes("GET /stream HTTP/1.1\r\nHost: a\r\n\r\n"), now);
  EXPECT_EQ(DrainStream(server, id, 4096, now),
            "HTTP/1.1 200 OK\r\nContent-Length: 10000\r\nConnection: keep-alive\r\n\r\n" + Pattern(40));
  EXPECT_TRUE(server.MustClose(id));
  EXPECT_EQ(server.response_pool().used, 0U);
}

}  // namespace
}  // namespace web
