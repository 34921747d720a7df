// The card's web application through the HTTP connection core: exact status codes and JSON for every
// API call, access rules (session, CSRF, write level, back-off), deferred register reads and writes over
// a scripted drive, the monitor's refresh rule, and the embedded page (docs/web.md "JSON API").
#include "web_application.h"

#include <gtest/gtest.h>

#include <string>
#include <string_view>
#include <vector>

#include "cip/byte_span_file.h"
#include "drive_link/drive_registers.h"
#include "drive_registers_fake.h"
#include "web/assets.h"
#include "web/http_server.h"
#include "web/password_store.h"
#include "web_fakes.h"

namespace firmware {
namespace {

using drive_link::AccessError;

class FakeScanner final : public drive_link::ScannerImage, public drive_link::LossSupervision {
 public:
  void SetCommandWords(const drive_link::ScannerWords& words) override { command = words; }
  drive_link::ScannerWords CommandWords() const override { return command; }
  drive_link::ScannerWords MonitorWords() const override { return monitor; }
  bool IsScannerTarget(std::uint16_t) const override { return false; }
  void NetworkLost(drive_link::LossCause, hal::Micros) override {}
  void NetworkRestored(hal::Micros) override {}
  bool loss_action_active() const override { return false; }

  drive_link::ScannerWords command{0xC400, 5000, 0, 0, 0, 0};
  drive_link::ScannerWords monitor{0x0400, 4321, 0, 0, 0, 0};
};

class FakeCardStatus final : public WebCardStatus {
 public:
  const config::CardConfig& config() const override { return card_config; }
  config::CardStatus card_status() const override { return status; }
  const char* drive_link_state() const override { return "up"; }
  const char* drive_model() const override { return "vf-s15"; }
  void WriteLeds(web::JsonWriter& json) const override {
    json.BeginObject().Key("ms").String("green").EndObject();
  }
  void WriteConnections(web::JsonWriter& json) const override { json.BeginArray().EndArray(); }
  void WriteStatistics(web::JsonWriter& json) const override {
    json.BeginObject().Key("ports").BeginArray().EndArray().EndObject();
  }

  config::CardConfig card_config;
  config::CardStatus status;
};

class WebApplicationTest : public ::testing::Test {
 protected:
  WebApplicationTest() {
    EXPECT_TRUE(passwords.Load().ok());
    drive.registers = {{0x0009, 100}, {0x0010, 200}, {0xC500, 0}, {0xFD00, 1234}, {0xFD01, 0x0400}};
    card.card_config.device_name = {'d', 'r', 'i', 'v', 'e', '1'};
    card.status.mac = {0x02, 0x00, 0x5e, 0x10, 0x20, 0x30};
    card.status.ip = {10, 0, 0, 5};
  }

