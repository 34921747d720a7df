#include "control_server.h"

#include <fcntl.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>

namespace hal::host {

std::size_t SplitCommand(std::string_view command, std::span<std::string_view> words) {
  std::size_t count = 0;
  while (!command.empty() && count < words.size()) {
    const std::size_t start = command.find_first_not_of(' ');
    if (start == std::string_view::npos) break;
    command.remove_prefix(start);
    const std::size_t end = command.find(' ');
    words[count++] = command.substr(0, end);
    command.remove_prefix(end == std::string_view::npos ? command.size() : end);
  }
  return command.find_first_not_of(' ') == std::string_view::npos ? count : words.size() + 1;
}

ControlServer::ControlServer(std::string path, Handler handler)
    : path_(std::move(path)), handler_(std::move(handler)) {}

ControlServer::~ControlServer() {
  for (Client& client : clients_) Close(client);
  if (listen_fd_ >= 0) {
    close(listen_fd_);
    unlink(path_.c_str());
  }
}

bool ControlServer::Start(std::string& error) {
  sockaddr_un address{};
  address.sun_family = AF_UNIX;
  if (path_.size() >= sizeof(address.sun_path)) {
    error = "control socket path too long: " + path_;
    return false;
  }
  std::memcpy(address.sun_path, path_.c_str(), path_.size() + 1);
  listen_fd_ = socket(AF_UNIX, SOCK_STREAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
  if (listen_fd_ < 0) {
    error = std::string("control socket: ") + std::strerror(errno);
    return false;
  }
  unlink(path_.c_str());
  if (bind(listen_fd_, reinterpret_cast<const sockaddr*>(&address), sizeof address) != 0 ||
      listen(listen_fd_, 4) != 0) {
    error = "control socket " + path_ + ": " + std::strerror(errno);
    close(listen_fd_);
    listen_fd_ = -1;
    return false;
  }
  return true;
}

void ControlServer::PrepareWait(PollSet& set, Micros& /*deadline*/) {
  if (listen_fd_ < 0) return;
  listen_slot_ = set.Add(listen_fd_, POLLIN);
  for (Client& client : clients_) {
    client.slot = set.Add(client.fd, static_cast<short>(POLLIN | (client.out.empty() ? 0 : POLLOUT)));
  }
}

void ControlServer::AfterWait(const PollSet& set) {
  if (listen_fd_ < 0) return;
  // Clients accepted in this call have no poll slot yet; serve only those that were polled.
  const std::size_t polled = clients_.size();
  for (std::size_t i = 0; i < polled; ++i) {
    Client& client = clients_[i];
    const short revents = set.Revents(client.slot);
    if ((revents & (POLLIN | POLLHUP | POLLERR)) != 0) ServeInput(client);
    if (client.fd >= 0 && !client.out.empty()) Flush(client);
  }
  clients_.erase(std::remove_if(clients_.begin(), clients_.end(),
                                [](const Client& c) { return c.fd < 0; }),
                 clients_.end());
  if ((set.Revents(listen_slot_) & POLLIN) != 0) Accept();
}

void ControlServer::Accept() {
  for (;;) {
    const int fd = accept4(listen_fd_, nullptr, nullptr, SOCK_NONBLOCK | SOCK_CLOEXEC);
    if (fd < 0) return;
    if (clients_.size() >= kMaxClients) {
      static constexpr char kRefusal[] = "error too many clients\n";
      (void)!send(fd, kRefusal, sizeof kRefusal - 1, MSG_NOSIGNAL);
      close(fd);
      continue;
    }
    clients_.push_back(Client{fd, {}, {}, 0});
  }
}

void ControlServer::ServeInput(Client& client) {
  char buffer[1024];
  for (;;) {
    const ssize_t n = recv(client.fd, buffer, sizeof buffer, 0);
    if (n == 0 || (n < 0 && errno != EAGAIN && errno != EINTR)) {
      // Peer closed: answer what was complete, then close after the flush.
      Flush(client);
      Close(client);
      return;
    }
    if (n < 0) break;
    client.in.append(buffer, static_cast<std::size_t>(n));
    std::size_t newline;
    while ((newline = client.in.find('\n')) != std::string::npos) {
      std::string_view line(client.in.data(), newline);
      if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
      if (!line.empty()) handler_(line, client.out);
      client.in.erase(0, newline + 1);
    }
    if (client.in.size() > kMaxLineBytes || client.out.size() > kMaxPendingReplyBytes) {
      client.out += "error line too long\n";
      Flush(client);
      Close(client);
      return;
    }
  }
}

void ControlServer::Flush(Client& client) {
  while (!client.out.empty() && client.fd >= 0) {
    const ssize_t n = send(client.fd, client.out.data(), client.out.size(), MSG_NOSIGNAL);
    if (n <= 0) {
      if (n < 0 && (errno == EAGAIN || errno == EINTR)) return;
      Close(client);
      return;
    }
    client.out.erase(0, static_cast<std::size_t>(n));
  }
}

void ControlServer::Close(Client& client) {
  if (client.fd >= 0) close(client.fd);
  client.fd = -1;
}

}  // namespace hal::host
