#include "web/http_server.h"

#include <algorithm>
#include <array>
#include <cstring>
#include <string_view>

namespace web {
namespace {

constexpr std::string_view kBusyResponse =
    "HTTP/1.1 503 Service Unavailable\r\n"
    "Content-Type: application/json\r\n"
    "Retry-After: 1\r\n"
    "Content-Length: 23\r\n"
    "Connection: close\r\n"
    "\r\n"
    "{\"error\":\"server busy\"}";

bool IsHead(const HttpRequest& request) { return request.method == "HEAD"; }

}  // namespace

std::span<const std::uint8_t> HttpServer::BusyResponse() {
  return std::span<const std::uint8_t>(reinterpret_cast<const std::uint8_t*>(kBusyResponse.data()),
                                       kBusyResponse.size());
}

base::Result<HttpClientId> HttpServer::Open(hal::Micros now) {
  for (std::size_t i = 0; i < kMaxHttpClients; ++i) {
    Client& client = clients_[i];
    if (client.open) continue;
    client.open = true;
    client.input_used = 0;
    client.unreleased = 0;
    client.response = kNoResponse;
    client.waiting_for_response = false;
    client.head_left = {};
    client.body_left = {};
    client.stream = nullptr;
    client.stream_offset = 0;
    client.request_bytes = 0;
    client.request_active = false;
    client.close_after_output = false;
    client.must_close = false;
    client.last_activity = now;
    client.request_started = hal::kNever;
    ++counters_.accepted;
    client_marks_.NoteTaken(open_clients());
    return static_cast<HttpClientId>(i);
  }
  client_marks_.NoteRefused();
  return base::ResourceExhausted();
}

std::optional<HttpClientId> HttpServer::IdleClientToEvict() const {
  std::optional<HttpClientId> oldest;
  for (std::size_t i = 0; i < kMaxHttpClients; ++i) {
    const Client& client = clients_[i];
    if (!client.open || client.must_close || client.input_used != 0 || client.request_active ||
        OutputPending(client)) {
      continue;
    }
    if (!oldest || client.last_activity < clients_[*oldest].last_activity) oldest = static_cast<HttpClientId>(i);
  }
  return oldest;
}

void HttpServer::Close(HttpClientId id) {
  if (!IsOpen(id)) return;
  Client& client = clients_[id];
  if (client.request_active) handler_.OnClientClosed(id);
  client.open = false;
  client.request_active = false;
  client.head_left = {};
  client.body_left = {};
  client.stream = nullptr;
  client.waiting_for_response = false;
  GiveBackResponse(client);
}

bool HttpServer::TakeResponse(Client& client) {
  if (client.response != kNoResponse) return true;
  for (std::size_t i = 0; i < kHttpResponseBuffers; ++i) {
    if (response_taken_[i]) continue;
    response_taken_[i] = true;
    client.response = i;
    client.waiting_for_response = false;
    response_marks_.NoteTaken(responses_in_use());
    return true;
  }
  if (!client.waiting_for_response) {
    // Counted once per answer, not once per attempt.
    client.waiting_for_response = true;
    ++counters_.response_waits;
    response_marks_.NoteRefused();
  }
  return false;
}

void HttpServer::GiveBackResponse(Client& client) {
  if (client.response == kNoResponse) return;
  response_taken_[client.response] = false;
  client.response = kNoResponse;
}

std::size_t HttpServer::responses_in_use() const {
  return static_cast<std::size_t>(std::count(response_taken_.begin(), response_taken_.end(), true));
}

bool HttpServer::AnyWaitingWithResponseFree() const {
  if (responses_in_use() == kHttpResponseBuffers) return false;
  return std::any_of(clients_.begin(), clients_.end(),
                     [](const Client& c) { return c.open && !c.must_close && c.waiting_for_response; });
}

std::size_t HttpServer::open_clients() const {
  return static_cast<std::size_t>(std::count_if(clients_.begin(), clients_.end(), [](const Client& c) { return c.open; }));
}

std::size_t HttpServer::Receive(HttpClientId id, std::span<const std::uint8_t> bytes, hal::Micros now) {
  if (!IsOpen(id)) return 0;
  Client& client = clients_[id];
  const std::size_t count = std::min(bytes.size(), client.input.size() - client.input_used);
  if (count == 0) return 0;
  client.unreleased += count;
  if (client.must_close || client.close_after_output) {
    // The connection is ending: what arrives now is never served, only taken so TCP is not stalled.
    return count;
  }
  std::memcpy(client.input.data() + client.input_used, bytes.data(), count);
  if (client.input_used == 0 && !client.request_active) client.request_started = now;
  client.input_used += count;
  client.last_activity = now;
  Serve(client, id, now);
  return count;
}

void HttpServer::Poll(hal::Micros now) {
  for (std::size_t i = 0; i < kMaxHttpClients; ++i) {
    Client& client = clients_[i];
    if (!client.open || client.must_close) continue;
    const auto id = static_cast<HttpClientId>(i);
    Serve(client, id, now);
    if (!client.head_left.empty() && now - client.answer_written >= kRequestTimeout) {
      // The client does not take its answer: give the response buffer to the others.
      ++counters_.answer_timeouts;
      client.must_close = true;
      continue;
    }
    if (OutputPending(client) || client.request_active || client.close_after_output) continue;
    if (client.input_used != 0 && now - client.request_started >= kRequestTimeout) {
      if (SendError(client, HttpStatus::kRequestTimeout, now)) ++counters_.request_timeouts;
    } else if (client.input_used == 0 && now - client.last_activity >= kIdleTimeout) {
      ++counters_.idle_closed;
      client.must_close = true;
    }
  }
}

hal::Micros HttpServer::NextDeadline() const {
  hal::Micros next = hal::kNever;
  bool any_pending = false;
  if (AnyWaitingWithResponseFree()) return 0;
  for (const Client& client : clients_) {
    if (!client.open) continue;
    if (client.must_close) return 0;
    if (!client.head_left.empty()) next = std::min(next, client.answer_written + kRequestTimeout);
    if (client.request_active) {
      any_pending = true;
      continue;
    }
    if (OutputPending(client) || client.close_after_output) continue;
    next = std::min(next, client.input_used != 0 ? client.request_started + kRequestTimeout
                                                 : client.last_activity + kIdleTimeout);
  }
  if (any_pending) next = std::min(next, handler_.NextDeadline());
  return next;
}

std::span<const std::uint8_t> HttpServer::PendingOutput(HttpClientId id) const {
  if (!IsOpen(id)) return {};
  const Client& client = clients_[id];
  return !client.head_left.empty() ? client.head_left : client.body_left;
}

void HttpServer::ConsumeOutput(HttpClientId id, std::size_t count, hal::Micros now) {
  if (!IsOpen(id)) return;
  Client& client = clients_[id];
  client.last_activity = now;
  const std::size_t from_head = std::min(count, client.head_left.size());
  client.head_left = client.head_left.subspan(from_head);
  count -= from_head;
  // The response buffer's bytes are with the transport: the buffer may serve another answer.
  if (client.head_left.empty()) GiveBackResponse(client);
  client.body_left = client.body_left.subspan(std::min(count, client.body_left.size()));
  if (OutputPending(client)) return;
  if (client.close_after_output) {
    client.must_close = true;
    return;
  }
  // A pipelined request may be waiting behind the answer just sent.
  if (client.input_used != 0) client.request_started = now;
  Serve(client, id, now);
}

void HttpServer::LoadStreamChunk(HttpClientId id, std::size_t room, hal::Micros now) {
  if (!IsOpen(id) || room == 0) return;
  Client& client = clients_[id];
  if (client.must_close || !client.head_left.empty() || !client.body_left.empty() || !StreamLeft(client)) return;
  if (!TakeResponse(client)) return;
  std::array<std::uint8_t, kHttpResponseBufferBytes>& buffer = responses_[client.response];
  const std::size_t want = std::min({room, buffer.size(), static_cast<std::size_t>(client.stream->Size() - client.stream_offset)});
  const std::size_t read = client.stream->ReadAt(client.stream_offset, std::span(buffer).first(want));
  if (read == 0) {
    // The source ended before its Content-Length: closing is the only honest end of this answer.
    GiveBackResponse(client);
    client.stream = nullptr;
    client.must_close = true;
    return;
  }
  client.stream_offset += static_cast<std::uint32_t>(std::min(read, want));
  client.head_left = std::span<const std::uint8_t>(buffer).first(std::min(read, want));
  client.answer_written = now;
}

std::size_t HttpServer::TakeReleasedInput(HttpClientId id, std::size_t window) {
  if (!IsOpen(id)) return 0;
  Client& client = clients_[id];
  // After releasing r, the peer may send window - (unreleased - r) more bytes; they must fit the free space.
  const std::size_t free_space = client.input.size() - client.input_used;
  if (free_space + client.unreleased <= window) return 0;
  const std::size_t released = std::min(client.unreleased, free_space + client.unreleased - window);
  client.unreleased -= released;
  return released;
}

void HttpServer::Serve(Client& client, HttpClientId id, hal::Micros now) {
  if (client.must_close || client.close_after_output || OutputPending(client)) return;
  if (!client.request_active) {
    if (client.input_used == 0) return;
    const ParseResult parsed =
        ParseHttpRequest(std::span<const std::uint8_t>(client.input.data(), client.input_used), client.request);
    if (parsed.state == ParseState::kIncomplete) return;
    if (parsed.state == ParseState::kError) {
      // Without a free response buffer the request is parsed again on a later pass.
      if (SendError(client, parsed.error, now)) ++counters_.parse_errors;
      return;
    }
    ++counters_.requests;
    client.request_active = true;
    client.request_bytes = parsed.consumed;
  }
  RunHandler(client, id, now);
}

void HttpServer::RunHandler(Client& client, HttpClientId id, hal::Micros now) {
  // The request waits (Poll tries again) until a response buffer is free.
  if (!TakeResponse(client)) return;
  HttpResponseWriter writer(responses_[client.response]);
  if (handler_.Handle(id, client.request, writer, now) == HandlerResult::kPending) {
    GiveBackResponse(client);
    return;
  }
  const bool keep_alive = client.request.keep_alive;
  writer.Finish(IsHead(client.request), keep_alive);
  if (writer.overflowed()) ++counters_.overflows;
  CountResponse(writer.status());
  client.head_left = writer.head();
  client.body_left = writer.external_body();
  client.stream = writer.streamed_body();
  client.stream_offset = 0;
  client.answer_written = now;
  client.close_after_output = !keep_alive || writer.overflowed();
  // The request is answered: its bytes leave the buffer (the answer no longer refers to them).
  client.request_active = false;
  std::memmove(client.input.data(), client.input.data() + client.request_bytes, client.input_used - client.request_bytes);
  client.input_used -= client.request_bytes;
  client.request_bytes = 0;
}

bool HttpServer::SendError(Client& client, HttpStatus status, hal::Micros now) {
  if (!TakeResponse(client)) return false;
  HttpResponseWriter writer(responses_[client.response]);
  writer.Start(status);
  writer.Header("Content-Type", "application/json");
  writer.BodyText("{\"error\":\"");
  writer.BodyText(ReasonPhrase(status));
  writer.BodyText("\"}");
  writer.Finish(false, false);
  CountResponse(writer.status());
  client.head_left = writer.head();
  client.body_left = {};
  client.stream = nullptr;
  client.answer_written = now;
  client.close_after_output = true;
  // Nothing more is parsed on this connection.
  client.input_used = 0;
  return true;
}

void HttpServer::CountResponse(HttpStatus status) {
  const std::size_t klass = static_cast<std::size_t>(status) / 100;
  if (klass < counters_.responses_by_class.size()) ++counters_.responses_by_class[klass];
}

}  // namespace web
