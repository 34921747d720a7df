// hal::host::ListeningSerialPort: the far end of a serial line served on a listening socket (UNIX or
// TCP), one client at a time, a new client replacing a dead one, bytes vanishing without a client.
#include "listening_serial_port.h"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <stdlib.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "host_clock.h"
#include "poll_waiter.h"

namespace hal::host {
namespace {

using Bytes = std::vector<std::uint8_t>;

// A connected client socket of the test (QEMU's part), closed at the end.
class Client {
 public:
  explicit Client(int fd) : fd_(fd) {}
  ~Client() { Close(); }
  Client(const Client&) = delete;
  Client& operator=(const Client&) = delete;

  bool ok() const { return fd_ >= 0; }
  void Send(const Bytes& bytes) const {
    ASSERT_EQ(send(fd_, bytes.data(), bytes.size(), MSG_NOSIGNAL), static_cast<ssize_t>(bytes.size()));
  }
  // What arrives within 1 s, up to `count` bytes; fewer when the stream ends.
  Bytes Receive(std::size_t count) const {
    Bytes bytes;
    pollfd ready{fd_, POLLIN, 0};
    while (bytes.size() < count && poll(&ready, 1, 1000) == 1) {
      std::uint8_t buffer[64];
      const ssize_t n = recv(fd_, buffer, std::min(sizeof buffer, count - bytes.size()), 0);
      if (n <= 0) break;
      bytes.insert(bytes.end(), buffer, buffer + n);
    }
    return bytes;
  }
  // True when the server closed the connection (end of stream within 1 s).
  bool ClosedByPeer() const {
    pollfd ready{fd_, POLLIN, 0};
    if (poll(&ready, 1, 1000) != 1) return false;
    std::uint8_t byte = 0;
    return recv(fd_, &byte, 1, 0) == 0;
  }
  void Close() {
    if (fd_ >= 0) close(fd_);
    fd_ = -1;
  }

 private:
  int fd_;
};

class ListeningSerialPortTest : public ::testing::Test {
 protected:
  ListeningSerialPortTest() {
    char pattern[] = "/tmp/ipe-listen-test.XXXXXX";
    dir_ = mkdtemp(pattern);
    path_ = dir_ + "/serial.sock";
  }
  ~ListeningSerialPortTest() override {
    port_.reset();
    std::filesystem::remove_all(dir_);
  }

  void Listen(const std::string& endpoint) {
    std::string error;
    auto port = ListeningSerialPort::Listen(endpoint, &error);
    ASSERT_TRUE(port.ok()) << error;
    port_ = std::move(port.value());
    waiter_.Register(*port_);
  }

  Client ConnectUnix() const {
    const int fd = socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
    sockaddr_un address{};
    address.sun_family = AF_UNIX;
    std::strncpy(address.sun_path, path_.c_str(), sizeof address.sun_path - 1);
    if (connect(fd, reinterpret_cast<const sockaddr*>(&address), sizeof address) != 0) {
      close(fd);
      return Client(-1);
    }
    return Client(fd);
  }

  // One pass of the loop: wait (at most 200 ms) for what is ready, then let the port act on it.
  void Pass() { waiter_.WaitUntil(clock_.NowMicros() + 200 * kMicrosPerMilli); }

  // Everything readable on the port right now.
  Bytes ReadAll() {
    Bytes all;
    std::uint8_t buffer[256];
    for (;;) {
      const base::Result<std::size_t> n = port_->Read(buffer);
      if (!n.ok()) break;
      all.insert(all.end(), buffer, buffer + *n);
    }
    return all;
  }
  // Reads until `count` bytes came (the client's bytes may need a pass to arrive).
  Bytes ReadBytes(std::size_t count) {
    Bytes all;
    for (int pass = 0; pass < 10 && all.size() < count; ++pass) {
      Pass();
      const Bytes more = ReadAll();
      all.insert(all.end(), more.begin(), more.end());
    }
    return all;
  }

