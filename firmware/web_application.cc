#include "web_application.h"

#include <algorithm>
#include <array>
#include <optional>

#include "drive_link/drive_registers.h"
#include "web/assets.h"

namespace firmware {
namespace {

using web::HandlerResult;
using web::HttpStatus;

// On every answer: no sniffing, no framing by other sites, no referrer leaving the card.
void SecurityHeaders(web::HttpResponseWriter& response) {
  response.Header("X-Content-Type-Options", "nosniff");
  response.Header("X-Frame-Options", "DENY");
  response.Header("Referrer-Policy", "no-referrer");
}

void BeginJson(web::HttpResponseWriter& response, HttpStatus status) {
  response.Start(status);
  SecurityHeaders(response);
  response.Header("Content-Type", "application/json");
  response.Header("Cache-Control", "no-store");
}

// Writes the body with `fill`; an answer larger than the buffer becomes the writer's 500.
template <typename Fill>
void JsonBody(web::HttpResponseWriter& response, Fill&& fill) {
  const std::span<std::uint8_t> space = response.BeginBody();
  web::JsonWriter json(space);
  fill(json);
  response.CommitBody(json.overflowed() ? space.size() + 1 : json.size());
}

HandlerResult Json(web::HttpResponseWriter& response, HttpStatus status, auto&& fill) {
  BeginJson(response, status);
  JsonBody(response, fill);
  return HandlerResult::kDone;
}

HandlerResult Error(web::HttpResponseWriter& response, HttpStatus status, std::string_view text) {
  return Json(response, status, [&](web::JsonWriter& json) { json.BeginObject().Key("error").String(text).EndObject(); });
}

HandlerResult ErrorWithRetry(web::HttpResponseWriter& response, HttpStatus status, std::string_view text,
                             std::uint32_t retry_after_ms) {
  BeginJson(response, status);
  if (status == HttpStatus::kTooManyRequests) response.Header("Retry-After", (retry_after_ms + 999) / 1000);
  JsonBody(response, [&](web::JsonWriter& json) {
    json.BeginObject().Key("error").String(text);
    if (retry_after_ms != 0) json.Key("retry_after_ms").Number(retry_after_ms);
    json.EndObject();
  });
  return HandlerResult::kDone;
}

HandlerResult NoContent(web::HttpResponseWriter& response) {
  response.Start(HttpStatus::kNoContent);
  SecurityHeaders(response);
  response.Header("Cache-Control", "no-store");
  return HandlerResult::kDone;
}

HandlerResult MethodNotAllowed(web::HttpResponseWriter& response, std::string_view allow) {
  BeginJson(response, HttpStatus::kMethodNotAllowed);
  response.Header("Allow", allow);
  JsonBody(response, [](web::JsonWriter& json) { json.BeginObject().Key("error").String("method not allowed").EndObject(); });
  return HandlerResult::kDone;
}

const char* LevelName(web::AccessLevel level) {
  switch (level) {
    case web::AccessLevel::kRead: return "read";
    case web::AccessLevel::kWrite: return "write";
    case web::AccessLevel::kNone: break;
  }
  return "none";
}

// 4 hex digits, either case: a communication number.
std::optional<std::uint16_t> ParseNumber(std::string_view text) {
  if (text.size() != 4) return std::nullopt;
  std::uint16_t value = 0;
  for (char c : text) {
    int digit = -1;
    if (c >= '0' && c <= '9') digit = c - '0';
    if (c >= 'a' && c <= 'f') digit = c - 'a' + 10;
    if (c >= 'A' && c <= 'F') digit = c - 'A' + 10;
    if (digit < 0) return std::nullopt;
    value = static_cast<std::uint16_t>(value << 4 | digit);
  }
  return value;
}

// The value of `name` in a query string ("numbers=0009,0010&x=1"); no percent-decoding (the API's
// values are hex digits and commas).
std::optional<std::string_view> QueryValue(std::string_view query, std::string_view name) {
  while (!query.empty()) {
    const std::size_t amp = query.find('&');
    const std::string_view pair = query.substr(0, amp);
    if (pair.size() > name.size() && pair.substr(0, name.size()) == name && pair[name.size()] == '=') {
      return pair.substr(name.size() + 1);
    }
    if (amp == std::string_view::npos) break;
    query = query.substr(amp + 1);
  }
  return std::nullopt;
}

// How a failed drive access is answered (docs/web.md "Data"); the text is AccessErrorName's.
HttpStatus StatusOf(drive_link::AccessError error) {
  switch (error) {
    case drive_link::AccessError::kNone: return HttpStatus::kOk;
    case drive_link::AccessError::kNoSuchRegister: return HttpStatus::kNotFound;
    case drive_link::AccessError::kOutOfRange: return HttpStatus::kUnprocessable;
    case drive_link::AccessError::kNotWritableWhileRunning:
    case drive_link::AccessError::kReadOnly:
    case drive_link::AccessError::kReservedForScanner:
    case drive_link::AccessError::kRefused:
    case drive_link::AccessError::kNetworkLost: return HttpStatus::kConflict;
    case drive_link::AccessError::kLinkDown: return HttpStatus::kServiceUnavailable;
    case drive_link::AccessError::kTimeout: return HttpStatus::kGatewayTimeout;
  }
  return HttpStatus::kInternalError;
}

void WordArray(web::JsonWriter& json, std::span<const std::uint16_t> words) {
  json.BeginArray();
  for (std::uint16_t w : words) json.Number(w);
  json.EndArray();
}

void ByteArray(web::JsonWriter& json, std::span<const std::uint8_t> bytes) {
  json.BeginArray();
  for (std::uint8_t b : bytes) json.Number(b);
  json.EndArray();
}

// A finished one-write job, answered: the access error's status and name, or what `ok` makes of the result.
template <typename Ok>
HandlerResult AnswerWrite(WebRegisterJobs& jobs, web::HttpClientId client, web::HttpResponseWriter& response, Ok&& ok) {
  const RegisterJobResult item = jobs.results(client)[0];
  jobs.Finish(client);
  if (!item.result.ok()) {
    return Error(response, StatusOf(item.result.error), drive_link::AccessErrorName(item.result.error));
  }
  return ok(item);
}

bool IsRead(const web::HttpRequest& request) { return request.method == "GET" || request.method == "HEAD"; }

}  // namespace

hal::Micros WebApplication::NextDeadline() const { return std::min(monitor_.NextDeadline(), jobs_.NextDeadline()); }

void WebApplication::Poll(hal::Micros now) {
  monitor_.Poll(now);
  jobs_.Poll(now);
}

HandlerResult WebApplication::Handle(web::HttpClientId client, const web::HttpRequest& request,
                                     web::HttpResponseWriter& response, hal::Micros now) {
  std::string_view session;
  if (const auto cookie = request.Header("Cookie")) session = web::SessionCookie(*cookie).value_or("");
  const Call call{client, request, response, now, session};
  constexpr std::string_view kApi = "/api/";
  if (request.path.substr(0, kApi.size()) == kApi) return HandleApi(call, request.path.substr(kApi.size()));
  return HandleAsset(call);
}

HandlerResult WebApplication::HandleAsset(const Call& call) {
  if (!IsRead(call.request)) return MethodNotAllowed(call.response, "GET, HEAD");
  const web::Asset* asset = web::FindAsset(call.request.path);
  if (asset == nullptr) return Error(call.response, HttpStatus::kNotFound, "not found");
  // Assets exist only gzip-compressed (the image budget). No Accept-Encoding means any coding will do
  // (RFC 9110 §12.5.3); one without gzip cannot be served.
  if (const auto accepted = call.request.Header("Accept-Encoding");
      accepted && accepted->find("gzip") == std::string_view::npos) {
    return Error(call.response, HttpStatus::kNotAcceptable, "gzip required");
  }
  web::HttpResponseWriter& response = call.response;
  const bool unchanged = call.request.Header("If-None-Match") == asset->etag;
  response.Start(unchanged ? HttpStatus::kNotModified : HttpStatus::kOk);
  SecurityHeaders(response);
  response.Header("ETag", asset->etag);
  // The page may be cached but must be revalidated: a new firmware image brings new assets.
  response.Header("Cache-Control", "no-cache");
  response.Header("Vary", "Accept-Encoding");
  if (unchanged) return HandlerResult::kDone;
  response.Header("Content-Type", asset->content_type);
  response.Header("Content-Encoding", "gzip");
  if (asset->content_type.substr(0, 9) == "text/html") {
    response.Header("Content-Security-Policy", "default-src 'self'; img-src 'self' data:; frame-ancestors 'none'; form-action 'self'");
  }
  response.ExternalBody(asset->gzip);
  return HandlerResult::kDone;
}

HandlerResult WebApplication::HandleApi(const Call& call, std::string_view route) {
  const web::HttpRequest& request = call.request;
  web::HttpResponseWriter& response = call.response;
  // A request already running on the drive link is finished first (its checks were made at its start).
  if (jobs_.active(call.client)) {
    if (route == "registers" && IsRead(request)) return ReadRegisters(call);
    if (route == "registers") return WriteRegister(call);
    return CommunicationReset(call);
  }
  const bool post = request.method == "POST";
  if (route == "session") {
    if (!IsRead(request)) return MethodNotAllowed(response, "GET, HEAD");
    const web::AccessLevel level =
        call.session.empty() ? web::AccessLevel::kNone : devices_.access.Lookup(call.session, call.now);
    return Json(response, HttpStatus::kOk, [&](web::JsonWriter& json) {
      json.BeginObject().Key("level").String(LevelName(level)).Key("defaults").Bool(devices_.access.defaults()).EndObject();
    });
  }
  if (route == "login") return post ? Login(call) : MethodNotAllowed(response, "POST");

  // Which calls take GET (and HEAD) and which POST (a change, with the CSRF token).
  static constexpr std::array<std::string_view, 7> kReads = {"monitor",     "registers",  "network", "modbus-scanner",
                                                             "eip-scanner", "statistics", "eds"};
  static constexpr std::array<std::string_view, 5> kChanges = {"logout", "elevate", "passwords", "network/reset",
                                                               "registers"};
  const bool readable = std::find(kReads.begin(), kReads.end(), route) != kReads.end();
  const bool changeable = std::find(kChanges.begin(), kChanges.end(), route) != kChanges.end();
  if (!readable && !changeable) return Error(response, HttpStatus::kNotFound, "no such call");
  if (!(post ? changeable : IsRead(request) && readable)) {
    return MethodNotAllowed(response, readable && changeable ? "GET, HEAD, POST" : readable ? "GET, HEAD" : "POST");
  }

  const web::AccessLevel level =
      call.session.empty() ? web::AccessLevel::kNone : devices_.access.Lookup(call.session, call.now);
  if (level == web::AccessLevel::kNone) return Error(response, HttpStatus::kUnauthorized, "login required");
  if (post) {
    const std::string_view csrf = request.Header("X-CSRF-Token").value_or("");
    if (!devices_.access.CheckCsrf(call.session, csrf, call.now)) {
      return Error(response, HttpStatus::kForbidden, "missing or wrong X-CSRF-Token");
    }
  }
  if (route == "logout") {
    devices_.access.Logout(call.session, call.now);
    response.Start(HttpStatus::kNoContent);
    SecurityHeaders(response);
    response.Header("Set-Cookie", "ipe_session=; Path=/; Max-Age=0; HttpOnly; SameSite=Strict");
    return HandlerResult::kDone;
  }
  if (route == "elevate") return Elevate(call);
  if (post && level != web::AccessLevel::kWrite) {
    return Error(response, HttpStatus::kForbidden, "write password required");
  }
  if (route == "passwords") return ChangePassword(call);
  if (route == "registers") return post ? WriteRegister(call) : ReadRegisters(call);
  if (route == "network/reset") return CommunicationReset(call);
  if (route == "eds") return Eds(call);
  if (route == "monitor") Monitor(call);
  if (route == "network") Network(call);
  if (route == "modbus-scanner") ModbusScanner(call);
  if (route == "eip-scanner") EipScanner(call);
  if (route == "statistics") {
    Json(response, HttpStatus::kOk, [&](web::JsonWriter& json) { devices_.status.WriteStatistics(json); });
  }
  return HandlerResult::kDone;
}

HandlerResult WebApplication::Eds(const Call& call) {
  const cip::ServedFile& eds = devices_.eds;
  if (eds.content == nullptr) return Error(call.response, HttpStatus::kNotFound, "no EDS");
  // attachment; filename="<name>": characters that would end or break the quoted string become '_'.
  constexpr std::string_view kHead = "attachment; filename=\"";
  std::array<char, kHead.size() + 256 + 1> disposition{};
  std::size_t n = kHead.copy(disposition.data(), kHead.size());
  for (char c : eds.name.substr(0, 255)) {
    const bool plain = c >= 0x20 && c < 0x7F && c != '"' && c != '\\';
    disposition[n++] = plain ? c : '_';
  }
  disposition[n++] = '"';
  web::HttpResponseWriter& response = call.response;
  response.Start(HttpStatus::kOk);
  SecurityHeaders(response);
  response.Header("Content-Type", "application/octet-stream");
  response.Header("Content-Disposition", std::string_view(disposition.data(), n));
  response.Header("Cache-Control", "no-store");
  response.StreamedBody(eds_body_);
  return HandlerResult::kDone;
}

HandlerResult WebApplication::Login(const Call& call) {
  web::JsonObject body;
  if (!web::ParseFlatJsonObject(call.request.body, body)) return Error(call.response, HttpStatus::kBadRequest, "malformed JSON");
  const std::optional<std::string_view> password = body.StringOf("password");
  if (!password) return Error(call.response, HttpStatus::kBadRequest, "password missing");
  const web::LoginResult result = devices_.access.Login(*password, call.now);
  if (result.outcome == web::AccessOutcome::kBackoff) {
    return ErrorWithRetry(call.response, HttpStatus::kTooManyRequests, "too many failed attempts", result.retry_after_ms);
  }
  if (result.outcome != web::AccessOutcome::kOk) {
    return ErrorWithRetry(call.response, HttpStatus::kUnauthorized, "wrong password", result.retry_after_ms);
  }
  // "ipe_session=" + 32 hex digits + attributes.
  std::array<char, 96> cookie{};
  const std::string_view head = "ipe_session=";
  const std::string_view tail = "; Path=/; HttpOnly; SameSite=Strict";
  std::size_t n = 0;
  for (std::string_view part : {head, result.session.text(), tail}) {
    std::copy(part.begin(), part.end(), cookie.begin() + static_cast<std::ptrdiff_t>(n));
    n += part.size();
  }
  BeginJson(call.response, HttpStatus::kOk);
  call.response.Header("Set-Cookie", std::string_view(cookie.data(), n));
  JsonBody(call.response, [&](web::JsonWriter& json) {
    json.BeginObject().Key("level").String(LevelName(result.level)).Key("csrf").String(result.csrf.text());
    json.Key("defaults").Bool(devices_.access.defaults()).EndObject();
  });
  return HandlerResult::kDone;
}

HandlerResult WebApplication::Elevate(const Call& call) {
  web::JsonObject body;
  if (!web::ParseFlatJsonObject(call.request.body, body)) return Error(call.response, HttpStatus::kBadRequest, "malformed JSON");
  const std::optional<std::string_view> password = body.StringOf("password");
  if (!password) return Error(call.response, HttpStatus::kBadRequest, "password missing");
  const web::ElevateResult result = devices_.access.Elevate(call.session, *password, call.now);
  switch (result.outcome) {
    case web::AccessOutcome::kOk:
      return Json(call.response, HttpStatus::kOk, [](web::JsonWriter& json) { json.BeginObject().Key("level").String("write").EndObject(); });
    case web::AccessOutcome::kBackoff:
      return ErrorWithRetry(call.response, HttpStatus::kTooManyRequests, "too many failed attempts", result.retry_after_ms);
    case web::AccessOutcome::kNoSession:
      return Error(call.response, HttpStatus::kUnauthorized, "login required");
    case web::AccessOutcome::kWrongPassword:
      break;
  }
  return ErrorWithRetry(call.response, HttpStatus::kUnauthorized, "wrong password", result.retry_after_ms);
}

HandlerResult WebApplication::ChangePassword(const Call& call) {
  web::JsonObject body;
  if (!web::ParseFlatJsonObject(call.request.body, body)) return Error(call.response, HttpStatus::kBadRequest, "malformed JSON");
  const std::optional<std::string_view> which = body.StringOf("which");
  const std::optional<std::string_view> password = body.StringOf("password");
  if (!which || (*which != "read" && *which != "write") || !password) {
    return Error(call.response, HttpStatus::kBadRequest, "which (read or write) and password required");
  }
  const base::Status changed = devices_.access.ChangePassword(
      *which == "read" ? web::PasswordKind::kRead : web::PasswordKind::kWrite, *password);
  if (changed.code() == base::StatusCode::kOutOfRange || changed.code() == base::StatusCode::kInvalidArgument) {
    return Error(call.response, HttpStatus::kBadRequest, "a password is 1 to 32 printable ASCII characters");
  }
  if (!changed.ok()) return Error(call.response, HttpStatus::kInternalError, "the card could not store it");
  devices_.access.NoteChange(call.session, call.now);
  return NoContent(call.response);
}

HandlerResult WebApplication::ReadRegisters(const Call& call) {
  if (!jobs_.active(call.client)) {
    const std::string_view list = QueryValue(call.request.query, "numbers").value_or("");
    std::array<std::uint16_t, kMaxRegistersPerRequest> numbers{};
    std::size_t count = 0;
    std::string_view rest = list;
    while (!rest.empty() || count == 0) {
      const std::size_t comma = rest.find(',');
      const std::optional<std::uint16_t> number = ParseNumber(rest.substr(0, comma));
      if (!number) return Error(call.response, HttpStatus::kBadRequest, "numbers: 4 hex digits each, comma-separated");
      if (count == numbers.size()) return Error(call.response, HttpStatus::kBadRequest, "at most 32 numbers");
      numbers[count++] = *number;
      if (comma == std::string_view::npos) break;
      rest = rest.substr(comma + 1);
      if (rest.empty()) return Error(call.response, HttpStatus::kBadRequest, "numbers: 4 hex digits each, comma-separated");
    }
    jobs_.StartReads(call.client, std::span<const std::uint16_t>(numbers.data(), count), call.now);
  }
  if (!jobs_.done(call.client)) return HandlerResult::kPending;
  Json(call.response, HttpStatus::kOk, [&](web::JsonWriter& json) {
    json.BeginObject().Key("values").BeginArray();
    for (const RegisterJobResult& item : jobs_.results(call.client)) {
      json.BeginObject().Key("number").Hex4(item.number);
      if (item.result.ok()) {
        json.Key("value").Number(item.result.value);
      } else {
        json.Key("error").String(drive_link::AccessErrorName(item.result.error));
      }
      json.EndObject();
    }
    json.EndArray().EndObject();
  });
  jobs_.Finish(call.client);
  return HandlerResult::kDone;
}

HandlerResult WebApplication::WriteRegister(const Call& call) {
  if (!jobs_.active(call.client)) {
    web::JsonObject body;
    if (!web::ParseFlatJsonObject(call.request.body, body)) return Error(call.response, HttpStatus::kBadRequest, "malformed JSON");
    const std::optional<std::uint16_t> number = ParseNumber(body.StringOf("number").value_or(""));
    const std::optional<std::int64_t> value = body.IntegerOf("value");
    if (!number || !value) return Error(call.response, HttpStatus::kBadRequest, "number (4 hex digits) and value required");
    // A word, given either as 0..65535 or, for signed registers, as -32768..-1.
    if (*value < -32768 || *value > 65535) return Error(call.response, HttpStatus::kUnprocessable, "value is not a 16-bit word");
    jobs_.StartWrite(call.client, *number, static_cast<std::uint16_t>(*value), drive_link::WriteMode::kRamAndEeprom, call.now);
    devices_.access.NoteChange(call.session, call.now);
  }
  if (!jobs_.done(call.client)) return HandlerResult::kPending;
  return AnswerWrite(jobs_, call.client, call.response, [&](const RegisterJobResult& item) {
    return Json(call.response, HttpStatus::kOk, [&](web::JsonWriter& json) {
      json.BeginObject().Key("number").Hex4(item.number).Key("value").Number(item.result.value).EndObject();
    });
  });
}

HandlerResult WebApplication::CommunicationReset(const Call& call) {
  if (!jobs_.active(call.client)) {
    web::JsonObject body;
    if (!web::ParseFlatJsonObject(call.request.body, body) || body.BoolOf("confirm") != std::optional<bool>(true)) {
      return Error(call.response, HttpStatus::kBadRequest, "confirm: true required");
    }
    // f899 = 1: the inverter resets its communication and the card reloads its configuration (RAM: the
    // value returns to 0 by itself, nothing for the EEPROM).
    jobs_.StartWrite(call.client, drive_link::reg::kF899, 1, drive_link::WriteMode::kRamOnly, call.now);
    devices_.access.NoteChange(call.session, call.now);
  }
  if (!jobs_.done(call.client)) return HandlerResult::kPending;
  return AnswerWrite(jobs_, call.client, call.response, [&](const RegisterJobResult&) {
    return Json(call.response, HttpStatus::kAccepted, [](web::JsonWriter& json) {
      json.BeginObject().Key("reset").String("communication reset started").EndObject();
    });
  });
}

void WebApplication::Monitor(const Call& call) {
  monitor_.NoteInterest(call.now);
  Json(call.response, HttpStatus::kOk, [&](web::JsonWriter& json) {
    const WebCardStatus& status = devices_.status;
    json.BeginObject().Key("link").String(status.drive_link_state()).Key("model").String(status.drive_model());
    json.Key("protocol").String(status.config().protocol == config::Protocol::kModbusTcp ? "modbus" : "ethernetip");
    json.Key("registers").BeginObject();
    std::array<char, 4> name{};
    for (std::size_t i = 0; i < kMonitorRegisterCount; ++i) {
      static constexpr char kHex[] = "0123456789ABCDEF";
      const std::uint16_t number = kMonitorRegisters[i];
      name = {kHex[number >> 12], kHex[(number >> 8) & 0xF], kHex[(number >> 4) & 0xF], kHex[number & 0xF]};
      json.Key(std::string_view(name.data(), name.size()));
      if (monitor_.known(i)) {
        json.Number(monitor_.value(i));
      } else {
        json.Null();
      }
    }
    json.EndObject();
    const hal::Micros completed = monitor_.round_completed();
    json.Key("age_ms");
    if (completed == 0) {
      json.Null();
    } else {
      json.Number((call.now - completed) / hal::kMicrosPerMilli);
    }
    json.Key("loss_action").Bool(devices_.loss.loss_action_active());
    json.Key("leds");
    status.WriteLeds(json);
    json.EndObject();
  });
}

void WebApplication::Network(const Call& call) {
  Json(call.response, HttpStatus::kOk, [&](web::JsonWriter& json) {
    const config::CardConfig& config = devices_.status.config();
    const config::CardStatus card = devices_.status.card_status();
    std::array<char, 17> mac{};
    static constexpr char kHex[] = "0123456789abcdef";
    const base::MacAddress::Octets& octets = card.mac.octets();
    for (std::size_t i = 0; i < octets.size(); ++i) {
      mac[i * 3] = kHex[octets[i] >> 4];
      mac[i * 3 + 1] = kHex[octets[i] & 0xF];
      if (i + 1 < octets.size()) mac[i * 3 + 2] = ':';
    }
    json.BeginObject().Key("mac").String(std::string_view(mac.data(), mac.size()));
    json.Key("config").BeginObject();
    json.Key("c500").Number(static_cast<int>(config.protocol)).Key("c501").Number(config.rate_setting);
    json.Key("c504").Number(static_cast<int>(config.ip_mode));
    json.Key("ip");
    ByteArray(json, config.ip.octets());
    json.Key("netmask");
    ByteArray(json, config.netmask.octets());
    json.Key("gateway");
    ByteArray(json, config.gateway.octets());
    json.Key("c523").Number(config.timeout_tenths).Key("c554").Number(config.web_server ? 1 : 0);
    const std::string_view name(config.device_name.data());
    json.Key("device_name").String(name).EndObject();
    json.Key("actual").BeginObject().Key("ip");
    ByteArray(json, card.ip.octets());
    json.Key("netmask");
    ByteArray(json, card.netmask.octets());
    json.Key("gateway");
    ByteArray(json, card.gateway.octets());
    json.Key("c502").Number(card.port_rates[0]).Key("c503").Number(card.port_rates[1]);
    json.Key("c536").Number(card.ethernet_error).EndObject().EndObject();
  });
}

void WebApplication::ModbusScanner(const Call& call) {
  Json(call.response, HttpStatus::kOk, [&](web::JsonWriter& json) {
    const config::CardConfig& config = devices_.status.config();
    json.BeginObject().Key("menus").BeginObject().Key("c001_c006");
    WordArray(json, config.command_menus);
    json.Key("c021_c026");
    WordArray(json, config.monitor_menus);
    json.EndObject().Key("master").BeginObject().Key("c600_c603");
    ByteArray(json, config.modbus_master.octets());
    json.Key("c604").Number(config.io_scanning ? 1 : 0).EndObject();
    json.Key("c523").Number(config.timeout_tenths);
    json.Key("live").BeginObject().Key("command");
    WordArray(json, devices_.scanner.CommandWords());
    json.Key("monitor");
    WordArray(json, devices_.scanner.MonitorWords());
    json.EndObject().Key("loss_action").Bool(devices_.loss.loss_action_active()).EndObject();
  });
}

void WebApplication::EipScanner(const Call& call) {
  Json(call.response, HttpStatus::kOk, [&](web::JsonWriter& json) {
    json.BeginObject().Key("connections");
    devices_.status.WriteConnections(json);
    json.Key("live").BeginObject().Key("command");
    WordArray(json, devices_.scanner.CommandWords());
    json.Key("monitor");
    WordArray(json, devices_.scanner.MonitorWords());
    json.EndObject().EndObject();
  });
}

}  // namespace firmware