  // Sends one request on a fresh connection, runs the drive (completing every access) and the
  // application until the answer is there; returns the whole answer.
  std::string Exchange(const std::string& request) {
    const auto id = server.Open(now);
    EXPECT_TRUE(id.ok());
    server.Receive(*id, Bytes(request), now);
    for (int i = 0; i < 100 && server.PendingOutput(*id).empty(); ++i) {
      now += 1000;
      application.Poll(now);
      drive.CompleteAll();
      server.Poll(now);
    }
    std::string answer;
    // As the transport takes it: a streamed body in chunks of the send buffer's room (700 bytes here).
    server.LoadStreamChunk(*id, 700, now);
    for (auto chunk = server.PendingOutput(*id); !chunk.empty(); chunk = server.PendingOutput(*id)) {
      answer.append(chunk.begin(), chunk.end());
      server.ConsumeOutput(*id, chunk.size(), now);
      server.LoadStreamChunk(*id, 700, now);
    }
    server.Close(*id);
    return answer;
  }
  static std::span<const std::uint8_t> Bytes(const std::string& text) {
    return {reinterpret_cast<const std::uint8_t*>(text.data()), text.size()};
  }
  std::string Get(std::string_view path, bool with_session = true) {
    std::string request = "GET " + std::string(path) + " HTTP/1.1\r\nHost: card\r\n";
    if (with_session && !cookie.empty()) request += "Cookie: theme=dark; ipe_session=" + cookie + "\r\n";
    return Exchange(request + "\r\n");
  }
  std::string Post(std::string_view path, std::string_view body, bool with_csrf = true) {
    std::string request = "POST " + std::string(path) + " HTTP/1.1\r\nHost: card\r\nContent-Type: application/json\r\n";
    if (!cookie.empty()) request += "Cookie: ipe_session=" + cookie + "\r\n";
    if (with_csrf && !csrf.empty()) request += "X-CSRF-Token: " + csrf + "\r\n";
    request += "Content-Length: " + std::to_string(body.size()) + "\r\n\r\n" + std::string(body);
    return Exchange(request);
  }
  static std::string StatusLine(const std::string& answer) { return answer.substr(0, answer.find("\r\n")); }
  static std::string Body(const std::string& answer) { return answer.substr(answer.find("\r\n\r\n") + 4); }
  void Login() {
    const std::string answer = Post("/api/login", R"({"password":"USER"})", false);
    ASSERT_EQ(StatusLine(answer), "HTTP/1.1 200 OK");
    const std::size_t at = answer.find("Set-Cookie: ipe_session=");
    ASSERT_NE(at, std::string::npos);
    cookie = answer.substr(at + 24, 32);
    const std::string body = Body(answer);
    csrf = body.substr(body.find("\"csrf\":\"") + 8, 32);
  }
  void Elevate() { ASSERT_EQ(StatusLine(Post("/api/elevate", R"({"password":"USER"})")), "HTTP/1.1 200 OK"); }

