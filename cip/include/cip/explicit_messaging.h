// The seam between the encapsulation layer and what answers explicit messages: the message router for
// unconnected (UCMM) requests, and the connection manager (a later issue) for class 3 connected data
// and for the lifetime of sessions that own CIP connections.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>

#include "base/addresses.h"
#include "base/byte_reader.h"
#include "base/byte_writer.h"
#include "cip/wire_types.h"
#include "hal/clock.h"

namespace cip {

struct Ipv4Endpoint {
  base::Ipv4Address address;
  std::uint16_t port = 0;

  constexpr bool operator==(const Ipv4Endpoint&) const = default;
};

// Everything about one explicit request that is not in its bytes.
struct RequestContext {
  hal::Micros now = 0;
  std::uint32_t session_handle = 0;  // the encapsulation session it arrived on (0: none, e.g. tests)
  Ipv4Endpoint peer;                 // the originator (its TCP endpoint)
  // Socket address items of the SendRRData packet (a Forward_Open may carry them) ...
  std::optional<SocketAddress> request_o_to_t;
  std::optional<SocketAddress> request_t_to_o;
  // ... and the ones a handler wants in the reply packet (a Forward_Open reply for multicast T->O).
  std::optional<SocketAddress> reply_o_to_t;
  std::optional<SocketAddress> reply_t_to_o;
  // Who asks: the binding's TCP connection (its index + 1; 0: none, e.g. tests). A requester has at most
  // one request in progress, so a handler may key work it started for a request on it.
  std::uint32_t requester = 0;
  // Deferred replies (docs/ethernetip.md "Deferred replies"). A handler that cannot answer yet (it started
  // a drive-link access) sets `pending`; the message router then stops and the encapsulation server
  // answers nothing, keeps the whole message and executes it again, from the start, when the binding
  // retries it. Handlers answer the repeat from what they recorded for `requester`, so a retried request
  // never starts an access twice.
  bool pending = false;
};

// The handlers' side of deferred replies (implemented by the drive objects' access journal). The
// encapsulation server calls Started before each execution of a request (the first and every retry) and
// Finished once its reply is produced or its requester is gone; the binding retries a pending request
// when ReadyToRetry says every access it started has completed.
class RequestLifecycle {
 public:
  virtual ~RequestLifecycle() = default;
  virtual void OnRequestStarted(std::uint32_t requester) = 0;
  virtual void OnRequestFinished(std::uint32_t requester) = 0;
  virtual bool ReadyToRetry(std::uint32_t requester) const = 0;
};

class UnconnectedMessageHandler {
 public:
  virtual ~UnconnectedMessageHandler() = default;
  // Answers one message router request. Writes the complete message router reply into `reply` and
  // returns its size (at most reply.size()). Every request gets a reply: errors are CIP error replies.
  virtual std::size_t HandleUnconnected(std::span<const std::uint8_t> request, RequestContext& context,
                                        std::span<std::uint8_t> reply) = 0;
};

// Implemented by the connection manager (class 3 explicit connections, I/O connection ownership).
class ConnectedMessageHandler {
 public:
  virtual ~ConnectedMessageHandler() = default;
  // A SendUnitData packet for `connection_id`. On a known class 3 connection of this session, writes
  // the connected data item's content (sequence count + message router reply) into `reply`, sets
  // `reply_connection_id` (the T->O connection ID) and returns the size. Returns 0 when there is no such
  // connection: the packet is then dropped without a reply (data for an unknown
  // connection is ignored).
  virtual std::size_t HandleConnected(std::uint32_t connection_id, std::uint16_t sequence_count,
                                      std::span<const std::uint8_t> request, RequestContext& context,
                                      std::span<std::uint8_t> reply, std::uint32_t& reply_connection_id) = 0;
  // Whether CIP connections opened on this session are still open: the TCP inactivity timeout does not
  // close such a connection (the encapsulation inactivity timer only runs while a session
  // has no CIP connections).
  virtual bool SessionHasConnections(std::uint32_t session_handle) const = 0;
  // The session ended (UnRegisterSession, TCP close, inactivity): class 3 connections of the session go.
  virtual void OnSessionClosed(std::uint32_t session_handle) = 0;
};

}  // namespace cip
