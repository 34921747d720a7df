#include "socket_io.h"

#include <arpa/inet.h>
#include <fcntl.h>
#include <ifaddrs.h>
#include <net/if.h>
#include <netdb.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>

#include "failure.h"

namespace ipe {
namespace {

std::string ErrnoText(int error) { return std::strerror(error); }

// poll() on one descriptor for at most timeout_ms in all. A signal that interrupts the wait (Ctrl-C while
// a request is out: the command finishes the request, then sees Interrupted()) waits on for the rest of
// the time instead of ending the command as an unreachable card. > 0 ready, 0 timed out, < 0 error.
int PollWithin(int fd, short events, int timeout_ms) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::milliseconds(timeout_ms);
  for (;;) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
    pollfd p{fd, events, 0};
    const int ready = poll(&p, 1, left.count() > 0 ? static_cast<int>(left.count()) : 0);
    if (ready >= 0 || errno != EINTR) return ready;
  }
}

}  // namespace

in_addr ResolveHost(const std::string& host) {
  in_addr address{};
  if (inet_pton(AF_INET, host.c_str(), &address) == 1) return address;
  addrinfo hints{};
  hints.ai_family = AF_INET;
  addrinfo* result = nullptr;
  if (getaddrinfo(host.c_str(), nullptr, &hints, &result) != 0 || result == nullptr) {
    Fail(kExitUsage, "cannot resolve host '" + host + "'");
  }
  address = reinterpret_cast<sockaddr_in*>(result->ai_addr)->sin_addr;
  freeaddrinfo(result);
  return address;
}

std::string FormatAddress(in_addr address) {
  char text[INET_ADDRSTRLEN] = {};
  inet_ntop(AF_INET, &address, text, sizeof text);
  return text;
}

TcpConnection::TcpConnection(const std::string& host, std::uint16_t port, int timeout_ms) : timeout_ms_(timeout_ms) {
  peer_ = ResolveHost(host);
  name_ = host + ":" + std::to_string(port);
  fd_ = socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC | SOCK_NONBLOCK, 0);
  if (fd_ < 0) Fail(kExitUnreachable, "socket: " + ErrnoText(errno));
  sockaddr_in to{};
  to.sin_family = AF_INET;
  to.sin_port = htons(port);
  to.sin_addr = peer_;
  if (connect(fd_, reinterpret_cast<const sockaddr*>(&to), sizeof to) != 0 && errno != EINPROGRESS) {
    Fail(kExitUnreachable, name_ + ": " + ErrnoText(errno));
  }
  const int ready = PollWithin(fd_, POLLOUT, timeout_ms_);
  if (ready == 0) Fail(kExitUnreachable, name_ + ": no answer within " + std::to_string(timeout_ms_) + " ms");
  int error = 0;
  socklen_t length = sizeof error;
  getsockopt(fd_, SOL_SOCKET, SO_ERROR, &error, &length);
  if (ready < 0 || error != 0) Fail(kExitUnreachable, name_ + ": " + ErrnoText(ready < 0 ? errno : error));
  const int one = 1;
  setsockopt(fd_, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
}

TcpConnection::~TcpConnection() {
  if (fd_ >= 0) close(fd_);
}

void TcpConnection::Send(std::span<const std::uint8_t> bytes) {
  std::size_t sent = 0;
  while (sent < bytes.size()) {
    const ssize_t n = send(fd_, bytes.data() + sent, bytes.size() - sent, MSG_NOSIGNAL);
    if (n < 0 && (errno == EAGAIN || errno == EINTR)) {
      if (PollWithin(fd_, POLLOUT, timeout_ms_) <= 0) Fail(kExitUnreachable, name_ + ": send timed out");
      continue;
    }
    if (n <= 0) Fail(kExitUnreachable, name_ + ": " + ErrnoText(errno));
    sent += static_cast<std::size_t>(n);
  }
}

void TcpConnection::WaitReadable() {
  const int ready = PollWithin(fd_, POLLIN, timeout_ms_);
  if (ready == 0) Fail(kExitUnreachable, name_ + ": no reply within " + std::to_string(timeout_ms_) + " ms");
  if (ready < 0) Fail(kExitUnreachable, name_ + ": " + ErrnoText(errno));
}

