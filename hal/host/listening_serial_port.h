// hal::SerialPort on the host, served on a listening socket: the far end of a serial line that another
// process connects to. The stand-alone simulated inverter (ipe002z-inverter) holds its end of the line
// here, and QEMU's UART chardev (`-chardev socket,path=PATH` or `host=...,port=...`, as a client)
// connects to it.
//
// Endpoints: "unix:PATH" (a UNIX stream socket at PATH; a stale socket file there is replaced, any other
// file is refused) or "tcp:HOST:PORT" (HOST a numeric IPv4 address, [IPv6] or localhost; PORT 0 lets the
// kernel choose, endpoint() then names the port in use).
//
// One client at a time, like the one cable of a serial line. A client that connects while another is
// connected and alive is refused (closed at once). A client whose peer went away (QEMU exited or was
// restarted) is dead: it is closed as soon as the line notices (a read finds the end of the stream, a
// write fails), and a new connection always replaces a dead one. Without a client the line behaves like
// a cable pulled out: reads find nothing, writes are accepted and go nowhere.
//
// Never blocks: every socket is non-blocking, and the PollSource adds the listening socket and the
// client to the waiter's poll(). Byte timing (baud, parity) is not modelled: Configure() records it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>

#include "base/status.h"
#include "hal/serial_port.h"
#include "poll_waiter.h"

namespace hal::host {

class ListeningSerialPort final : public SerialPort, public PollSource {
 public:
  struct Counters {
    std::uint64_t connections = 0;  // clients accepted as the line's client
    std::uint64_t replaced = 0;     // of those, how many took the place of a dead client
    std::uint64_t refused = 0;      // clients closed at once: another one was connected and alive
    std::uint64_t disconnects = 0;  // clients closed because they went away (end of stream, reset,
                                    // broken pipe), the dead ones a new client replaced included
  };

  // Binds and listens on `endpoint` ("unix:PATH" or "tcp:HOST:PORT"). kInvalidArgument for an endpoint
  // that does not parse, kUnavailable when the socket cannot be bound; `error` says why in one line.
  static base::Result<std::unique_ptr<ListeningSerialPort>> Listen(std::string_view endpoint, std::string* error);
  // Whether `endpoint` parses (what Listen checks before touching a socket); false with the reason in
  // `error` ("expected unix:PATH or tcp:HOST:PORT, ...").
  static bool CheckEndpoint(std::string_view endpoint, std::string* error);

  ~ListeningSerialPort() override;  // closes the sockets and removes the UNIX socket file
  ListeningSerialPort(const ListeningSerialPort&) = delete;
  ListeningSerialPort& operator=(const ListeningSerialPort&) = delete;

  // hal::SerialPort. Configure: kInvalidArgument for baud 0 or stop bits other than 1 or 2.
  base::Status Configure(const SerialConfig& config) override;
  base::Result<std::size_t> Read(std::span<std::uint8_t> buffer) override;
  base::Result<std::size_t> Write(std::span<const std::uint8_t> bytes) override;

  // hal::host::PollSource: the listening socket (new clients) and the client's input.
  void PrepareWait(PollSet& set, Micros& deadline) override;
  void AfterWait(const PollSet& set) override;

  // "unix:PATH" or "tcp:ADDRESS:PORT" with the port actually bound.
  const std::string& endpoint() const { return endpoint_; }
  bool connected() const { return client_fd_ >= 0; }
  const Counters& counters() const { return counters_; }
  const SerialConfig& config() const { return config_; }

 private:
  ListeningSerialPort(int listen_fd, std::string endpoint, std::string unix_path, bool tcp);
  void Accept();
  void DropClient();
  bool ClientIsDead() const;

  int listen_fd_ = -1;
  int client_fd_ = -1;
  std::string endpoint_;
  std::string unix_path_;  // removed at destruction; empty for TCP
  bool tcp_ = false;
  std::size_t listen_slot_ = 0;
  SerialConfig config_;
  Counters counters_;
};

}  // namespace hal::host
