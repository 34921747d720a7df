// The web server's connection core (docs/web.md "Connections"): up to kMaxHttpClients connections, each
// with its receive buffer, sharing kHttpResponseBuffers response buffers; requests parsed by
// ParseHttpRequest and handed to an HttpHandler one at a time per connection (pipelined requests wait their
// turn), answers taken out by the transport (firmware/web_service binds this to lwIP). Pure: bytes in,
// bytes out, time injected.
//
// - A handler may answer later (kPending): the server calls it again with the same request on each Poll
//   until it is done (the drive's registers are read over the serial link). The request stays in the
//   receive buffer meanwhile, so the views in HttpRequest remain valid.
// - Response buffers: an answer (or an error) is written into a response buffer taken for it, which is
//   given back once the transport has taken the bytes in it (an asset's body is sent from flash and needs
//   no buffer). A request whose answer finds no buffer free waits (Poll tries again). An answer still in
//   its buffer kRequestTimeout after it was written closes its connection, so a client that does not
//   read cannot keep the others waiting.
// - A streamed body (HttpResponseWriter::StreamedBody) is read chunk by chunk into a response buffer when
//   the transport has room for it (LoadStreamChunk): the buffer is held only while a chunk is handed to
//   TCP, so other answers take it between chunks, and the file is never in RAM as a whole.
// - Keep-alive: after an answer the next request on the connection is served. A malformed request gets
//   its 4xx and the connection closes after it (its framing can no longer be trusted).
// - Slots: when a connection arrives and every slot is taken, the transport may close the connection that
//   has been idle longest between requests (IdleClientToEvict: a browser keeps idle connections open, and
//   a server may close an idle connection at any time, RFC 9112 §9.5); when none is idle it answers
//   BusyResponse() and closes.
// - Timers: a request must arrive whole within kRequestTimeout of its first byte (408 otherwise: a client
//   sending one byte a second cannot hold a slot); an idle connection closes after kIdleTimeout.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>

#include "base/pool_stats.h"
#include "base/status.h"
#include "hal/clock.h"
#include "web/http_request.h"
#include "web/http_response.h"

namespace web {

// A browser loading the page fetches the stylesheet and both scripts at once (lwipopts.h
// IPE_MAX_HTTP_CLIENTS); a fourth connection takes an idle one's slot or is answered 503.
inline constexpr std::size_t kMaxHttpClients = 3;
// lwIP reopens a receive window only in steps of half a window (silly window avoidance): the receive
// buffer keeps that much room beyond the largest request, so that the last step before a request at the
// limits is always announced. At least TCP_WND / 2 (static_assert in firmware/web_service.cc).
inline constexpr std::size_t kHttpReceiveSlack = 272;
// A whole request (headers and body at their limits) fits: nothing is ever refused back to TCP.
inline constexpr std::size_t kHttpReceiveBufferBytes = kMaxHeaderBlock + kMaxBody + kHttpReceiveSlack;
// Headers and an in-buffer body. The largest answer is /api/eip-scanner with all 16 CIP connections
// (about 3.9 KiB); assets are sent from flash, only their head is in the buffer. An answer that does not
// fit is replaced by a bodiless 500 (counters().overflows).
inline constexpr std::size_t kHttpResponseBufferBytes = 4096;
// Response buffers shared by the connections. A buffer is held only until the transport has handed its
// bytes to TCP: an asset's head or a JSON answer of up to TCP_SND_BUF leaves at once, a larger answer
// within a few round trips; so one buffer serves a page load and its pollers (docs/web.md "Connections").
inline constexpr std::size_t kHttpResponseBuffers = 1;
inline constexpr hal::Micros kRequestTimeout = 10 * hal::kMicrosPerSecond;
inline constexpr hal::Micros kIdleTimeout = 60 * hal::kMicrosPerSecond;

using HttpClientId = std::uint8_t;

enum class HandlerResult : std::uint8_t { kDone, kPending };

class HttpHandler {
 public:
  virtual ~HttpHandler() = default;
  // Writes the answer to `request` (Start, headers, body; the server adds Content-Length and Connection
  // and finishes it), or returns kPending and is called again later with the same request. An external
  // body must stay valid for as long as the program runs (embedded assets).
  virtual HandlerResult Handle(HttpClientId client, const HttpRequest& request, HttpResponseWriter& response,
                               hal::Micros now) = 0;
  // The connection is gone: forget what was pending for it.
  virtual void OnClientClosed(HttpClientId client) = 0;
  // When a pending request wants to be called again (hal::kNever: only when something else happens).
  virtual hal::Micros NextDeadline() const = 0;
};

struct HttpServerCounters {
  std::uint32_t accepted = 0;
  std::uint32_t requests = 0;         // requests parsed whole and handed to the handler
  std::uint32_t parse_errors = 0;     // answered 4xx/5xx by the parser's verdict
  std::uint32_t request_timeouts = 0; // 408: a request did not arrive whole in time
  std::uint32_t idle_closed = 0;      // closed after kIdleTimeout without a request
  std::uint32_t overflows = 0;        // an answer too large for the response buffer (500 sent)
  std::uint32_t response_waits = 0;   // requests (or errors) that waited for a response buffer
  std::uint32_t answer_timeouts = 0;  // connections closed: their answer stayed kRequestTimeout in its buffer
  std::array<std::uint32_t, 6> responses_by_class{};  // [2] = 2xx ... [5] = 5xx
};

class HttpServer {
 public:
  explicit HttpServer(HttpHandler& handler) : handler_(handler) {}
  HttpServer(const HttpServer&) = delete;
  HttpServer& operator=(const HttpServer&) = delete;