  web::test::CountingRandom random;
  web::test::MemoryNvStore nv;
  web::PasswordStore passwords{nv, 0x0020, random};
  web::AccessControl access{passwords, random};
  drive_link::test::ScriptedDriveRegisters drive;
  FakeScanner scanner;
  FakeCardStatus card;
  // The EDS: 3000 bytes, byte i = i mod 253.
  std::vector<std::uint8_t> eds_bytes = [] {
    std::vector<std::uint8_t> bytes(3000);
    for (std::size_t i = 0; i < bytes.size(); ++i) bytes[i] = static_cast<std::uint8_t>(i % 253);
    return bytes;
  }();
  cip::ByteSpanFile eds{eds_bytes};
  WebApplication application{{access, drive, scanner, scanner, card, {&eds, "vf-mb1 \"x\".eds", 1, 0}}};
  web::HttpServer server{application};
  hal::Micros now = 1'000'000'000;
  std::string cookie;
  std::string csrf;
};

TEST_F(WebApplicationTest, SessionLoginAndCookie) {
  EXPECT_EQ(Body(Get("/api/session")), R"({"level":"none","defaults":true})");
  EXPECT_EQ(StatusLine(Get("/api/monitor")), "HTTP/1.1 401 Unauthorized");
  EXPECT_EQ(Body(Get("/api/monitor")), R"({"error":"login required"})");
  const std::string wrong = Post("/api/login", R"({"password":"user"})", false);
  EXPECT_EQ(StatusLine(wrong), "HTTP/1.1 401 Unauthorized");
  EXPECT_EQ(Body(wrong), R"({"error":"wrong password"})");
  const std::string answer = Post("/api/login", R"({"password":"USER"})", false);
  EXPECT_NE(answer.find("\r\nSet-Cookie: ipe_session="), std::string::npos);
  EXPECT_NE(answer.find("; Path=/; HttpOnly; SameSite=Strict\r\n"), std::string::npos);
  EXPECT_NE(answer.find("\r\nCache-Control: no-store\r\n"), std::string::npos);
  Login();
  EXPECT_EQ(Body(Get("/api/session")), R"({"level":"read","defaults":true})");
  EXPECT_EQ(StatusLine(Post("/api/logout", "")), "HTTP/1.1 204 No Content");
  EXPECT_EQ(StatusLine(Get("/api/monitor")), "HTTP/1.1 401 Unauthorized");
}

TEST_F(WebApplicationTest, ChangesNeedCsrfAndWriteLevel) {
  Login();
  EXPECT_EQ(StatusLine(Post("/api/registers", R"({"number":"0009","value":5})", false)), "HTTP/1.1 403 Forbidden");
  const std::string read_level = Post("/api/registers", R"({"number":"0009","value":5})");
  EXPECT_EQ(StatusLine(read_level), "HTTP/1.1 403 Forbidden");
  EXPECT_EQ(Body(read_level), R"({"error":"write password required"})");
  EXPECT_EQ(Body(Post("/api/elevate", R"({"password":"nope"})")), R"({"error":"wrong password"})");
  EXPECT_EQ(Body(Post("/api/elevate", R"({"password":"USER"})")), R"({"level":"write"})");
  EXPECT_TRUE(drive.log.empty());  // nothing reached the drive so far
  const std::string written = Post("/api/registers", R"({"number":"0009","value":55})");
  EXPECT_EQ(StatusLine(written), "HTTP/1.1 200 OK");
  EXPECT_EQ(Body(written), R"({"number":"0009","value":55})");
  ASSERT_EQ(drive.log.size(), 1U);
  EXPECT_EQ(drive.log[0], (drive_link::test::ScriptedDriveRegisters::Access{
                              true, 0x0009, 55, drive_link::WriteMode::kRamAndEeprom}));
  EXPECT_EQ(drive.registers[0x0009], 55);
}

TEST_F(WebApplicationTest, RegisterReadsAreDeferredAndExact) {
  Login();
  const std::string answer = Get("/api/registers?numbers=0009,0010,fd00,0011");
  EXPECT_EQ(StatusLine(answer), "HTTP/1.1 200 OK");
  EXPECT_EQ(Body(answer),
            R"({"values":[{"number":"0009","value":100},{"number":"0010","value":200},)"
            R"({"number":"FD00","value":1234},{"number":"0011","error":")" +
                std::string(drive_link::AccessErrorName(AccessError::kNoSuchRegister)) + R"("}]})");
  EXPECT_EQ(drive.log.size(), 4U);
  // Refusals of the request itself.
  EXPECT_EQ(StatusLine(Get("/api/registers?numbers=")), "HTTP/1.1 400 Bad Request");
  EXPECT_EQ(StatusLine(Get("/api/registers?numbers=0009,")), "HTTP/1.1 400 Bad Request");
  EXPECT_EQ(StatusLine(Get("/api/registers?numbers=009")), "HTTP/1.1 400 Bad Request");
  std::string many = "/api/registers?numbers=0009";
  for (int i = 0; i < 32; ++i) many += ",0009";
  EXPECT_EQ(Body(Get(many)), R"({"error":"at most 32 numbers"})");
}

TEST_F(WebApplicationTest, PoolFullIsRetriedAndLinkDownIsReported) {
  Login();
  drive.busy_next = 3;
  EXPECT_EQ(Body(Get("/api/registers?numbers=0009")), R"({"values":[{"number":"0009","value":100}]})");
  drive.link_down = true;
  EXPECT_EQ(Body(Get("/api/registers?numbers=0009")),
            R"({"values":[{"number":"0009","error":")" + std::string(drive_link::AccessErrorName(AccessError::kLinkDown)) +
                R"("}]})");
}

