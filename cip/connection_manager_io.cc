// The connection manager's traffic: class 1 datagrams on UDP 2222 (consumption with sequence counts and
// run/idle, production on absolute deadlines), watchdogs, class 3 requests over SendUnitData, and the
// status the rest of the card derives from the connections.
#include <algorithm>

#include "cip/connection_manager.h"
#include "cip/cpf.h"

namespace cip {
namespace {

constexpr std::size_t kSequenceCountSize = 2;
constexpr std::uint32_t kRunBit = 0x00000001;

}  // namespace

void ConnectionManager::OnIoDatagram(std::span<const std::uint8_t> bytes, Ipv4Endpoint from, hal::Micros now) {
  const base::Result<ReceivedIoDatagram> datagram = ParseIoDatagram(bytes);
  Connection* connection = nullptr;
  if (datagram.ok()) {
    for (Connection& candidate : connections_) {
      if (candidate.open && candidate.transport_class == 1 && candidate.o_to_t_id == datagram->connection_id &&
          candidate.originator_address == from.address) {
        connection = &candidate;
        break;
      }
    }
  }
  // Unknown connection, another sender, a stale or repeated packet, a wrong size: dropped, and the
  // watchdog is not fed.
  if (connection == nullptr || datagram->data.size() != connection->o_to_t_size ||
      (connection->received &&
       !SequenceAfter32(datagram->encapsulation_sequence, connection->last_encapsulation_sequence))) {
    ++dropped_datagrams_;
    return;
  }
  connection->last_encapsulation_sequence = datagram->encapsulation_sequence;
  connection->deadline = now + connection->timeout;

  base::ByteReader in(datagram->data);
  const std::uint16_t sequence = in.U16Le();
  if (connection->received && !SequenceAfter16(sequence, connection->last_sequence)) return;  // no new data
  connection->received = true;
  connection->last_sequence = sequence;
  if (connection->has_header) {
    const bool run = (in.U32Le() & kRunBit) != 0;
    if (run != connection->run) {
      connection->run = run;
      if (events_ != nullptr) events_->OnRunIdleChanged(InfoOf(*connection), run);
    }
  }
  if (connection->consumed_size > 0 && application_ != nullptr && connection->open) {
    application_->Consume(connection->points.consumed, in.Bytes(connection->consumed_size), connection->run);
  }
}

void ConnectionManager::CheckTimeouts(hal::Micros now) {
  for (std::size_t i = 0; i < connections_.size(); ++i) {
    Connection& connection = connections_[i];
    if (!connection.open || now < connection.deadline) continue;
    ++counters_.connection_timeouts;
    if (connection.transport_class == 1) io_faulted_ = true;
    const ConnectionInfo info = InfoOf(connection);
    Close(i, CloseReason::kTimedOut);
    if (events_ != nullptr) events_->OnConnectionTimedOut(info);
  }
}

bool ConnectionManager::TakeDueProduction(hal::Micros now, IoDatagram& out) {
  CheckTimeouts(now);
  Producer* due = nullptr;
  for (Producer& producer : producers_) {
    if (producer.active && producer.next <= now && (due == nullptr || producer.next < due->next)) due = &producer;
  }
  if (due == nullptr) return false;
  ++due->encapsulation_sequence;
  ++due->sequence;  // every production carries new data (the consumer never has to compare bytes)
  base::ByteWriter writer(datagram_);
  writer.U16Le(2);  // item count
  const std::size_t address_at = BeginCpfItem(writer, CpfItemType::kSequencedAddress);
  writer.U32Le(due->connection_id);
  writer.U32Le(due->encapsulation_sequence);
  FinishCpfItem(writer, address_at);
  const std::size_t data_at = BeginCpfItem(writer, CpfItemType::kConnectedData);
  writer.U16Le(due->sequence);
  // The application writes straight into the datagram (at most kMaxIoData bytes: checked at open).
  const std::span<std::uint8_t> data = writer.Tail().first(due->size);
  std::fill(data.begin(), data.end(), std::uint8_t{0});
  if (application_ != nullptr) application_->Produce(due->point, data);
  writer.Advance(due->size);
  FinishCpfItem(writer, data_at);
  due->next = NextProductionSlot(due->next, due->api, now, missed_productions_);
  out.to = due->to;
  out.multicast = due->multicast;
  out.priority = due->priority;
  out.bytes = writer.written();
  return true;
}

hal::Micros ConnectionManager::NextDeadline() const {
  hal::Micros next = hal::kNever;
  for (const Connection& connection : connections_) {
    if (connection.open) next = std::min(next, connection.deadline);
  }
  for (const Producer& producer : producers_) {
    if (producer.active) next = std::min(next, producer.next);
  }
  return next;
}

ExtendedDeviceStatus ConnectionManager::IoStatus() const {
  if (io_faulted_) return ExtendedDeviceStatus::kFaultedIoConnection;
  bool any = false;
  for (const Connection& connection : connections_) {
    if (!connection.open || connection.transport_class != 1) continue;
    if (connection.run) return ExtendedDeviceStatus::kIoConnectionInRunMode;
    any = true;
  }
  return any ? ExtendedDeviceStatus::kIoConnectionsIdle : ExtendedDeviceStatus::kNoIoConnections;
}

// ---- Class 3 -------------------------------------------------------------------------------------------

std::size_t ConnectionManager::HandleConnected(std::uint32_t connection_id, std::uint16_t sequence_count,
                                               std::span<const std::uint8_t> request, RequestContext& context,
                                               std::span<std::uint8_t> reply, std::uint32_t& reply_connection_id) {
  Connection* found = nullptr;
  for (Connection& connection : connections_) {
    if (connection.open && connection.transport_class == 3 && connection.o_to_t_id == connection_id &&
        connection.session_handle == context.session_handle) {
      found = &connection;
      break;
    }
  }
  if (found == nullptr || found->explicit_slot == kNone || reply.size() < kSequenceCountSize) return 0;
  Connection& connection = *found;
  connection.deadline = context.now + connection.timeout;
  std::span<std::uint8_t> cache = explicit_replies_[static_cast<std::size_t>(connection.explicit_slot)];
  reply_connection_id = connection.t_to_o_id;
  if (connection.has_reply && sequence_count == connection.last_sequence) {
    if (connection.reply_size > reply.size()) return 0;
    std::copy_n(cache.begin(), connection.reply_size, reply.begin());
    return connection.reply_size;
  }

  // The reply may not exceed the T->O connection size (which counts the sequence count too).
  const std::size_t capacity = std::min({reply.size(), cache.size(), static_cast<std::size_t>(connection.t_to_o_size)});
  if (capacity <= kSequenceCountSize) return 0;
  const std::uint32_t t_to_o_id = connection.t_to_o_id;
  const int slot = connection.explicit_slot;
  base::ByteWriter out(reply.first(capacity));
  out.U16Le(sequence_count);
  const std::size_t size = router_.Handle(request, context, out.Tail(), 0);
  // Deferred: nothing is kept, the retry executes the request again (and then stores its reply).
  if (context.pending) return 0;
  if (size == 0) return 0;
  out.Advance(size);
  // The request may have closed this very connection (a Forward_Close over it): then nothing is kept.
  if (connection.open && connection.t_to_o_id == t_to_o_id && connection.explicit_slot == slot) {
    std::copy(out.written().begin(), out.written().end(), cache.begin());
    connection.has_reply = true;
    connection.last_sequence = sequence_count;
    connection.reply_size = static_cast<std::uint16_t>(out.size());
  }
  return out.size();
}

bool ConnectionManager::SessionHasConnections(std::uint32_t session_handle) const {
  return session_handle != 0 && std::any_of(connections_.begin(), connections_.end(), [&](const Connection& c) {
           return c.open && c.session_handle == session_handle;
         });
}

void ConnectionManager::OnSessionClosed(std::uint32_t session_handle) {
  if (session_handle == 0) return;
  for (std::size_t i = 0; i < connections_.size(); ++i) {
    Connection& connection = connections_[i];
    if (!connection.open || connection.session_handle != session_handle) continue;
    if (connection.transport_class == 3) {
      Close(i, CloseReason::kSessionClosed);
    } else {
      connection.session_handle = 0;  // I/O connections outlive the TCP connection that opened them
    }
  }
}

}  // namespace cip
