// firmware::WebService on lwIP: HTTP clients written on lwIP's raw API talk to a web::HttpServer through the
// lwIP binding, over two netifs wired back to back (lwip_tcp_pair.h). Exact bytes at the limits that lwIP
// and the server's buffers set together: a request at its limits through windows of TCP_WND, one byte
// more, the connection beyond the slots. The HTTP rules themselves are the core's tests.
#include "web_service.h"

#include <gtest/gtest.h>

#include <string>
#include <string_view>

#include "lwip_tcp_pair.h"

namespace firmware {
namespace {

using test::Bytes;
using test::TcpTestClient;

constexpr std::uint16_t kPort = 80;

Bytes Of(std::string_view text) { return Bytes(text.begin(), text.end()); }
std::string Text(const Bytes& bytes) { return std::string(bytes.begin(), bytes.end()); }

// Answers every request "ok" with the size of its body.
class BodySizeHandler final : public web::HttpHandler {
 public:
  web::HandlerResult Handle(web::HttpClientId, const web::HttpRequest& request, web::HttpResponseWriter& response,
                            hal::Micros) override {
    response.Start(web::HttpStatus::kOk);
    response.BodyText("ok " + std::to_string(request.body.size()));
    return web::HandlerResult::kDone;
  }
  void OnClientClosed(web::HttpClientId) override {}
  hal::Micros NextDeadline() const override { return hal::kNever; }
};

class WebServiceTest : public test::LwipPairTest {
 protected:
  void SetUp() override {
    StartNetifs();
    ASSERT_TRUE(service_.Start().ok());
    Pump();
  }
  void TearDown() override {
    CloseClients();
    service_.Stop();
  }
  void PollServices() override { service_.Poll(clock().NowMicros()); }

  // Sends `bytes` in pieces as the client's send buffer (TCP_SND_BUF) takes them.
  void SendAll(TcpTestClient& client, const Bytes& bytes) {
    std::size_t sent = 0;
    for (int round = 0; round < 100 && sent < bytes.size(); ++round) {
      const std::size_t count = std::min<std::size_t>(bytes.size() - sent, tcp_sndbuf(client.pcb));
      if (count > 0) {
        ASSERT_EQ(tcp_write(client.pcb, bytes.data() + sent, static_cast<u16_t>(count), TCP_WRITE_FLAG_COPY), ERR_OK);
        ASSERT_EQ(tcp_output(client.pcb), ERR_OK);
        sent += count;
      }
      Pump();
    }
    ASSERT_EQ(sent, bytes.size());
  }

  BodySizeHandler handler_;
  web::HttpServer server_{handler_};
  WebService service_{server_, clock()};
};

// A POST whose header block is exactly kMaxHeaderBlock (2048) bytes and whose body is kMaxBody (512):
// 2560 bytes, almost five windows. The server reopens the window as its buffer allows; lwIP announces a
// reopened window only in steps of half a window, which the buffer's slack beyond a whole request covers.
Bytes LargestPost(std::size_t body_size) {
  const std::string head = "POST /x HTTP/1.1\r\nHost: card\r\nContent-Length: " + std::to_string(body_size) + "\r\nX: ";
  std::string request = head + std::string(web::kMaxHeaderBlock - head.size() - 4, 'h') + "\r\n\r\n";
  request += std::string(body_size, 'b');
  return Of(request);
}

TEST_F(WebServiceTest, LargestRequestArrivesThroughTheWindows) {
  TcpTestClient& client = Connect(kPort);
  const Bytes request = LargestPost(web::kMaxBody);
  ASSERT_EQ(request.size(), web::kMaxHeaderBlock + web::kMaxBody);
  ASSERT_GT(request.size(), 4U * TCP_WND);
  SendAll(client, request);
  EXPECT_EQ(Text(client.received), "HTTP/1.1 200 OK\r\nContent-Length: 6\r\nConnection: keep-alive\r\n\r\nok 512");
  EXPECT_FALSE(client.peer_closed);
}

TEST_F(WebServiceTest, BodyOneByteOverTheLimit_413ThenClosed) {
  TcpTestClient& client = Connect(kPort);
  // The header announces kMaxBody + 1: refused as soon as the header block is whole.
  Bytes request = LargestPost(web::kMaxBody + 1);
  request.resize(web::kMaxHeaderBlock);
  SendAll(client, request);
  EXPECT_EQ(Text(client.received),
            "HTTP/1.1 413 Content Too Large\r\nContent-Type: application/json\r\nContent-Length: 29\r\n"
            "Connection: close\r\n\r\n{\"error\":\"Content Too Large\"}");
  EXPECT_TRUE(client.peer_closed);
}

TEST_F(WebServiceTest, HeaderBlockOneByteOverTheLimit_431ThenClosed) {
  TcpTestClient& client = Connect(kPort);
  const std::string head = "GET / HTTP/1.1\r\nHost: card\r\nX: ";
  const std::string request = head + std::string(web::kMaxHeaderBlock - head.size() - 3, 'h') + "\r\n\r\n";
  ASSERT_EQ(request.size(), web::kMaxHeaderBlock + 1);
  SendAll(client, Of(request));
  EXPECT_EQ(Text(client.received),
            "HTTP/1.1 431 Request Header Fields Too Large\r\nContent-Type: application/json\r\n"
            "Content-Length: 43\r\nConnection: close\r\n\r\n{\"error\":\"Request Header Fields Too Large\"}");
  EXPECT_TRUE(client.peer_closed);
}

TEST_F(WebServiceTest, ConnectionBeyondThreeBusyOnes_503ThenClosed) {
  std::vector<TcpTestClient*> busy;
  for (std::size_t i = 0; i < web::kMaxHttpClients; ++i) {
    TcpTestClient& client = Connect(kPort);
    ASSERT_TRUE(client.connected) << i;
    Send(client, Of("GET / HTTP/1.1\r\n"));  // a request under way: the slot is busy
    busy.push_back(&client);
  }
  TcpTestClient& extra = Connect(kPort);
  EXPECT_EQ(Text(extra.received),
            "HTTP/1.1 503 Service Unavailable\r\nContent-Type: application/json\r\nRetry-After: 1\r\n"
            "Content-Length: 23\r\nConnection: close\r\n\r\n{\"error\":\"server busy\"}");
  EXPECT_TRUE(extra.peer_closed);
  EXPECT_EQ(service_.counters().refused_busy, 1U);
  constexpr std::size_t kMax = web::kMaxHttpClients;
  EXPECT_EQ(service_.slot_pool(), (base::PoolStats{kMax, kMax, kMax, 1}));
  // The busy ones are still served.
  for (TcpTestClient* client : busy) {
    Send(*client, Of("Host: card\r\n\r\n"));
    EXPECT_EQ(Text(client->received), "HTTP/1.1 200 OK\r\nContent-Length: 4\r\nConnection: keep-alive\r\n\r\nok 0");
  }
}

}  // namespace
}  // namespace firmware
