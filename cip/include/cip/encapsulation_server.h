// The card's side of the encapsulation protocol on TCP and UDP 44818: TCP connections and their
// sessions, the commands and their replies, discovery over UDP with the delayed broadcast ListIdentity,
// and the per-connection inactivity timeout. Bytes in, decisions and bytes out; the lwIP binding owns
// the sockets and calls:
//
//   OpenTcpConnection    when it accepts a connection (kResourceExhausted: abort it, no slot)
//   OnTcpData            with received bytes, repeatedly until every byte is consumed; sends `reply`
//                        (if any) in order, and closes the connection when `close` is set
//   CloseTcpConnection   when the connection is gone (closed by either side, reset, error)
//   OnUdpDatagram        with each datagram on UDP 44818; sends the reply now, later, or not at all
//   NextDeadline         to know when to call TakeDueDatagram / TakeExpiredConnection
//
// Decisions (docs/ethernetip.md lists them with their reasons):
// - At most kMaxSessions sessions; the 9th RegisterSession gets 0x0002 and changes nothing else. Up to
//   kMaxTcpConnections (one more than sessions) TCP connections, so that a connection beyond the session
//   limit still gets that answer (and can use ListIdentity) instead of a reset.
// - One session per TCP connection; a second RegisterSession on it gets 0x0001 with the existing handle.
// - Session handles are random, non-zero and unique, and valid only on the connection that registered
//   them: anything else gets 0x0064.
// - A message whose header options field is not 0 is dropped without a reply.
// - NOP is never answered; a valid UnRegisterSession is not answered and closes the connection.
// - A TCP connection without traffic for kTcpInactivityTimeout is closed, unless its session still owns
//   CIP connections (ConnectedMessageHandler::SessionHasConnections).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>

#include "base/pool_stats.h"
#include "base/status.h"
#include "cip/cpf.h"
#include "cip/encapsulation.h"
#include "cip/explicit_messaging.h"
#include "cip/tcp_message_assembler.h"
#include "hal/clock.h"
#include "hal/random.h"

namespace cip {

inline constexpr std::size_t kMaxSessions = 8;
// One more than sessions: room to answer one client too many 0x0002 (lwipopts.h IPE_ENIP_TCP_CONNECTIONS).
// Each connection costs its assembler (kMaxEncapsulationMessage), the binding's input buffer (TCP_WND),
// a drive-access journal and a PCB: about 2 KB on the card.
inline constexpr std::size_t kMaxTcpConnections = kMaxSessions + 1;
// The TCP/IP object's default encapsulation inactivity timeout (its attribute 13, which the card does
// not expose); lwIP's keepalive finds dead peers independently.
inline constexpr hal::Micros kTcpInactivityTimeout = 120 * hal::kMicrosPerSecond;
// Broadcast ListIdentity replies waiting for their random delay; more are dropped (the originator
// repeats its request, and a scanner never sends more than a few per second).
inline constexpr std::size_t kMaxDelayedReplies = 2;
// The maximum delay of a broadcast ListIdentity reply is bytes 0-1 of the sender context, in ms;
// 0 means 2000 ms and 1-499 mean 500 ms (the rule the ODVA stacks follow, e.g. OpENer).
inline constexpr hal::Micros kDefaultListIdentityMaxDelay = 2000 * hal::kMicrosPerMilli;
inline constexpr hal::Micros kMinListIdentityMaxDelay = 500 * hal::kMicrosPerMilli;
// Every reply fits this many bytes (the lwIP binding must be able to queue one such reply).
inline constexpr std::size_t kMaxReplyMessage = kMaxEncapsulationMessage;
// Every reply on UDP fits this many bytes: the largest is ListIdentity with a 32-character product name
// (24-byte header, item count 2, item type and length 4, identity item 34 + 32); ListServices is 46 bytes,
// ListInterfaces 26, an error reply 24.
inline constexpr std::size_t kMaxUdpReply = 96;

// What the card says about itself in ListIdentity (the composition root builds it from the Identity
// object and the TCP/IP interface).
class DiscoverySource {
 public:
  virtual ~DiscoverySource() = default;
  virtual IdentityItem ListIdentity() const = 0;
};

struct TcpConnectionId {
  std::uint8_t index = 0;
  constexpr bool operator==(const TcpConnectionId&) const = default;
};

struct TcpStep {
  std::size_t consumed = 0;             // bytes of the input taken; call again with the rest
  std::span<const std::uint8_t> reply;  // send first (valid until the next OnTcpData)
  bool close = false;                   // then close the connection and call CloseTcpConnection
  // The message is answered later (deferred reply): keep the input after `consumed`, feed nothing more
  // and call RetryTcp once ReadyToRetry says so (docs/ethernetip.md "Deferred replies").
  bool pending = false;
};

struct UdpSource {
  Ipv4Endpoint peer;
  bool broadcast = false;  // sent to a broadcast or multicast address
};

struct UdpDecision {
  enum class Action : std::uint8_t { kDrop, kSendNow, kSendLater };
  Action action = Action::kDrop;
  std::span<const std::uint8_t> reply;  // kSendNow: valid until the next OnUdpDatagram/TakeDueDatagram
  hal::Micros send_at = 0;              // kSendLater: TakeDueDatagram hands it out from this time on
};

struct DueDatagram {
  Ipv4Endpoint to;
  std::span<const std::uint8_t> bytes;  // valid until the next OnUdpDatagram/TakeDueDatagram
};

class EncapsulationServer {
 public:
  EncapsulationServer(UnconnectedMessageHandler& router, const DiscoverySource& discovery,
                      hal::RandomSource& random);

