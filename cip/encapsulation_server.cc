#include "cip/encapsulation_server.h"

#include <algorithm>

#include "cip/cpf.h"

namespace cip {
namespace {

constexpr std::uint16_t Cmd(EncapCommand command) { return static_cast<std::uint16_t>(command); }

// Room kept free after the message router reply for the two socket address items a Forward_Open
// reply may add.
constexpr std::size_t kSockaddrItemsRoom = 2 * (4 + SocketAddress::kWireSize);
// Interface handle, timeout and item count in front of the items of SendRRData/SendUnitData.
constexpr std::size_t kSendDataPrefix = 4 + 2 + 2;

bool IsDiscovery(std::uint16_t command) {
  return command == Cmd(EncapCommand::kListIdentity) || command == Cmd(EncapCommand::kListServices) ||
         command == Cmd(EncapCommand::kListInterfaces);
}

// Patches the header's length field once the reply data is written.
std::size_t FinishReply(base::ByteWriter& out) {
  out.PatchU16Le(2, static_cast<std::uint16_t>(out.size() - kEncapsulationHeaderSize));
  return out.ok() ? out.size() : 0;
}

std::size_t DiscoveryReply(const EncapsulationHeader& request, const DiscoverySource& discovery,
                           std::span<std::uint8_t> buffer) {
  // The discovery requests carry no data.
  if (request.length != 0) return EncodeEmptyReply(request, EncapStatus::kInvalidLength, buffer);
  base::ByteWriter out(buffer);
  EncodeEncapsulationHeader(ReplyHeaderFor(request, EncapStatus::kSuccess), out);
  if (request.command == Cmd(EncapCommand::kListIdentity)) {
    EncodeListIdentityData(discovery.ListIdentity(), out);
  } else if (request.command == Cmd(EncapCommand::kListServices)) {
    EncodeListServicesData(out);
  } else {
    EncodeListInterfacesData(out);
  }
  return FinishReply(out);
}

}  // namespace

std::size_t EncodeEmptyReply(const EncapsulationHeader& request, EncapStatus status, std::span<std::uint8_t> out) {
  base::ByteWriter writer(out);
  EncodeEncapsulationHeader(ReplyHeaderFor(request, status), writer);
  return writer.ok() ? writer.size() : 0;
}

EncapsulationServer::EncapsulationServer(UnconnectedMessageHandler& router, const DiscoverySource& discovery,
                                         hal::RandomSource& random)
    : router_(router), discovery_(discovery), random_(random) {}

base::Result<TcpConnectionId> EncapsulationServer::OpenTcpConnection(Ipv4Endpoint peer, hal::Micros now) {
  for (std::size_t i = 0; i < connections_.size(); ++i) {
    Connection& connection = connections_[i];
    if (connection.open) continue;
    connection.open = true;
    connection.expiry_reported = false;
    connection.peer = peer;
    connection.session_handle = 0;
    connection.last_activity = now;
    connection.assembler.Reset();
    connection_marks_.NoteTaken(connection_count());
    return TcpConnectionId{static_cast<std::uint8_t>(i)};
  }
  connection_marks_.NoteRefused();
  return base::ResourceExhausted();
}

void EncapsulationServer::CloseTcpConnection(TcpConnectionId id) {
  Connection* connection = Find(id);
  if (connection == nullptr) return;
  if (connection->pending && lifecycle_ != nullptr) lifecycle_->OnRequestFinished(RequesterOf(*connection));
  connection->pending = false;
  EndSession(*connection);
  connection->open = false;
  connection->assembler.Reset();
}

EncapsulationServer::Connection* EncapsulationServer::Find(TcpConnectionId id) {
  if (id.index >= connections_.size() || !connections_[id.index].open) return nullptr;
  return &connections_[id.index];
}

TcpStep EncapsulationServer::OnTcpData(TcpConnectionId id, std::span<const std::uint8_t> input, hal::Micros now) {
  Connection* connection = Find(id);
  if (connection == nullptr) return TcpStep{input.size(), {}, true};
  if (connection->pending) return TcpStep{0, {}, false, true};
  const TcpMessageAssembler::PushResult pushed = connection->assembler.Push(input);
  if (pushed.consumed > 0) {
    connection->last_activity = now;
    connection->expiry_reported = false;
  }
  if (!pushed.message_ready) return TcpStep{pushed.consumed, {}, false};
  TcpStep step = AnswerAssembled(*connection, now);
  step.consumed = pushed.consumed;
  return step;
}

bool EncapsulationServer::ReadyToRetry(TcpConnectionId id) const {
  if (id.index >= connections_.size()) return false;
  const Connection& connection = connections_[id.index];
  if (!connection.open || !connection.pending) return false;
  return lifecycle_ == nullptr || lifecycle_->ReadyToRetry(RequesterOf(connection));
}

TcpStep EncapsulationServer::RetryTcp(TcpConnectionId id, hal::Micros now) {
  Connection* connection = Find(id);
  if (connection == nullptr) return TcpStep{0, {}, true};
  if (!connection->pending) return TcpStep{};
  connection->last_activity = now;
  return AnswerAssembled(*connection, now);
}

bool EncapsulationServer::has_pending() const {
  return std::any_of(connections_.begin(), connections_.end(),
                     [](const Connection& c) { return c.open && c.pending; });
}

// Answers the assembled message, or keeps it when its reply is deferred.
TcpStep EncapsulationServer::AnswerAssembled(Connection& connection, hal::Micros now) {
  TcpStep step = Answer(connection, now);
  if (connection.pending) {
    step.pending = true;
    return step;
  }
  connection.assembler.Next();
  return step;
}

std::uint32_t EncapsulationServer::RequesterOf(const Connection& connection) const {
  return static_cast<std::uint32_t>(&connection - connections_.data()) + 1;
}

TcpStep EncapsulationServer::Answer(Connection& connection, hal::Micros now) {
  const EncapsulationHeader& request = connection.assembler.header();
  const std::span<const std::uint8_t> body = connection.assembler.body();
  // A receiver discards a message with options it does not know; every option bit is unknown.
  if (request.options != 0) return TcpStep{};
  const std::span<std::uint8_t> buffer(tcp_reply_);
  std::size_t size = 0;
  if (request.command == Cmd(EncapCommand::kNop)) {
    return TcpStep{};  // NOP is never answered, whatever its length
  } else if (connection.assembler.oversized()) {
    size = EncodeEmptyReply(request, EncapStatus::kInsufficientMemory, buffer);
  } else if (IsDiscovery(request.command)) {
    size = DiscoveryReply(request, discovery_, buffer);
  } else if (request.command == Cmd(EncapCommand::kRegisterSession)) {
    size = RegisterSession(connection, request, body);
  } else if (request.command == Cmd(EncapCommand::kUnRegisterSession)) {
    if (connection.session_handle != 0 && request.session_handle == connection.session_handle) {
      EndSession(connection);
      return TcpStep{0, {}, true};
    }
    size = EncodeEmptyReply(request, EncapStatus::kInvalidSessionHandle, buffer);
  } else if (request.command == Cmd(EncapCommand::kSendRRData) ||
             request.command == Cmd(EncapCommand::kSendUnitData)) {
    RequestContext context;
    context.now = now;
    context.session_handle = connection.session_handle;
    context.peer = connection.peer;
    context.requester = RequesterOf(connection);
    if (lifecycle_ != nullptr) lifecycle_->OnRequestStarted(context.requester);
    size = request.command == Cmd(EncapCommand::kSendRRData) ? SendRRData(connection, request, body, context)
                                                               : SendUnitData(connection, request, body, context);
    connection.pending = context.pending && lifecycle_ != nullptr;
    if (connection.pending) return TcpStep{};
    if (lifecycle_ != nullptr) lifecycle_->OnRequestFinished(context.requester);
  } else {
    size = EncodeEmptyReply(request, EncapStatus::kInvalidCommand, buffer);
  }
  return TcpStep{0, buffer.first(size), false};
}

std::size_t EncapsulationServer::RegisterSession(Connection& connection, const EncapsulationHeader& request,
                                                 std::span<const std::uint8_t> body) {
  if (body.size() != 4) return EncodeEmptyReply(request, EncapStatus::kInvalidLength, tcp_reply_);
  base::ByteReader in(body);
  const std::uint16_t version = in.U16Le();
  const std::uint16_t options = in.U16Le();
  EncapsulationHeader reply = ReplyHeaderFor(request, EncapStatus::kSuccess);
  reply.length = 4;
  std::uint16_t reply_version = version;
  if (version != kEncapsulationProtocolVersion || options != 0) {
    reply.status = static_cast<std::uint32_t>(EncapStatus::kUnsupportedProtocol);
    reply_version = kEncapsulationProtocolVersion;  // tell the originator what the card speaks
  } else if (connection.session_handle != 0) {
    reply.status = static_cast<std::uint32_t>(EncapStatus::kInvalidCommand);
    reply.session_handle = connection.session_handle;
  } else {
    const std::uint32_t handle = session_count() < kMaxSessions ? NewSessionHandle() : 0;
    if (handle == 0) {
      reply.status = static_cast<std::uint32_t>(EncapStatus::kInsufficientMemory);
      reply.session_handle = 0;
      session_marks_.NoteRefused();
    } else {
      connection.session_handle = handle;
      reply.session_handle = handle;
      session_marks_.NoteTaken(session_count());
    }
  }
  base::ByteWriter out(tcp_reply_);
  EncodeEncapsulationHeader(reply, out);
  out.U16Le(reply_version);
  out.U16Le(options);
  return out.ok() ? out.size() : 0;
}

// What SendRRData and SendUnitData check alike: the connection's own session, the interface handle and
// timeout, a Common Packet Format. The error reply's size, or nullopt with `command` decoded.
std::optional<std::size_t> EncapsulationServer::CheckSendData(const Connection& connection,
                                                              const EncapsulationHeader& request,
                                                              std::span<const std::uint8_t> body,
                                                              SendDataCommand& command) {
  if (connection.session_handle == 0 || request.session_handle != connection.session_handle) {
    return EncodeEmptyReply(request, EncapStatus::kInvalidSessionHandle, tcp_reply_);
  }
  if (body.size() < kSendDataPrefix) return EncodeEmptyReply(request, EncapStatus::kInvalidLength, tcp_reply_);
  const base::Result<SendDataCommand> decoded = DecodeSendDataCommand(body);
  if (!decoded.ok()) return EncodeEmptyReply(request, EncapStatus::kIncorrectData, tcp_reply_);
  command = *decoded;
  return std::nullopt;
}

std::size_t EncapsulationServer::SendRRData(Connection& connection, const EncapsulationHeader& request,
                                            std::span<const std::uint8_t> body, RequestContext& context) {
  SendDataCommand command;
  if (const std::optional<std::size_t> error = CheckSendData(connection, request, body, command)) return *error;
  const base::Result<UnconnectedMessage> message = ParseUnconnectedMessage(command.packet);
  if (!message.ok()) return EncodeEmptyReply(request, EncapStatus::kIncorrectData, tcp_reply_);

  context.request_o_to_t = message->o_to_t;
  context.request_t_to_o = message->t_to_o;

  base::ByteWriter out(tcp_reply_);
  EncodeEncapsulationHeader(ReplyHeaderFor(request, EncapStatus::kSuccess), out);
  out.U32Le(0);  // interface handle
  out.U16Le(0);  // timeout
  const std::size_t count_at = out.size();
  out.U16Le(2);
  FinishCpfItem(out, BeginCpfItem(out, CpfItemType::kNullAddress));
  const std::size_t data_at = BeginCpfItem(out, CpfItemType::kUnconnectedData);
  const std::span<std::uint8_t> tail = out.Tail();
  if (!out.ok() || tail.size() < kSockaddrItemsRoom) return 0;  // cannot happen: the buffer is fixed
  out.Advance(router_.HandleUnconnected(message->request, context, tail.first(tail.size() - kSockaddrItemsRoom)));
  if (context.pending) return 0;
  FinishCpfItem(out, data_at);
  std::uint16_t count = 2;
  if (context.reply_o_to_t) {
    EncodeSockaddrItem(out, CpfItemType::kSockaddrOtoT, *context.reply_o_to_t);
    ++count;
  }
  if (context.reply_t_to_o) {
    EncodeSockaddrItem(out, CpfItemType::kSockaddrTtoO, *context.reply_t_to_o);
    ++count;
  }
  out.PatchU16Le(count_at, count);
  return FinishReply(out);
}

std::size_t EncapsulationServer::SendUnitData(Connection& connection, const EncapsulationHeader& request,
                                              std::span<const std::uint8_t> body, RequestContext& context) {
  SendDataCommand command;
  if (const std::optional<std::size_t> error = CheckSendData(connection, request, body, command)) return *error;
  const base::Result<ConnectedMessage> message = ParseConnectedMessage(command.packet);
  if (!message.ok()) return EncodeEmptyReply(request, EncapStatus::kIncorrectData, tcp_reply_);
  if (connected_ == nullptr) return 0;  // no connection manager: no class 3 connection can exist

  base::ByteWriter out(tcp_reply_);
  EncodeEncapsulationHeader(ReplyHeaderFor(request, EncapStatus::kSuccess), out);
  out.U32Le(0);  // interface handle
  out.U16Le(0);  // timeout
  out.U16Le(2);  // item count
  const std::size_t address_at = BeginCpfItem(out, CpfItemType::kConnectedAddress);
  const std::size_t connection_id_at = out.size();
  out.U32Le(0);
  FinishCpfItem(out, address_at);
  const std::size_t data_at = BeginCpfItem(out, CpfItemType::kConnectedData);
  if (!out.ok()) return 0;
  std::uint32_t reply_connection_id = 0;
  const std::size_t size = connected_->HandleConnected(message->connection_id, message->sequence_count,
                                                       message->request, context, out.Tail(), reply_connection_id);
  if (size == 0) return 0;
  out.Advance(size);
  FinishCpfItem(out, data_at);
  out.PatchU32Le(connection_id_at, reply_connection_id);
  return FinishReply(out);
}

std::uint32_t EncapsulationServer::NewSessionHandle() {
  // A collision with a live handle (or 0) is a 1-in-500-million event per draw; a few draws make a
  // failure practically impossible while keeping the loop bounded.
  for (int attempt = 0; attempt < 4; ++attempt) {
    const std::uint32_t handle = random_.NextU32();
    if (handle != 0 && !HandleInUse(handle)) return handle;
  }
  return 0;
}

bool EncapsulationServer::HandleInUse(std::uint32_t handle) const {
  for (const Connection& connection : connections_) {
    if (connection.open && connection.session_handle == handle) return true;
  }
  return false;
}

void EncapsulationServer::EndSession(Connection& connection) {
  if (connection.session_handle == 0) return;
  const std::uint32_t handle = connection.session_handle;
  connection.session_handle = 0;
  if (connected_ != nullptr) connected_->OnSessionClosed(handle);
}

UdpDecision EncapsulationServer::OnUdpDatagram(std::span<const std::uint8_t> datagram, const UdpSource& source,
                                               hal::Micros now) {
  UdpDecision decision;
  const base::Result<EncapsulationHeader> header = DecodeEncapsulationHeader(datagram);
  // One datagram carries exactly one message; a short, long or optioned one is not answered.
  if (!header.ok() || datagram.size() != kEncapsulationHeaderSize + header->length || header->options != 0) {
    return decision;
  }
  const EncapsulationHeader& request = *header;
  const std::span<std::uint8_t> buffer(udp_reply_);
  std::size_t size = 0;
  if (request.command == Cmd(EncapCommand::kListIdentity) && source.broadcast && request.length == 0) {
    if (ScheduleListIdentity(request, source, now, decision.send_at) == 0) return decision;
    decision.action = UdpDecision::Action::kSendLater;
    return decision;
  }
  if (IsDiscovery(request.command)) {
    if (source.broadcast && request.length != 0) return decision;
    size = DiscoveryReply(request, discovery_, buffer);
  } else if (source.broadcast || request.command == Cmd(EncapCommand::kNop)) {
    return decision;  // nothing else is for UDP; broadcasts are never answered with an error
  } else {
    size = EncodeEmptyReply(request, EncapStatus::kInvalidCommand, buffer);
  }
  if (size == 0) return decision;
  decision.action = UdpDecision::Action::kSendNow;
  decision.reply = buffer.first(size);
  return decision;
}

std::size_t EncapsulationServer::ScheduleListIdentity(const EncapsulationHeader& request, const UdpSource& source,
                                                      hal::Micros now, hal::Micros& send_at) {
  for (std::size_t i = 0; i < delayed_.size(); ++i) {
    DelayedReply& slot = delayed_[i];
    if (slot.pending) continue;
    const hal::Micros requested = static_cast<hal::Micros>(request.sender_context[0] | request.sender_context[1] << 8) *
                                  hal::kMicrosPerMilli;
    hal::Micros max_delay = requested;
    if (max_delay == 0) {
      max_delay = kDefaultListIdentityMaxDelay;
    } else if (max_delay < kMinListIdentityMaxDelay) {
      max_delay = kMinListIdentityMaxDelay;
    }
    slot.pending = true;
    slot.to = source.peer;
    slot.request = request;
    slot.due = now + random_.NextU32() % (max_delay + 1);
    send_at = slot.due;
    delayed_marks_.NoteTaken(delayed_count());
    return i + 1;
  }
  delayed_marks_.NoteRefused();
  return 0;
}

bool EncapsulationServer::TakeDueDatagram(hal::Micros now, DueDatagram& out) {
  DelayedReply* due = nullptr;
  for (DelayedReply& slot : delayed_) {
    if (slot.pending && slot.due <= now && (due == nullptr || slot.due < due->due)) due = &slot;
  }
  if (due == nullptr) return false;
  due->pending = false;
  const std::size_t size = DiscoveryReply(due->request, discovery_, udp_reply_);
  out.to = due->to;
  out.bytes = std::span<const std::uint8_t>(udp_reply_).first(size);
  return size != 0;
}

bool EncapsulationServer::TakeExpiredConnection(hal::Micros now, TcpConnectionId& out) {
  for (std::size_t i = 0; i < connections_.size(); ++i) {
    Connection& connection = connections_[i];
    if (!connection.open || connection.expiry_reported) continue;
    if (now < connection.last_activity || now - connection.last_activity < kTcpInactivityTimeout) continue;
    if (connected_ != nullptr && connection.session_handle != 0 &&
        connected_->SessionHasConnections(connection.session_handle)) {
      connection.last_activity = now;  // its CIP connections keep it alive; look again later
      continue;
    }
    connection.expiry_reported = true;
    out = TcpConnectionId{static_cast<std::uint8_t>(i)};
    return true;
  }
  return false;
}

hal::Micros EncapsulationServer::NextDeadline() const {
  hal::Micros deadline = hal::kNever;
  for (const Connection& connection : connections_) {
    if (!connection.open || connection.expiry_reported) continue;
    const hal::Micros expiry = connection.last_activity + kTcpInactivityTimeout;
    if (expiry < deadline) deadline = expiry;
  }
  for (const DelayedReply& slot : delayed_) {
    if (slot.pending && slot.due < deadline) deadline = slot.due;
  }
  return deadline;
}

std::size_t EncapsulationServer::session_count() const {
  std::size_t count = 0;
  for (const Connection& connection : connections_) {
    if (connection.open && connection.session_handle != 0) ++count;
  }
  return count;
}

std::size_t EncapsulationServer::delayed_count() const {
  return static_cast<std::size_t>(
      std::count_if(delayed_.begin(), delayed_.end(), [](const DelayedReply& d) { return d.pending; }));
}

std::size_t EncapsulationServer::connection_count() const {
  std::size_t count = 0;
  for (const Connection& connection : connections_) {
    if (connection.open) ++count;
  }
  return count;
}

}  // namespace cip