  // A new connection. kResourceExhausted: every slot is taken.
  base::Result<HttpClientId> Open(hal::Micros now);
  // The longest-idle connection with nothing received, pending or unsent, if any.
  std::optional<HttpClientId> IdleClientToEvict() const;
  // Forgets the connection (the transport closes it).
  void Close(HttpClientId client);
  bool IsOpen(HttpClientId client) const { return client < kMaxHttpClients && clients_[client].open; }

  // Takes received bytes (all of them while the transport's window is no larger than the buffer) and
  // serves what has become complete. Returns the count taken.
  std::size_t Receive(HttpClientId client, std::span<const std::uint8_t> bytes, hal::Micros now);
  // Calls pending handlers again, applies the timeouts.
  void Poll(hal::Micros now);
  hal::Micros NextDeadline() const;

  // The next bytes to send, and the transport's report that `count` of them went to TCP (which may let
  // the next pipelined request be served).
  std::span<const std::uint8_t> PendingOutput(HttpClientId client) const;
  // When the answer's streamed body is next and nothing else is pending: reads its next chunk, at most
  // `room` bytes (the transport's free send buffer), into a response buffer, where PendingOutput() shows
  // it. Without a free response buffer it waits (the transport calls again). A source that comes up short
  // of its size closes the connection.
  void LoadStreamChunk(HttpClientId client, std::size_t room, hal::Micros now);
  void ConsumeOutput(HttpClientId client, std::size_t count, hal::Micros now);
  // PendingOutput() is an external body (valid for the program's life: the transport may reference it
  // instead of copying), not the response buffer, which the next answer reuses.
  bool PendingOutputIsStatic(HttpClientId client) const {
    return IsOpen(client) && clients_[client].head_left.empty() && !clients_[client].body_left.empty();
  }
  // How far the transport may reopen its receive window now, given its full window size: received bytes
  // not yet reported, as far as the buffer's free space still covers a whole window after them (a request
  // larger than one window arrives while the earlier part waits in the buffer).
  std::size_t TakeReleasedInput(HttpClientId client, std::size_t window);
  // The connection must be closed now (after a closing answer was sent, or a timeout).
  bool MustClose(HttpClientId client) const { return IsOpen(client) && clients_[client].must_close; }

  // What a connection beyond every slot is told before it is closed.
  static std::span<const std::uint8_t> BusyResponse();

  const HttpServerCounters& counters() const { return counters_; }
  std::size_t open_clients() const;
  // The client table (docs/robustness.md "Exhaustion"); refused: Open found every slot taken (the
  // transport then evicts an idle connection or answers 503).
  base::PoolStats client_pool() const { return client_marks_.Stats(open_clients(), kMaxHttpClients); }
  // The response buffers; refused: an answer had to wait for one (counted once per answer).
  base::PoolStats response_pool() const { return response_marks_.Stats(responses_in_use(), kHttpResponseBuffers); }

 private:
  static constexpr std::size_t kNoResponse = kHttpResponseBuffers;

  struct Client {
    bool open = false;
    std::array<std::uint8_t, kHttpReceiveBufferBytes> input{};
    std::size_t input_used = 0;
    std::size_t unreleased = 0;  // taken by Receive, not yet handed back to the transport's window
    std::size_t response = kNoResponse;  // the response buffer this client holds
    bool waiting_for_response = false;   // an answer or error is due but no response buffer was free
    hal::Micros answer_written = 0;      // when the answer in the response buffer was written
    std::span<const std::uint8_t> head_left;  // in the response buffer
    std::span<const std::uint8_t> body_left;
    const HttpBodySource* stream = nullptr;  // the answer's streamed body
    std::uint32_t stream_offset = 0;          // its next byte to read
    HttpRequest request;
    std::size_t request_bytes = 0;  // the active request's length in `input`
    bool request_active = false;    // parsed, the handler has not finished it
    bool close_after_output = false;
    bool must_close = false;
    hal::Micros last_activity = 0;  // last byte received or sent
    hal::Micros request_started = hal::kNever;  // first byte of an incomplete request
  };

  void Serve(Client& client, HttpClientId id, hal::Micros now);
  void RunHandler(Client& client, HttpClientId id, hal::Micros now);
  // Both write into a response buffer and return false (nothing done) when none is free.
  bool SendError(Client& client, HttpStatus status, hal::Micros now);
  bool TakeResponse(Client& client);
  void GiveBackResponse(Client& client);
  std::size_t responses_in_use() const;
  bool AnyWaitingWithResponseFree() const;
  void CountResponse(HttpStatus status);
  static bool StreamLeft(const Client& client) {
    return client.stream != nullptr && client.stream_offset < client.stream->Size();
  }
  bool OutputPending(const Client& client) const {
    return !client.head_left.empty() || !client.body_left.empty() || StreamLeft(client);
  }

  HttpHandler& handler_;
  std::array<Client, kMaxHttpClients> clients_{};
  std::array<std::array<std::uint8_t, kHttpResponseBufferBytes>, kHttpResponseBuffers> responses_{};
  std::array<bool, kHttpResponseBuffers> response_taken_{};
  HttpServerCounters counters_;
  base::PoolWatermark client_marks_;
  base::PoolWatermark response_marks_;
};

}  // namespace web