  // The connection manager, once it exists; without one, SendUnitData is never answered.
  void set_connected_handler(ConnectedMessageHandler* handler) { connected_ = handler; }
  // The handlers' journal of deferred drive accesses; without one no request is ever deferred.
  void set_request_lifecycle(RequestLifecycle* lifecycle) { lifecycle_ = lifecycle; }

  base::Result<TcpConnectionId> OpenTcpConnection(Ipv4Endpoint peer, hal::Micros now);
  void CloseTcpConnection(TcpConnectionId id);
  // Consumes input up to the end of the first complete message and answers it. An unknown id consumes
  // everything and asks for the connection to be closed.
  // While a message of the connection is pending, nothing is consumed (TcpStep::pending again).
  TcpStep OnTcpData(TcpConnectionId id, std::span<const std::uint8_t> input, hal::Micros now);
  // Deferred replies: whether the connection's pending message can be executed again now, and that
  // execution (consumed is 0; the reply, or pending once more).
  bool ReadyToRetry(TcpConnectionId id) const;
  TcpStep RetryTcp(TcpConnectionId id, hal::Micros now);
  bool has_pending() const;

  UdpDecision OnUdpDatagram(std::span<const std::uint8_t> datagram, const UdpSource& source, hal::Micros now);
  // Hands out one delayed reply that is due at `now`; false when none is.
  bool TakeDueDatagram(hal::Micros now, DueDatagram& out);
  // Names one connection whose inactivity timeout has run out at `now` (each only once); the binding
  // closes it and calls CloseTcpConnection. False when none has.
  bool TakeExpiredConnection(hal::Micros now, TcpConnectionId& out);
  // The earliest delayed reply or inactivity timeout, hal::kNever when there is none.
  hal::Micros NextDeadline() const;

  std::size_t session_count() const;
  std::size_t connection_count() const;
  // The fixed pools (docs/robustness.md "Exhaustion"): TCP connections (refused: OpenTcpConnection
  // found none free), sessions (refused: RegisterSession answered 0x0002), delayed broadcast
  // ListIdentity replies (refused: the request was dropped).
  base::PoolStats connection_pool() const { return connection_marks_.Stats(connection_count(), kMaxTcpConnections); }
  base::PoolStats session_pool() const { return session_marks_.Stats(session_count(), kMaxSessions); }
  base::PoolStats delayed_reply_pool() const { return delayed_marks_.Stats(delayed_count(), kMaxDelayedReplies); }

 private:
  struct Connection {
    bool open = false;
    bool expiry_reported = false;
    bool pending = false;  // the assembled message waits for a deferred reply
    Ipv4Endpoint peer;
    std::uint32_t session_handle = 0;  // 0: no session registered on this connection
    hal::Micros last_activity = 0;
    TcpMessageAssembler assembler;
  };
  struct DelayedReply {
    bool pending = false;
    Ipv4Endpoint to;
    EncapsulationHeader request;
    hal::Micros due = 0;
  };

  Connection* Find(TcpConnectionId id);
  TcpStep Answer(Connection& connection, hal::Micros now);
  TcpStep AnswerAssembled(Connection& connection, hal::Micros now);
  std::uint32_t RequesterOf(const Connection& connection) const;
  // Each writes the complete reply into tcp_reply_ and returns its size; 0 means no reply.
  std::size_t RegisterSession(Connection& connection, const EncapsulationHeader& request,
                              std::span<const std::uint8_t> body);
  std::optional<std::size_t> CheckSendData(const Connection& connection, const EncapsulationHeader& request,
                                           std::span<const std::uint8_t> body, SendDataCommand& command);
  // Both set context.pending when the reply is deferred (and then return 0).
  std::size_t SendRRData(Connection& connection, const EncapsulationHeader& request,
                         std::span<const std::uint8_t> body, RequestContext& context);
  std::size_t SendUnitData(Connection& connection, const EncapsulationHeader& request,
                           std::span<const std::uint8_t> body, RequestContext& context);
  std::uint32_t NewSessionHandle();
  bool HandleInUse(std::uint32_t handle) const;
  std::size_t delayed_count() const;
  void EndSession(Connection& connection);
  std::size_t ScheduleListIdentity(const EncapsulationHeader& request, const UdpSource& source,
                                   hal::Micros now, hal::Micros& send_at);

  UnconnectedMessageHandler& router_;
  const DiscoverySource& discovery_;
  hal::RandomSource& random_;
  ConnectedMessageHandler* connected_ = nullptr;
  RequestLifecycle* lifecycle_ = nullptr;
  std::array<Connection, kMaxTcpConnections> connections_{};
  std::array<DelayedReply, kMaxDelayedReplies> delayed_{};
  std::array<std::uint8_t, kMaxReplyMessage> tcp_reply_{};
  std::array<std::uint8_t, kMaxUdpReply> udp_reply_{};
  base::PoolWatermark connection_marks_;
  base::PoolWatermark session_marks_;
  base::PoolWatermark delayed_marks_;
};

// Writes a reply with no data: the request's header echoed with `status` and length 0.
std::size_t EncodeEmptyReply(const EncapsulationHeader& request, EncapStatus status, std::span<std::uint8_t> out);

}  // namespace cip