TEST_F(WebApplicationTest, WriteRefusalsMapToStatusCodes) {
  Login();
  Elevate();
  const struct {
    AccessError error;
    const char* status;
  } cases[] = {{AccessError::kNoSuchRegister, "HTTP/1.1 404 Not Found"},
               {AccessError::kOutOfRange, "HTTP/1.1 422 Unprocessable Content"},
               {AccessError::kNotWritableWhileRunning, "HTTP/1.1 409 Conflict"},
               {AccessError::kReadOnly, "HTTP/1.1 409 Conflict"},
               {AccessError::kReservedForScanner, "HTTP/1.1 409 Conflict"},
               {AccessError::kRefused, "HTTP/1.1 409 Conflict"},
               {AccessError::kNetworkLost, "HTTP/1.1 409 Conflict"},
               {AccessError::kTimeout, "HTTP/1.1 504 Gateway Timeout"}};
  for (const auto& c : cases) {
    drive.errors[0x0009] = c.error;
    const std::string answer = Post("/api/registers", R"({"number":"0009","value":1})");
    EXPECT_EQ(StatusLine(answer), c.status);
    EXPECT_EQ(Body(answer), std::string(R"({"error":")") + drive_link::AccessErrorName(c.error) + "\"}");
  }
  drive.errors.clear();
  EXPECT_EQ(StatusLine(Post("/api/registers", R"({"number":"0009","value":65536})")), "HTTP/1.1 422 Unprocessable Content");
  EXPECT_EQ(StatusLine(Post("/api/registers", R"({"number":"0009","value":-32769})")), "HTTP/1.1 422 Unprocessable Content");
  EXPECT_EQ(StatusLine(Post("/api/registers", R"({"number":"9","value":1})")), "HTTP/1.1 400 Bad Request");
  EXPECT_EQ(StatusLine(Post("/api/registers", R"({"number":"0009"})")), "HTTP/1.1 400 Bad Request");
  EXPECT_EQ(StatusLine(Post("/api/registers", R"({"number":"0009","value":-1})")), "HTTP/1.1 200 OK");
  EXPECT_EQ(drive.registers[0x0009], 0xFFFF);
}

TEST_F(WebApplicationTest, CommunicationResetWritesF899AfterConfirmation) {
  Login();
  Elevate();
  drive.registers[drive_link::reg::kF899] = 0;
  EXPECT_EQ(Body(Post("/api/network/reset", "{}")), R"({"error":"confirm: true required"})");
  const std::string answer = Post("/api/network/reset", R"({"confirm":true})");
  EXPECT_EQ(StatusLine(answer), "HTTP/1.1 202 Accepted");
  ASSERT_EQ(drive.log.size(), 1U);
  EXPECT_EQ(drive.log[0], (drive_link::test::ScriptedDriveRegisters::Access{true, drive_link::reg::kF899, 1,
                                                                            drive_link::WriteMode::kRamOnly}));
}

TEST_F(WebApplicationTest, MonitorReadsOnlyWhileWatched) {
  Login();
  const std::string first = Body(Get("/api/monitor"));
  EXPECT_EQ(first.rfind(R"({"link":"up","model":"vf-s15","protocol":"modbus","registers":{"FD00":null,)", 0), 0U)
      << first;
  // Watched: rounds of the 10 monitor registers every 250 ms.
  for (int i = 0; i < 300; ++i) {
    now += 1000;
    application.Poll(now);
    drive.CompleteAll();
  }
  const std::size_t reads = drive.log.size();
  EXPECT_GE(reads, 10U);
  const std::string second = Body(Get("/api/monitor"));
  EXPECT_NE(second.find(R"("FD00":1234,"FD01":1024,)"), std::string::npos) << second;
  EXPECT_NE(second.find(R"("leds":{"ms":"green"})"), std::string::npos) << second;
  // Nobody asks for 5 s: no more reads.
  for (int i = 0; i < 6000; ++i) {
    now += 1000;
    application.Poll(now);
    drive.CompleteAll();
  }
  const std::size_t after_interest = drive.log.size();
  for (int i = 0; i < 2000; ++i) {
    now += 1000;
    application.Poll(now);
    drive.CompleteAll();
  }
  EXPECT_EQ(drive.log.size(), after_interest);
}