  std::string dir_;
  std::string path_;
  HostClock clock_;
  PollWaiter waiter_{clock_};
  std::unique_ptr<ListeningSerialPort> port_;
};

// The manual's binary read of FD01 and its answer, as opaque bytes.
const Bytes kRequest = {0x2F, 0x52, 0xFD, 0x01, 0x7F};
const Bytes kAnswer = {0x2F, 0x52, 0xFD, 0x01, 0x48, 0x00, 0xC7};

TEST_F(ListeningSerialPortTest, UnixClientExchangesBytes) {
  Listen("unix:" + path_);
  EXPECT_EQ(port_->endpoint(), "unix:" + path_);
  EXPECT_FALSE(port_->connected());
  Client qemu = ConnectUnix();
  ASSERT_TRUE(qemu.ok());
  Pass();
  EXPECT_TRUE(port_->connected());
  EXPECT_EQ(port_->counters().connections, 1u);
  qemu.Send(kRequest);
  EXPECT_EQ(ReadBytes(kRequest.size()), kRequest);
  ASSERT_EQ(port_->Write(kAnswer).value(), kAnswer.size());
  EXPECT_EQ(qemu.Receive(kAnswer.size()), kAnswer);
}

TEST_F(ListeningSerialPortTest, WithoutAClientBytesVanish) {
  Listen("unix:" + path_);
  std::uint8_t buffer[8];
  EXPECT_EQ(port_->Read(buffer).status(), base::Unavailable());
  EXPECT_EQ(port_->Write(kAnswer).value(), kAnswer.size());  // a cable pulled out: nobody notices
  Client qemu = ConnectUnix();
  Pass();
  ASSERT_TRUE(port_->connected());
  EXPECT_EQ(qemu.Receive(1), Bytes{});  // what was written before it came is not delivered
}

TEST_F(ListeningSerialPortTest, ASecondClientIsRefusedWhileTheFirstLives) {
  Listen("unix:" + path_);
  Client first = ConnectUnix();
  Pass();
  Client second = ConnectUnix();
  ASSERT_TRUE(second.ok());
  Pass();
  EXPECT_TRUE(second.ClosedByPeer());
  EXPECT_EQ(port_->counters().refused, 1u);
  EXPECT_EQ(port_->counters().connections, 1u);
  first.Send(kRequest);  // the first one keeps the line
  EXPECT_EQ(ReadBytes(kRequest.size()), kRequest);
}

TEST_F(ListeningSerialPortTest, ANewClientReplacesADeadOne) {
  Listen("unix:" + path_);
  Client first = ConnectUnix();
  Pass();
  first.Close();  // QEMU exits; nothing has read the line since
  Client second = ConnectUnix();
  Pass();
  EXPECT_TRUE(port_->connected());
  EXPECT_EQ(port_->counters().connections, 2u);
  EXPECT_EQ(port_->counters().replaced, 1u);
  EXPECT_EQ(port_->counters().disconnects, 1u);
  EXPECT_EQ(port_->counters().refused, 0u);
  second.Send(kRequest);
  EXPECT_EQ(ReadBytes(kRequest.size()), kRequest);
  ASSERT_EQ(port_->Write(kAnswer).value(), kAnswer.size());
  EXPECT_EQ(second.Receive(kAnswer.size()), kAnswer);
}

TEST_F(ListeningSerialPortTest, AClientThatLeavesIsDroppedByTheReadThatSeesTheEnd) {
  Listen("unix:" + path_);
  Client qemu = ConnectUnix();
  Pass();
  qemu.Send(kRequest);
  qemu.Close();
  EXPECT_EQ(ReadBytes(kRequest.size()), kRequest);  // what it sent before it left is still read
  std::uint8_t buffer[8];
  EXPECT_EQ(port_->Read(buffer).status(), base::Unavailable());
  EXPECT_FALSE(port_->connected());
  EXPECT_EQ(port_->counters().disconnects, 1u);
  EXPECT_EQ(port_->Write(kAnswer).value(), kAnswer.size());
}

TEST_F(ListeningSerialPortTest, TcpOnAPortTheKernelChooses) {
  Listen("tcp:127.0.0.1:0");
  const std::string& endpoint = port_->endpoint();
  ASSERT_EQ(endpoint.rfind("tcp:127.0.0.1:", 0), 0u) << endpoint;
  const int port = std::stoi(endpoint.substr(std::string("tcp:127.0.0.1:").size()));
  ASSERT_GT(port, 0);
  const int fd = socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(static_cast<std::uint16_t>(port));
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  ASSERT_EQ(connect(fd, reinterpret_cast<const sockaddr*>(&address), sizeof address), 0);
  Client qemu(fd);
  Pass();
  ASSERT_TRUE(port_->connected());
  qemu.Send(kRequest);
  EXPECT_EQ(ReadBytes(kRequest.size()), kRequest);
  ASSERT_EQ(port_->Write(kAnswer).value(), kAnswer.size());
  EXPECT_EQ(qemu.Receive(kAnswer.size()), kAnswer);
}

TEST_F(ListeningSerialPortTest, EndpointsThatDoNotParse) {
  const std::string too_long = "unix:" + std::string(sizeof(sockaddr_un::sun_path), 'x');
  for (const std::string& endpoint :
       {std::string("serial.sock"), std::string("unix:"), std::string("tcp:127.0.0.1"), std::string("tcp::5000"),
        std::string("tcp:127.0.0.1:"), std::string("tcp:127.0.0.1:65536"), std::string("tcp:127.0.0.1:x"),
        std::string("tcp:example.org:5000"), std::string("tcp:[::1:5000"), too_long}) {
    std::string error;
    EXPECT_FALSE(ListeningSerialPort::CheckEndpoint(endpoint, &error)) << endpoint;
    auto port = ListeningSerialPort::Listen(endpoint, &error);
    EXPECT_EQ(port.status(), base::InvalidArgument()) << endpoint;
  }
  std::string error;
  EXPECT_FALSE(ListeningSerialPort::CheckEndpoint("tcp:localhost", &error));
  EXPECT_EQ(error, "expected unix:PATH or tcp:HOST:PORT, HOST a numeric address or localhost");
  EXPECT_FALSE(ListeningSerialPort::CheckEndpoint(too_long, &error));
  EXPECT_EQ(error, "the path must be 1 to 107 bytes");
  for (const char* endpoint : {"unix:/tmp/x.sock", "tcp:127.0.0.1:5000", "tcp:localhost:0", "tcp:[::1]:5000"}) {
    EXPECT_TRUE(ListeningSerialPort::CheckEndpoint(endpoint, &error)) << endpoint;
  }
}

TEST_F(ListeningSerialPortTest, ItsSocketFileReplacesAStaleOneAndIsRemovedAtTheEnd) {
  Listen("unix:" + path_);
  port_.reset();  // as a killed process would, except that the file stays: make one
  EXPECT_FALSE(std::filesystem::exists(path_));
  const int stale = socket(AF_UNIX, SOCK_STREAM, 0);
  sockaddr_un address{};
  address.sun_family = AF_UNIX;
  std::strncpy(address.sun_path, path_.c_str(), sizeof address.sun_path - 1);
  ASSERT_EQ(bind(stale, reinterpret_cast<const sockaddr*>(&address), sizeof address), 0);
  close(stale);  // bound, never listening: nobody accepts there
  ASSERT_TRUE(std::filesystem::is_socket(path_));
  std::string error;
  auto port = ListeningSerialPort::Listen("unix:" + path_, &error);
  ASSERT_TRUE(port.ok()) << error;
}

TEST_F(ListeningSerialPortTest, NeitherALiveSocketNorAnotherFileIsTaken) {
  Listen("unix:" + path_);
  std::string error;
  auto second = ListeningSerialPort::Listen("unix:" + path_, &error);
  EXPECT_EQ(second.status(), base::Unavailable());
  EXPECT_EQ(error, "serial endpoint " + path_ + ": another process listens there");
  const std::string file = dir_ + "/notes.txt";
  std::ofstream(file) << "keep me\n";
  auto third = ListeningSerialPort::Listen("unix:" + file, &error);
  EXPECT_EQ(third.status(), base::Unavailable());
  EXPECT_EQ(error, "serial endpoint " + file + ": exists and is not a socket");
  std::ifstream kept(file);
  std::string line;
  std::getline(kept, line);
  EXPECT_EQ(line, "keep me");
}

TEST_F(ListeningSerialPortTest, ConfigureRecordsOnlyValidSettings) {
  Listen("unix:" + path_);
  EXPECT_TRUE(port_->Configure({9600, Parity::kNone, 2}).ok());
  EXPECT_EQ(port_->config().baud, 9600u);
  EXPECT_EQ(port_->Configure({0, Parity::kEven, 1}), base::InvalidArgument());
  EXPECT_EQ(port_->Configure({19200, Parity::kEven, 3}), base::InvalidArgument());
  EXPECT_EQ(port_->config().baud, 9600u);
}

}  // namespace
}  // namespace hal::host
