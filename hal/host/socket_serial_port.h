// hal::SerialPort on the host: one end of a Unix stream socket pair stands in for the card's UART, the
// other end for the inverter's. The simulated inverter (a later part) holds the far end, which is the
// same class, so both sides read, write and plug into the event loop's poll() the same way.
//
// Byte timing of the real line (baud rate, parity, character gaps) is not modelled here yet: Configure()
// only records the settings. When the far end closes, the line behaves like a cable pulled out of the
// inverter: reads find nothing, writes are accepted and go nowhere, and poll() stops watching it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>

#include "base/status.h"
#include "hal/serial_port.h"
#include "poll_waiter.h"

namespace hal::host {

class SocketSerialPort final : public SerialPort, public PollSource {
 public:
  struct Pair {
    std::unique_ptr<SocketSerialPort> card;      // the card's UART
    std::unique_ptr<SocketSerialPort> inverter;  // the far end, for the simulated inverter
  };
  // A connected, non-blocking socketpair(AF_UNIX, SOCK_STREAM). kInternal: the OS refused.
  static base::Result<Pair> CreatePair();

  // Takes ownership of a connected stream socket (made non-blocking here).
  explicit SocketSerialPort(int fd);
  ~SocketSerialPort() override;
  SocketSerialPort(const SocketSerialPort&) = delete;
  SocketSerialPort& operator=(const SocketSerialPort&) = delete;

  // hal::SerialPort. Configure: kInvalidArgument for baud 0 or stop bits other than 1 or 2.
  base::Status Configure(const SerialConfig& config) override;
  base::Result<std::size_t> Read(std::span<std::uint8_t> buffer) override;
  base::Result<std::size_t> Write(std::span<const std::uint8_t> bytes) override;

  const SerialConfig& config() const { return config_; }
  bool peer_closed() const { return peer_closed_; }
  int fd() const { return fd_; }

  // hal::host::PollSource: watches the socket for input until the far end closes.
  void PrepareWait(PollSet& set, Micros& deadline) override;
  void AfterWait(const PollSet& set) override;

 private:
  int fd_ = -1;
  SerialConfig config_;
  bool peer_closed_ = false;
};

}  // namespace hal::host