TEST_F(WebApplicationTest, PagesOfCardData) {
  Login();
  EXPECT_EQ(Body(Get("/api/network")),
            R"({"mac":"02:00:5e:10:20:30","config":{"c500":0,"c501":0,"c504":0,"ip":[0,0,0,0],)"
            R"("netmask":[0,0,0,0],"gateway":[0,0,0,0],"c523":20,"c554":1,"device_name":"drive1"},)"
            R"("actual":{"ip":[10,0,0,5],"netmask":[0,0,0,0],"gateway":[0,0,0,0],"c502":0,"c503":0,"c536":0}})");
  EXPECT_EQ(Body(Get("/api/modbus-scanner")),
            R"({"menus":{"c001_c006":[1,3,0,0,0,0],"c021_c026":[1,2,0,0,0,0]},)"
            R"("master":{"c600_c603":[0,0,0,0],"c604":0},"c523":20,)"
            R"("live":{"command":[50176,5000,0,0,0,0],"monitor":[1024,4321,0,0,0,0]},"loss_action":false})");
  EXPECT_EQ(Body(Get("/api/eip-scanner")),
            R"({"connections":[],"live":{"command":[50176,5000,0,0,0,0],"monitor":[1024,4321,0,0,0,0]}})");
  EXPECT_EQ(Body(Get("/api/statistics")), R"({"ports":[]})");
}

TEST_F(WebApplicationTest, UnknownCallsAndMethods) {
  Login();
  EXPECT_EQ(StatusLine(Get("/api/nope")), "HTTP/1.1 404 Not Found");
  const std::string wrong_method = Post("/api/monitor", "{}");
  EXPECT_EQ(StatusLine(wrong_method), "HTTP/1.1 405 Method Not Allowed");
  EXPECT_NE(wrong_method.find("\r\nAllow: GET, HEAD\r\n"), std::string::npos);
  EXPECT_NE(Get("/api/login").find("\r\nAllow: POST\r\n"), std::string::npos);
  EXPECT_EQ(StatusLine(Post("/api/login", "not json", false)), "HTTP/1.1 400 Bad Request");
}

TEST_F(WebApplicationTest, PasswordChangeAndBackoff) {
  Login();
  Elevate();
  EXPECT_EQ(StatusLine(Post("/api/passwords", R"({"which":"read","password":"Secret-1"})")), "HTTP/1.1 204 No Content");
  EXPECT_EQ(StatusLine(Post("/api/passwords", R"({"which":"both","password":"x"})")), "HTTP/1.1 400 Bad Request");
  EXPECT_EQ(StatusLine(Post("/api/passwords", R"({"which":"read","password":""})")), "HTTP/1.1 400 Bad Request");
  cookie.clear();
  csrf.clear();
  EXPECT_EQ(StatusLine(Post("/api/login", R"({"password":"USER"})", false)), "HTTP/1.1 401 Unauthorized");
  EXPECT_EQ(StatusLine(Post("/api/login", R"({"password":"x2"})", false)), "HTTP/1.1 401 Unauthorized");
  const std::string third = Post("/api/login", R"({"password":"x3"})", false);
  EXPECT_EQ(Body(third), R"({"error":"wrong password","retry_after_ms":1000})");
  const std::string waiting = Post("/api/login", R"({"password":"Secret-1"})", false);
  EXPECT_EQ(StatusLine(waiting), "HTTP/1.1 429 Too Many Requests");
  EXPECT_NE(waiting.find("\r\nRetry-After: 1\r\n"), std::string::npos);
  now += web::kFirstBackoff;
  EXPECT_EQ(StatusLine(Post("/api/login", R"({"password":"Secret-1"})", false)), "HTTP/1.1 200 OK");
}