std::vector<std::uint8_t> TcpConnection::Receive(std::size_t count) {
  std::vector<std::uint8_t> bytes(count);
  std::size_t got = 0;
  while (got < count) {
    WaitReadable();
    const ssize_t n = recv(fd_, bytes.data() + got, count - got, 0);
    if (n == 0) Fail(kExitUnreachable, name_ + ": the card closed the connection");
    if (n < 0) {
      if (errno == EAGAIN || errno == EINTR) continue;
      Fail(kExitUnreachable, name_ + ": " + ErrnoText(errno));
    }
    got += static_cast<std::size_t>(n);
  }
  return bytes;
}

std::vector<std::uint8_t> TcpConnection::ReceiveSome() {
  std::vector<std::uint8_t> bytes(512);
  for (;;) {
    WaitReadable();
    const ssize_t n = recv(fd_, bytes.data(), bytes.size(), 0);
    if (n == 0) Fail(kExitUnreachable, name_ + ": the card closed the connection");
    if (n < 0) {
      if (errno == EAGAIN || errno == EINTR) continue;
      Fail(kExitUnreachable, name_ + ": " + ErrnoText(errno));
    }
    bytes.resize(static_cast<std::size_t>(n));
    return bytes;
  }
}

UdpSocket::UdpSocket(in_addr bind_address, std::uint16_t port) {
  fd_ = socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
  if (fd_ < 0) Fail(kExitUnreachable, "socket: " + ErrnoText(errno));
  const int one = 1;
  setsockopt(fd_, SOL_SOCKET, SO_BROADCAST, &one, sizeof one);
  sockaddr_in local{};
  local.sin_family = AF_INET;
  local.sin_port = htons(port);
  local.sin_addr = bind_address;
  if (bind(fd_, reinterpret_cast<const sockaddr*>(&local), sizeof local) != 0) {
    Fail(kExitUnreachable, "cannot bind UDP " + FormatAddress(bind_address) + ":" + std::to_string(port) + ": " +
                               ErrnoText(errno));
  }
}

UdpSocket::~UdpSocket() {
  if (fd_ >= 0) close(fd_);
}

void UdpSocket::SendTo(std::span<const std::uint8_t> bytes, in_addr address, std::uint16_t port) {
  sockaddr_in to{};
  to.sin_family = AF_INET;
  to.sin_port = htons(port);
  to.sin_addr = address;
  if (sendto(fd_, bytes.data(), bytes.size(), 0, reinterpret_cast<const sockaddr*>(&to), sizeof to) < 0) {
    Fail(kExitUnreachable, "send to " + FormatAddress(address) + ":" + std::to_string(port) + ": " + ErrnoText(errno));
  }
}

bool UdpSocket::ReceiveFrom(std::vector<std::uint8_t>& bytes, sockaddr_in& from, int timeout_ms) {
  const int ready = PollWithin(fd_, POLLIN, timeout_ms < 0 ? 0 : timeout_ms);
  if (ready <= 0) return false;
  bytes.resize(1500);
  socklen_t length = sizeof from;
  const ssize_t n = recvfrom(fd_, bytes.data(), bytes.size(), 0, reinterpret_cast<sockaddr*>(&from), &length);
  if (n < 0) return false;
  bytes.resize(static_cast<std::size_t>(n));
  return true;
}

void UdpSocket::BindToDevice(const std::string& interface_name) {
  // Best effort: without CAP_NET_RAW the kernel refuses SO_BINDTODEVICE; the broadcast address of the
  // interface still routes the request out of it.
  (void)setsockopt(fd_, SOL_SOCKET, SO_BINDTODEVICE, interface_name.c_str(),
                   static_cast<socklen_t>(interface_name.size()));
}

in_addr InterfaceBroadcast(const std::string& interface_name) {
  ifaddrs* list = nullptr;
  if (getifaddrs(&list) != 0) Fail(kExitUsage, "cannot list network interfaces");
  in_addr found{};
  bool have = false;
  for (ifaddrs* i = list; i != nullptr; i = i->ifa_next) {
    if (i->ifa_addr == nullptr || i->ifa_addr->sa_family != AF_INET || interface_name != i->ifa_name) continue;
    if ((i->ifa_flags & IFF_BROADCAST) != 0 && i->ifa_broadaddr != nullptr) {
      found = reinterpret_cast<sockaddr_in*>(i->ifa_broadaddr)->sin_addr;
      have = true;
      break;
    }
  }
  freeifaddrs(list);
  if (!have) Fail(kExitUsage, "interface '" + interface_name + "' has no IPv4 broadcast address");
  return found;
}

}  // namespace ipe
