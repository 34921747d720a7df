// The card's Modbus TCP server (seed 000 §8, §9; MB-1..MB-5), without any transport: the lwIP binding
// (firmware/modbus_tcp_service.h) opens a connection per accepted TCP client, feeds its bytes in,
// takes the answers out and closes it when told. docs/modbus.md describes the behaviour.
//
//   modbus::Server server(drive_registers, scanner_image, loss_supervision);
//   server.Configure(card_config);              // c500, c523, c600-c604, ... (again after f899 = 1)
//   server.SetBoardData(board_data);            // whenever the firmware's data changes
//   ConnectionId id = *server.Open(peer, now);  // kResourceExhausted: kMaxClients open already
//   server.Receive(id, bytes, now);             // then hand server.PendingOutput(id) to TCP
//   server.Poll(now);                           // every pass; NextDeadline() says when next
//
// Time is injected (absolute microseconds on hal::Clock) with the meaning of firmware::Service. Units:
// 0-248 the drive (through drive_link::DriveRegisters, asynchronous), 251 the option board (read-only,
// option_board.h), 255 IO scanning (io_scanning.h). The c523 timer (loss_timer.h) runs over all
// connections together.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "base/pool_stats.h"
#include "base/status.h"
#include "config/card_config.h"
#include "drive_link/register_access.h"
#include "hal/clock.h"
#include "modbus/connection.h"
#include "modbus/io_scanning.h"
#include "modbus/option_board.h"

namespace modbus {

using ConnectionId = std::uint8_t;

struct ServerOptions {
  // A connection without a request for this long is closed (0: never). Two minutes: the same order as
  // the TCP keepalive that finds a vanished peer (lwipopts.h: 60 s + 6 x 10 s); a polling client
  // sends far more often.
  hal::Micros idle_timeout = 120 * hal::kMicrosPerSecond;
};

class Server {
 public:
  // Concurrent clients (IPE_MAX_MODBUS_CLIENTS in lwipopts.h).
  static constexpr std::size_t kMaxClients = 8;

  Server(drive_link::DriveRegisters& drive, drive_link::ScannerImage& scanner,
         drive_link::LossSupervision& supervision, const ServerOptions& options = {});
  Server(const Server&) = delete;
  Server& operator=(const Server&) = delete;

  void Configure(const config::CardConfig& config);
  void SetBoardData(const OptionBoardData& data) { shared_.board = data; }

  // A TCP client was accepted. kResourceExhausted when kMaxClients are open (the caller refuses it).
  base::Result<ConnectionId> Open(const base::Ipv4Address& peer, hal::Micros now);
  // The client is gone or the binding closed it: drive accesses in flight are cancelled.
  void Close(ConnectionId id);

  // Received bytes; returns how many were taken (all of them while lwIP's window is not larger than
  // kReceiveBufferBytes). Answers ready at once are in PendingOutput afterwards.
  std::size_t Receive(ConnectionId id, std::span<const std::uint8_t> bytes, hal::Micros now);
  std::span<const std::uint8_t> PendingOutput(ConnectionId id) const;
  // `count` bytes of PendingOutput were handed to TCP.
  void ConsumeOutput(ConnectionId id, std::size_t count, hal::Micros now);
  // Receive bytes freed since the last call: the binding reopens the TCP window by as much.
  std::size_t TakeReleasedInput(ConnectionId id);
  // The connection must be closed (a header that cannot be framed, or idle): after handing over its
  // PendingOutput, the binding closes the TCP connection and calls Close().
  bool MustClose(ConnectionId id) const;

  void Poll(hal::Micros now);
  hal::Micros NextDeadline() const;

  std::size_t open_connections() const { return shared_.clients; }
  // The client table (docs/robustness.md "Exhaustion"), counted from the slots; refused: Open answered
  // kResourceExhausted.
  base::PoolStats client_pool() const;
  LossState loss_state() const { return shared_.loss.state(); }
  const ServerCounters& counters() const { return shared_.counters; }
  const config::CardConfig& config() const { return shared_.config; }

 private:
  Connection* Find(ConnectionId id);
  const Connection* Find(ConnectionId id) const;

  ServerShared shared_;
  std::array<Connection, kMaxClients> connections_;
  base::PoolWatermark client_marks_;
};

}  // namespace modbus