TEST_F(WebApplicationTest, PageIsServedCompressedWithEtag) {
  const web::Asset* index = web::FindAsset("/");
  ASSERT_NE(index, nullptr);
  const std::string answer = Exchange("GET / HTTP/1.1\r\nHost: card\r\nAccept-Encoding: gzip, br\r\n\r\n");
  EXPECT_EQ(StatusLine(answer), "HTTP/1.1 200 OK");
  EXPECT_NE(answer.find("\r\nContent-Encoding: gzip\r\n"), std::string::npos);
  EXPECT_NE(answer.find("\r\nContent-Length: " + std::to_string(index->gzip.size()) + "\r\n"), std::string::npos);
  EXPECT_EQ(Body(answer).size(), index->gzip.size());
  const std::string etag(index->etag);
  EXPECT_EQ(StatusLine(Exchange("GET / HTTP/1.1\r\nHost: card\r\nIf-None-Match: " + etag + "\r\n\r\n")),
            "HTTP/1.1 304 Not Modified");
  EXPECT_EQ(StatusLine(Exchange("GET / HTTP/1.1\r\nHost: card\r\nAccept-Encoding: identity\r\n\r\n")),
            "HTTP/1.1 406 Not Acceptable");
  EXPECT_EQ(StatusLine(Exchange("GET /missing.js HTTP/1.1\r\nHost: card\r\n\r\n")), "HTTP/1.1 404 Not Found");
  EXPECT_EQ(StatusLine(Exchange("POST / HTTP/1.1\r\nHost: card\r\nContent-Length: 0\r\n\r\n")),
            "HTTP/1.1 405 Method Not Allowed");
}

TEST_F(WebApplicationTest, EdsIsStreamedAsAnAttachmentToASession) {
  EXPECT_EQ(StatusLine(Get("/api/eds")), "HTTP/1.1 401 Unauthorized");
  Login();
  const std::string answer = Get("/api/eds");
  EXPECT_EQ(StatusLine(answer), "HTTP/1.1 200 OK");
  EXPECT_NE(answer.find("\r\nContent-Type: application/octet-stream\r\n"), std::string::npos);
  // The quotes of the name would end the quoted string: they become '_'.
  EXPECT_NE(answer.find("\r\nContent-Disposition: attachment; filename=\"vf-mb1 _x_.eds\"\r\n"), std::string::npos);
  EXPECT_NE(answer.find("\r\nCache-Control: no-store\r\n"), std::string::npos);
  EXPECT_NE(answer.find("\r\nContent-Length: 3000\r\n"), std::string::npos);
  EXPECT_EQ(Body(answer), std::string(eds_bytes.begin(), eds_bytes.end()));
  const std::string head = Exchange("HEAD /api/eds HTTP/1.1\r\nHost: card\r\nCookie: ipe_session=" + cookie + "\r\n\r\n");
  EXPECT_NE(head.find("\r\nContent-Length: 3000\r\n"), std::string::npos);
  EXPECT_EQ(Body(head), "");
  const std::string post = Post("/api/eds", "{}");
  EXPECT_EQ(StatusLine(post), "HTTP/1.1 405 Method Not Allowed");
  EXPECT_NE(post.find("\r\nAllow: GET, HEAD\r\n"), std::string::npos);
}

TEST_F(WebApplicationTest, NoEdsIs404) {
  WebApplication without{{access, drive, scanner, scanner, card}};
  web::HttpServer other{without};
  Login();
  const auto id = other.Open(now);
  ASSERT_TRUE(id.ok());
  other.Receive(*id, Bytes("GET /api/eds HTTP/1.1\r\nHost: card\r\nCookie: ipe_session=" + cookie + "\r\n\r\n"), now);
  const auto chunk = other.PendingOutput(*id);
  const std::string answer(chunk.begin(), chunk.end());
  EXPECT_EQ(StatusLine(answer), "HTTP/1.1 404 Not Found");
  EXPECT_EQ(Body(answer), R"({"error":"no EDS"})");
}

}  // namespace
}  // namespace firmware
