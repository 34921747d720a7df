// Kernel sockets with bounded waits for tools/ipe: a TCP connection to the card and UDP datagrams.
// Every call fails with kExitUnreachable (failure.h) on a refused connection or a timeout.
#pragma once

#include <netinet/in.h>

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace ipe {

// Resolves an IPv4 address or host name; Fail(kExitUsage) when it cannot.
in_addr ResolveHost(const std::string& host);
std::string FormatAddress(in_addr address);

class TcpConnection {
 public:
  // Connects within timeout_ms.
  TcpConnection(const std::string& host, std::uint16_t port, int timeout_ms);
  ~TcpConnection();
  TcpConnection(const TcpConnection&) = delete;
  TcpConnection& operator=(const TcpConnection&) = delete;

  void Send(std::span<const std::uint8_t> bytes);
  // Exactly `count` bytes within timeout_ms.
  std::vector<std::uint8_t> Receive(std::size_t count);
  // Whatever arrives next (at least one byte) within timeout_ms.
  std::vector<std::uint8_t> ReceiveSome();
  in_addr peer() const { return peer_; }
  const std::string& name() const { return name_; }

 private:
  void WaitReadable();
  int fd_ = -1;
  int timeout_ms_;
  in_addr peer_{};
  std::string name_;  // "host:port" for messages
};

class UdpSocket {
 public:
  // Bound to `bind_address:port` (port 0: any), broadcast allowed.
  UdpSocket(in_addr bind_address, std::uint16_t port);
  ~UdpSocket();
  UdpSocket(const UdpSocket&) = delete;
  UdpSocket& operator=(const UdpSocket&) = delete;

  void SendTo(std::span<const std::uint8_t> bytes, in_addr address, std::uint16_t port);
  // One datagram within timeout_ms (false on timeout); its sender in `from`.
  bool ReceiveFrom(std::vector<std::uint8_t>& bytes, sockaddr_in& from, int timeout_ms);
  // Restricts sends to one interface (SO_BINDTODEVICE may need privileges; IP_MULTICAST_IF does not).
  void BindToDevice(const std::string& interface_name);

 private:
  int fd_ = -1;
};

// The IPv4 broadcast address of a network interface ("eth0"); Fail(kExitUsage) when it has none.
in_addr InterfaceBroadcast(const std::string& interface_name);

}  // namespace ipe
