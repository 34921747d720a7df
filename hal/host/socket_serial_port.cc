#include "socket_serial_port.h"

#include <fcntl.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>

namespace hal::host {

base::Result<SocketSerialPort::Pair> SocketSerialPort::CreatePair() {
  int fds[2] = {-1, -1};
  if (socketpair(AF_UNIX, SOCK_STREAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0, fds) != 0) {
    return base::Internal();
  }
  Pair pair;
  pair.card = std::make_unique<SocketSerialPort>(fds[0]);
  pair.inverter = std::make_unique<SocketSerialPort>(fds[1]);
  return pair;
}

SocketSerialPort::SocketSerialPort(int fd) : fd_(fd) {
  const int flags = fcntl(fd_, F_GETFL);
  if (flags >= 0) fcntl(fd_, F_SETFL, flags | O_NONBLOCK);
}

SocketSerialPort::~SocketSerialPort() {
  if (fd_ >= 0) close(fd_);
}

base::Status SocketSerialPort::Configure(const SerialConfig& config) {
  if (config.baud == 0 || (config.stop_bits != 1 && config.stop_bits != 2)) {
    return base::InvalidArgument();
  }
  config_ = config;
  return base::OkStatus();
}

base::Result<std::size_t> SocketSerialPort::Read(std::span<std::uint8_t> buffer) {
  // recv() of zero bytes would be indistinguishable from the far end closing.
  if (buffer.empty() || peer_closed_) return base::Unavailable();
  ssize_t n = -1;
  do {
    n = recv(fd_, buffer.data(), buffer.size(), 0);
  } while (n < 0 && errno == EINTR);
  if (n < 0) {
    if (errno == EAGAIN || errno == EWOULDBLOCK) return base::Unavailable();
    if (errno != ECONNRESET) return base::Internal();
    n = 0;
  }
  if (n == 0) {
    peer_closed_ = true;
    return base::Unavailable();
  }
  return static_cast<std::size_t>(n);
}

base::Result<std::size_t> SocketSerialPort::Write(std::span<const std::uint8_t> bytes) {
  if (bytes.empty()) return std::size_t{0};
  // A UART transmits into a dead line without noticing: once the far end is gone, bytes vanish.
  if (peer_closed_) return bytes.size();
  ssize_t n = -1;
  do {
    // MSG_NOSIGNAL: a closed far end must give EPIPE, not kill the process with SIGPIPE.
    n = send(fd_, bytes.data(), bytes.size(), MSG_NOSIGNAL);
  } while (n < 0 && errno == EINTR);
  if (n < 0) {
    if (errno == EAGAIN || errno == EWOULDBLOCK) return std::size_t{0};  // transmit buffer full
    if (errno == EPIPE || errno == ECONNRESET) {
      peer_closed_ = true;
      return bytes.size();
    }
    return base::Internal();
  }
  return static_cast<std::size_t>(n);
}

void SocketSerialPort::PrepareWait(PollSet& set, Micros& /*deadline*/) {
  // A closed socket is readable forever (end of file); watching it would make poll() spin.
  if (!peer_closed_) set.Add(fd_, POLLIN);
}

void SocketSerialPort::AfterWait(const PollSet& /*set*/) {
  // Nothing to do: Read() takes the bytes straight from the socket.
}

}  // namespace hal::host
