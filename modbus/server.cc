#include "modbus/server.h"

#include <algorithm>

namespace modbus {

Server::Server(drive_link::DriveRegisters& drive, drive_link::ScannerImage& scanner,
               drive_link::LossSupervision& supervision, const ServerOptions& options)
    : shared_(drive, scanner, supervision) {
  shared_.idle_timeout = options.idle_timeout;
  for (Connection& connection : connections_) connection.Attach(shared_);
  Configure(shared_.config);
}

void Server::Configure(const config::CardConfig& config) {
  shared_.config = config;
  shared_.loss.Configure(config.timeout_tenths, config.io_scanning);
}

base::Result<ConnectionId> Server::Open(const base::Ipv4Address& peer, hal::Micros now) {
  for (std::size_t i = 0; i < connections_.size(); ++i) {
    if (connections_[i].is_open()) continue;
    connections_[i].Open(peer, now);
    ++shared_.clients;
    ++shared_.counters.accepted;
    client_marks_.NoteTaken(client_pool().used);
    return static_cast<ConnectionId>(i);
  }
  ++shared_.counters.refused;
  client_marks_.NoteRefused();
  return base::ResourceExhausted();
}

base::PoolStats Server::client_pool() const {
  const auto used = static_cast<std::size_t>(
      std::count_if(connections_.begin(), connections_.end(), [](const Connection& c) { return c.is_open(); }));
  return client_marks_.Stats(used, kMaxClients);
}

void Server::Close(ConnectionId id) {
  Connection* connection = Find(id);
  if (connection == nullptr) return;
  connection->Close();
  --shared_.clients;
}

std::size_t Server::Receive(ConnectionId id, std::span<const std::uint8_t> bytes, hal::Micros now) {
  Connection* connection = Find(id);
  return connection == nullptr ? 0 : connection->Receive(bytes, now);
}

std::span<const std::uint8_t> Server::PendingOutput(ConnectionId id) const {
  const Connection* connection = Find(id);
  return connection == nullptr ? std::span<const std::uint8_t>() : connection->answers();
}

void Server::ConsumeOutput(ConnectionId id, std::size_t count, hal::Micros now) {
  Connection* connection = Find(id);
  if (connection != nullptr) connection->ConsumeAnswers(count, now);
}

std::size_t Server::TakeReleasedInput(ConnectionId id) {
  Connection* connection = Find(id);
  return connection == nullptr ? 0 : connection->TakeReleasedInput();
}

bool Server::MustClose(ConnectionId id) const {
  const Connection* connection = Find(id);
  return connection != nullptr && connection->must_close();
}

void Server::Poll(hal::Micros now) {
  for (Connection& connection : connections_) connection.Poll(now);
  shared_.loss.Poll(now);
}

hal::Micros Server::NextDeadline() const {
  hal::Micros deadline = shared_.loss.NextDeadline();
  for (const Connection& connection : connections_) deadline = std::min(deadline, connection.NextDeadline());
  return deadline;
}

Connection* Server::Find(ConnectionId id) {
  if (id >= connections_.size() || !connections_[id].is_open()) return nullptr;
  return &connections_[id];
}

const Connection* Server::Find(ConnectionId id) const {
  if (id >= connections_.size() || !connections_[id].is_open()) return nullptr;
  return &connections_[id];
}

}  // namespace modbus
