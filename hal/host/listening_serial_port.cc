#include "listening_serial_port.h"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <cstring>

namespace hal::host {
namespace {

// Pending connections the kernel keeps while the line is busy: QEMU connects once per start.
constexpr int kListenBacklog = 2;

std::string Errno(const std::string& what) { return what + ": " + std::strerror(errno); }

// One bound address: IPv4 or IPv6.
struct TcpAddress {
  sockaddr_storage storage{};
  socklen_t length = 0;
};

// HOST:PORT with HOST a numeric IPv4 address, a bracketed IPv6 address or "localhost" (127.0.0.1).
bool ParseTcp(std::string_view text, TcpAddress& out) {
  const std::size_t colon = text.rfind(':');
  if (colon == std::string_view::npos || colon == 0) return false;
  std::string host(text.substr(0, colon));
  const std::string_view port_text = text.substr(colon + 1);
  unsigned port = 0;
  const auto [end, ec] = std::from_chars(port_text.data(), port_text.data() + port_text.size(), port);
  if (port_text.empty() || ec != std::errc() || end != port_text.data() + port_text.size() || port > 65535) {
    return false;
  }
  if (host == "localhost") host = "127.0.0.1";
  if (host.size() > 2 && host.front() == '[' && host.back() == ']') {
    sockaddr_in6 v6{};
    v6.sin6_family = AF_INET6;
    v6.sin6_port = htons(static_cast<std::uint16_t>(port));
    if (inet_pton(AF_INET6, host.substr(1, host.size() - 2).c_str(), &v6.sin6_addr) != 1) return false;
    std::memcpy(&out.storage, &v6, sizeof v6);
    out.length = sizeof v6;
    return true;
  }
  sockaddr_in v4{};
  v4.sin_family = AF_INET;
  v4.sin_port = htons(static_cast<std::uint16_t>(port));
  if (inet_pton(AF_INET, host.c_str(), &v4.sin_addr) != 1) return false;
  std::memcpy(&out.storage, &v4, sizeof v4);
  out.length = sizeof v4;
  return true;
}

// "tcp:ADDRESS:PORT" of a bound socket (the port the kernel chose for port 0).
std::string TcpEndpointOf(int fd) {
  sockaddr_storage bound{};
  socklen_t length = sizeof bound;
  if (getsockname(fd, reinterpret_cast<sockaddr*>(&bound), &length) != 0) return "tcp:?";
  char text[INET6_ADDRSTRLEN] = "?";
  if (bound.ss_family == AF_INET6) {
    sockaddr_in6 v6{};
    std::memcpy(&v6, &bound, sizeof v6);
    inet_ntop(AF_INET6, &v6.sin6_addr, text, sizeof text);
    return "tcp:[" + std::string(text) + "]:" + std::to_string(ntohs(v6.sin6_port));
  }
  sockaddr_in v4{};
  std::memcpy(&v4, &bound, sizeof v4);
  inet_ntop(AF_INET, &v4.sin_addr, text, sizeof text);
  return "tcp:" + std::string(text) + ":" + std::to_string(ntohs(v4.sin_port));
}

// Whether a live process accepts connections on the UNIX socket at `address` (a stale socket file left
// by a process that ended refuses them).
bool SomeoneListens(const sockaddr_un& address) {
  const int probe = socket(AF_UNIX, SOCK_STREAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
  if (probe < 0) return false;
  const int rc = connect(probe, reinterpret_cast<const sockaddr*>(&address), sizeof address);
  const bool live = rc == 0 || errno == EAGAIN;  // EAGAIN: alive, its backlog is full
  close(probe);
  return live;
}

// A parsed endpoint: a UNIX socket path or a TCP address.
struct Endpoint {
  bool tcp = false;
  std::string path;  // UNIX
  sockaddr_un unix_address{};
  TcpAddress tcp_address;
};

bool ParseEndpoint(std::string_view text, Endpoint& out, std::string& why) {
  if (text.substr(0, 5) == "unix:") {
    out.tcp = false;
    out.path = std::string(text.substr(5));
    if (out.path.empty() || out.path.size() >= sizeof out.unix_address.sun_path) {
      why = "the path must be 1 to " + std::to_string(sizeof out.unix_address.sun_path - 1) + " bytes";
      return false;
    }
    out.unix_address.sun_family = AF_UNIX;
    std::memcpy(out.unix_address.sun_path, out.path.c_str(), out.path.size() + 1);
    return true;
  }
  out.tcp = true;
  if (text.substr(0, 4) == "tcp:" && ParseTcp(text.substr(4), out.tcp_address)) return true;
  why = "expected unix:PATH or tcp:HOST:PORT, HOST a numeric address or localhost";
  return false;
}

}  // namespace

bool ListeningSerialPort::CheckEndpoint(std::string_view endpoint, std::string* error) {
  Endpoint parsed;
  std::string scratch;
  return ParseEndpoint(endpoint, parsed, error != nullptr ? *error : scratch);
}

base::Result<std::unique_ptr<ListeningSerialPort>> ListeningSerialPort::Listen(std::string_view endpoint,
                                                                               std::string* error) {
  std::string scratch;
  std::string& why = error != nullptr ? *error : scratch;
  Endpoint parsed;
  if (!ParseEndpoint(endpoint, parsed, why)) {
    why = "serial endpoint '" + std::string(endpoint) + "': " + why;
    return base::InvalidArgument();
  }
  const bool tcp = parsed.tcp;
  const std::string& path = parsed.path;
  const TcpAddress& tcp_address = parsed.tcp_address;
  const sockaddr_un& unix_address = parsed.unix_address;

  const int family = tcp ? tcp_address.storage.ss_family : AF_UNIX;
  const int fd = socket(family, SOCK_STREAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
  if (fd < 0) {
    why = Errno("serial socket");
    return base::Unavailable();
  }
  int bound = -1;
  if (tcp) {
    const int one = 1;  // a restarted simulator binds again at once, even with connections in TIME_WAIT
    setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
    bound = bind(fd, reinterpret_cast<const sockaddr*>(&tcp_address.storage), tcp_address.length);
  } else {
    // Replace a socket a previous run left behind; never a live one, nor a file of another kind.
    struct stat existing {};
    if (lstat(path.c_str(), &existing) == 0) {
      const char* refusal = !S_ISSOCK(existing.st_mode) ? "exists and is not a socket"
                            : SomeoneListens(unix_address) ? "another process listens there"
                                                           : nullptr;
      if (refusal != nullptr) {
        why = "serial endpoint " + path + ": " + refusal;
        close(fd);
        return base::Unavailable();
      }
      unlink(path.c_str());
    }
    bound = bind(fd, reinterpret_cast<const sockaddr*>(&unix_address), sizeof unix_address);
  }
  if (bound != 0 || listen(fd, kListenBacklog) != 0) {
    why = Errno("serial endpoint " + std::string(endpoint));
    close(fd);
    return base::Unavailable();
  }
  const std::string name = tcp ? TcpEndpointOf(fd) : "unix:" + path;
  return std::unique_ptr<ListeningSerialPort>(new ListeningSerialPort(fd, name, tcp ? "" : path, tcp));
}

ListeningSerialPort::ListeningSerialPort(int listen_fd, std::string endpoint, std::string unix_path, bool tcp)
    : listen_fd_(listen_fd), endpoint_(std::move(endpoint)), unix_path_(std::move(unix_path)), tcp_(tcp) {}

ListeningSerialPort::~ListeningSerialPort() {
  if (client_fd_ >= 0) close(client_fd_);
  if (listen_fd_ >= 0) close(listen_fd_);
  if (!unix_path_.empty()) unlink(unix_path_.c_str());
}

base::Status ListeningSerialPort::Configure(const SerialConfig& config) {
  if (config.baud == 0 || (config.stop_bits != 1 && config.stop_bits != 2)) return base::InvalidArgument();
  config_ = config;
  return base::OkStatus();
}

base::Result<std::size_t> ListeningSerialPort::Read(std::span<std::uint8_t> buffer) {
  // recv() of zero bytes would be indistinguishable from the client going away.
  if (buffer.empty() || client_fd_ < 0) return base::Unavailable();
  ssize_t n = -1;
  do {
    n = recv(client_fd_, buffer.data(), buffer.size(), 0);
  } while (n < 0 && errno == EINTR);
  if (n > 0) return static_cast<std::size_t>(n);
  if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) return base::Unavailable();
  DropClient();  // end of stream, or the connection failed: the cable is out until the next client
  return base::Unavailable();
}

base::Result<std::size_t> ListeningSerialPort::Write(std::span<const std::uint8_t> bytes) {
  // A UART transmits into an unplugged line without noticing: without a client, bytes vanish.
  if (bytes.empty()) return std::size_t{0};
  if (client_fd_ < 0) return bytes.size();
  ssize_t n = -1;
  do {
    // MSG_NOSIGNAL: a vanished client must give EPIPE, not kill the process with SIGPIPE.
    n = send(client_fd_, bytes.data(), bytes.size(), MSG_NOSIGNAL);
  } while (n < 0 && errno == EINTR);
  if (n >= 0) return static_cast<std::size_t>(n);
  if (errno == EAGAIN || errno == EWOULDBLOCK) return std::size_t{0};  // transmit buffer full: retry later
  DropClient();
  return bytes.size();
}

void ListeningSerialPort::PrepareWait(PollSet& set, Micros& /*deadline*/) {
  listen_slot_ = set.Add(listen_fd_, POLLIN);
  // The client's input is read by whoever reads the line (Read); watching it here wakes the loop. A
  // client at end of stream stays readable until a Read notices and drops it, on the same pass.
  if (client_fd_ >= 0) set.Add(client_fd_, POLLIN);
}

void ListeningSerialPort::AfterWait(const PollSet& set) {
  if ((set.Revents(listen_slot_) & POLLIN) != 0) Accept();
}

bool ListeningSerialPort::ClientIsDead() const {
  pollfd probe{client_fd_, POLLIN | POLLRDHUP, 0};
  if (poll(&probe, 1, 0) < 0) return false;
  return (probe.revents & (POLLRDHUP | POLLHUP | POLLERR)) != 0;
}

void ListeningSerialPort::Accept() {
  for (;;) {
    const int fd = accept4(listen_fd_, nullptr, nullptr, SOCK_NONBLOCK | SOCK_CLOEXEC);
    if (fd < 0) return;  // EAGAIN: no more waiting; other errors: the client gave up already
    if (client_fd_ >= 0 && !ClientIsDead()) {
      ++counters_.refused;  // one cable, one peer
      close(fd);
      continue;
    }
    if (client_fd_ >= 0) {
      DropClient();
      ++counters_.replaced;
    }
    if (tcp_) {
      const int one = 1;  // a reply goes out at once, not after the peer's delayed ACK
      setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
    }
    client_fd_ = fd;
    ++counters_.connections;
  }
}

void ListeningSerialPort::DropClient() {
  if (client_fd_ < 0) return;
  close(client_fd_);
  client_fd_ = -1;
  ++counters_.disconnects;
}

}  // namespace hal::host
