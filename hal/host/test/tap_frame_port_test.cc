// TapFramePort against real TAP interfaces. Each test forks a child that moves into a new, empty network
// namespace before creating any interface, so the machine's own namespace is never touched and every
// interface disappears with the child. The child runs ordinary gtest assertions (their messages reach
// the shared stdout) and reports the verdict through its exit status.
#include "tap_frame_port.h"

#include <arpa/inet.h>
#include <fcntl.h>
#include <linux/if_packet.h>
#include <linux/if_tun.h>
#include <net/if.h>
#include <poll.h>
#include <sched.h>
#include <sys/ioctl.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <functional>
#include <optional>
#include <utility>
#include <string>
#include <vector>

namespace hal::host {
namespace {

using Bytes = std::vector<std::uint8_t>;

constexpr int kChildSkipped = 77;
constexpr std::uint16_t kTestEtherType = 0x88B5;  // IEEE 802 local experimental
constexpr base::MacAddress kCardMac = {0x00, 0x00, 0xA0, 0x12, 0x34, 0x56};
constexpr int kWaitMs = 2000;

// --- Namespace plumbing (runs in the child only) ----------------------------------------------------

// Creates a persistent TAP (or TUN) interface in the current namespace; no process stays attached.
bool CreateInterface(const std::string& name, short kind) {
  const int fd = open("/dev/net/tun", O_RDWR | O_CLOEXEC);
  if (fd < 0) return false;
  ifreq ifr{};
  ifr.ifr_flags = static_cast<short>(kind | IFF_NO_PI);
  std::strncpy(ifr.ifr_name, name.c_str(), IFNAMSIZ - 1);
  const bool ok = ioctl(fd, TUNSETIFF, &ifr) == 0 && ioctl(fd, TUNSETPERSIST, 1) == 0;
  close(fd);
  return ok;
}

// Interface up, IPv6 off first so the kernel sends nothing of its own (router solicitations, MLD)
// that would mix with the test's frames.
bool BringUp(const std::string& name, int mtu = 1500) {
  std::ofstream("/proc/sys/net/ipv6/conf/" + name + "/disable_ipv6") << "1";
  const int sock = socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
  if (sock < 0) return false;
  ifreq ifr{};
  std::strncpy(ifr.ifr_name, name.c_str(), IFNAMSIZ - 1);
  ifr.ifr_mtu = mtu;
  bool ok = ioctl(sock, SIOCSIFMTU, &ifr) == 0 && ioctl(sock, SIOCGIFFLAGS, &ifr) == 0;
  ifr.ifr_flags = static_cast<short>(ifr.ifr_flags | IFF_UP);
  ok = ok && ioctl(sock, SIOCSIFFLAGS, &ifr) == 0;
  close(sock);
  return ok;
}

// The host's side of a TAP interface: an AF_PACKET socket bound to it, seeing only test frames.
class KernelSide {
 public:
  explicit KernelSide(const std::string& ifname) {
    fd_ = socket(AF_PACKET, SOCK_RAW | SOCK_CLOEXEC, htons(kTestEtherType));
    sockaddr_ll addr{};
    addr.sll_family = AF_PACKET;
    addr.sll_protocol = htons(kTestEtherType);
    addr.sll_ifindex = static_cast<int>(if_nametoindex(ifname.c_str()));
    if (fd_ >= 0 && bind(fd_, reinterpret_cast<const sockaddr*>(&addr), sizeof(addr)) != 0) {
      close(fd_);
      fd_ = -1;
    }
  }
  ~KernelSide() {
    if (fd_ >= 0) close(fd_);
  }
  bool ok() const { return fd_ >= 0; }

  // The host transmits `frame` out of the interface, i.e. towards the card.
  bool Send(const Bytes& frame) {
    return send(fd_, frame.data(), frame.size(), 0) == static_cast<ssize_t>(frame.size());
  }
  // The next frame the host received from the card, if one comes within `wait_ms`.
  std::optional<Bytes> Receive(int wait_ms = kWaitMs) {
    pollfd pfd{fd_, POLLIN, 0};
    if (poll(&pfd, 1, wait_ms) != 1) return std::nullopt;
    Bytes frame(70000);
    sockaddr_ll from{};
    socklen_t from_len = sizeof(from);
    const ssize_t n = recvfrom(fd_, frame.data(), frame.size(), 0, reinterpret_cast<sockaddr*>(&from),
                               &from_len);
    if (n < 0 || from.sll_pkttype == PACKET_OUTGOING) return std::nullopt;
    frame.resize(static_cast<std::size_t>(n));
    return frame;
  }

 private:
  int fd_ = -1;
};

// A test frame: broadcast from a host MAC, the test EtherType, `size` bytes in all, payload from `seed`.
Bytes TestFrame(std::size_t size, std::uint8_t seed,
                base::MacAddress destination = {0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF}) {
  Bytes frame(size);
  std::copy(destination.begin(), destination.end(), frame.begin());
  const base::MacAddress source = {0x02, 0x00, 0x00, 0x00, 0x00, 0x01};
  std::copy(source.begin(), source.end(), frame.begin() + 6);
  frame[12] = kTestEtherType >> 8;
  frame[13] = kTestEtherType & 0xFF;
  for (std::size_t i = 14; i < size; ++i) frame[i] = static_cast<std::uint8_t>(seed + i);
  return frame;
}

// Sleeps in poll() on the port's own descriptors until one is readable (or kWaitMs passes).
bool WaitReadable(TapFramePort& tap) {
  PollSet set;
  Micros deadline = kNever;
  tap.PrepareWait(set, deadline);
  return poll(set.data(), set.size(), kWaitMs) > 0;
}

bool AnythingReadable(TapFramePort& tap) {
  PollSet set;
  Micros deadline = kNever;
  tap.PrepareWait(set, deadline);
  return poll(set.data(), set.size(), 0) > 0;
}

// Like the event loop: wait for the descriptors, then Receive().
base::Result<ReceivedFrame> ReceiveWaiting(TapFramePort& tap, std::span<std::uint8_t> buffer) {
  base::Result<ReceivedFrame> result = tap.Receive(buffer);
  for (int attempt = 0; attempt < 3 && result.status() == base::Unavailable(); ++attempt) {
    WaitReadable(tap);
    result = tap.Receive(buffer);
  }
  return result;
}

std::unique_ptr<TapFramePort> OpenTap(std::vector<std::string> names) {
  std::string error;
  base::Result<std::unique_ptr<TapFramePort>> tap = TapFramePort::Open(names, kCardMac, &error);
  EXPECT_TRUE(tap.ok()) << base::StatusName(tap.status()) << ": " << error;
  return std::move(tap.value());
}

// --- Running a scenario in a private network namespace ----------------------------------------------

// Runs `scenario` in a forked child inside a new network namespace, with `interfaces` TAP interfaces
// created and up. Returns in the parent; a failed or skipped child fails or skips the calling test.
void RunInPrivateNetns(const std::vector<std::string>& interfaces, const std::function<void()>& scenario,
                       std::string* skip_reason) {
  int report[2];
  ASSERT_EQ(pipe(report), 0);
  std::fflush(stdout);
  const pid_t pid = fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    close(report[0]);
    const auto skip = [&](const std::string& why) {
      (void)!write(report[1], why.data(), why.size());
      _exit(kChildSkipped);
    };
    if (unshare(CLONE_NEWNET) != 0) skip(std::string("unshare(CLONE_NEWNET): ") + std::strerror(errno));
    for (const std::string& name : interfaces) {
      if (!CreateInterface(name, IFF_TAP) || !BringUp(name)) {
        skip("cannot create TAP " + name + ": " + std::strerror(errno));
      }
    }
    scenario();
    std::fflush(stdout);
    _exit(::testing::Test::HasFailure() ? 1 : 0);
  }
  close(report[1]);
  std::string reason;
  char chunk[256];
  ssize_t n = 0;
  while ((n = read(report[0], chunk, sizeof(chunk))) > 0) reason.append(chunk, static_cast<std::size_t>(n));
  close(report[0]);
  int status = 0;
  ASSERT_EQ(waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(WIFEXITED(status)) << "child died by signal " << WTERMSIG(status);
  const int exit_code = WEXITSTATUS(status);
  if (exit_code == kChildSkipped) {
    *skip_reason = reason;
    return;
  }
  EXPECT_EQ(exit_code, 0) << "assertions failed in the namespace child (see above)";
}

class TapFramePortTest : public ::testing::Test {
 protected:
  void SetUp() override {
    if (geteuid() != 0) GTEST_SKIP() << "needs root (network namespaces, TAP interfaces)";
    if (access("/dev/net/tun", R_OK | W_OK) != 0) GTEST_SKIP() << "no /dev/net/tun";
  }

  void Run(const std::vector<std::string>& interfaces, const std::function<void()>& scenario) {
    std::string skip_reason;
    RunInPrivateNetns(interfaces, scenario, &skip_reason);
    if (!skip_reason.empty()) GTEST_SKIP() << skip_reason;
  }
};

// --- Tests --------------------------------------------------------------------------------------------

TEST_F(TapFramePortTest, ReceivesExactlyTheFrameTheHostSent) {
  Run({"ipet0"}, [] {
    std::unique_ptr<TapFramePort> tap = OpenTap({"ipet0"});
    ASSERT_NE(tap, nullptr);
    KernelSide host("ipet0");
    ASSERT_TRUE(host.ok());
    EXPECT_EQ(tap->PortCount(), 1u);
    EXPECT_EQ(tap->Mac(), kCardMac);
    EXPECT_EQ(tap->InterfaceName(PortId::kLeft), "ipet0");

    Bytes buffer(kMaxFrameBytes, 0);
    EXPECT_EQ(tap->Receive(buffer).status(), base::Unavailable());

    const Bytes frame = TestFrame(60, 1);
    ASSERT_TRUE(host.Send(frame));
    const base::Result<ReceivedFrame> got = ReceiveWaiting(*tap, buffer);
    ASSERT_TRUE(got.ok()) << base::StatusName(got.status());
    EXPECT_EQ(got->port, PortId::kLeft);
    ASSERT_EQ(got->length, 60u);
    EXPECT_EQ(Bytes(buffer.begin(), buffer.begin() + 60), frame);
    EXPECT_EQ(tap->Receive(buffer).status(), base::Unavailable());

    const PortCounters counters = tap->Counters(PortId::kLeft);
    EXPECT_EQ(counters.rx_frames, 1u);
    EXPECT_EQ(counters.rx_octets, 60u);
    EXPECT_EQ(counters.rx_errors, 0u);
    EXPECT_EQ(counters.tx_frames, 0u);
  });
}

TEST_F(TapFramePortTest, ReceivesTheSmallestAndLargestFrames) {
  Run({"ipet0"}, [] {
    std::unique_ptr<TapFramePort> tap = OpenTap({"ipet0"});
    ASSERT_NE(tap, nullptr);
    KernelSide host("ipet0");
    ASSERT_TRUE(host.ok());
    Bytes buffer(kMaxFrameBytes, 0);

    const Bytes smallest = TestFrame(kMinFrameBytes, 0);
    ASSERT_TRUE(host.Send(smallest));
    base::Result<ReceivedFrame> got = ReceiveWaiting(*tap, buffer);
    ASSERT_TRUE(got.ok()) << base::StatusName(got.status());
    EXPECT_EQ(Bytes(buffer.begin(), buffer.begin() + static_cast<std::ptrdiff_t>(got->length)), smallest);

    // 1518 bytes: a full 1500-byte payload behind an 802.1Q tag.
    Bytes largest = TestFrame(kMaxFrameBytes, 9);
    largest[12] = 0x81;
    largest[13] = 0x00;
    largest[14] = 0x00;
    largest[15] = 0x05;
    largest[16] = kTestEtherType >> 8;
    largest[17] = kTestEtherType & 0xFF;
    ASSERT_TRUE(host.Send(largest)) << std::strerror(errno);
    got = ReceiveWaiting(*tap, buffer);
    ASSERT_TRUE(got.ok()) << base::StatusName(got.status());
    ASSERT_EQ(got->length, kMaxFrameBytes);
    EXPECT_EQ(buffer, largest);
    EXPECT_EQ(tap->Counters(PortId::kLeft).rx_octets, kMinFrameBytes + kMaxFrameBytes);
  });
}

TEST_F(TapFramePortTest, DropsAndCountsFramesThatDoNotFit) {
  Run({"ipet0"}, [] {
    ASSERT_TRUE(BringUp("ipet0", 2000));  // lets the host send frames longer than a card accepts
    std::unique_ptr<TapFramePort> tap = OpenTap({"ipet0"});
    ASSERT_NE(tap, nullptr);
    KernelSide host("ipet0");
    ASSERT_TRUE(host.ok());

    // Longer than the caller's buffer: dropped, and the next call returns the next frame.
    ASSERT_TRUE(host.Send(TestFrame(200, 1)));
    const Bytes next = TestFrame(100, 2);
    ASSERT_TRUE(host.Send(next));
    Bytes small(100, 0);
    EXPECT_EQ(ReceiveWaiting(*tap, small).status(), base::OutOfRange());
    base::Result<ReceivedFrame> got = ReceiveWaiting(*tap, small);
    ASSERT_TRUE(got.ok()) << base::StatusName(got.status());
    EXPECT_EQ(small, next);

    // Longer than any valid Ethernet frame: dropped even when the buffer would hold it.
    ASSERT_TRUE(host.Send(TestFrame(kMaxFrameBytes + 1, 3)));
    Bytes big(4096, 0);
    EXPECT_EQ(ReceiveWaiting(*tap, big).status(), base::OutOfRange());
    EXPECT_EQ(tap->Receive(big).status(), base::Unavailable());

    const PortCounters counters = tap->Counters(PortId::kLeft);
    EXPECT_EQ(counters.rx_errors, 2u);
    EXPECT_EQ(counters.rx_frames, 1u);
    EXPECT_EQ(counters.rx_octets, 100u);
  });
}

TEST_F(TapFramePortTest, TransmitsExactlyTheFrameToTheHost) {
  Run({"ipet0"}, [] {
    std::unique_ptr<TapFramePort> tap = OpenTap({"ipet0"});
    ASSERT_NE(tap, nullptr);
    KernelSide host("ipet0");
    ASSERT_TRUE(host.ok());

    const Bytes broadcast = TestFrame(60, 4);
    ASSERT_EQ(tap->Transmit(PortId::kLeft, broadcast), base::OkStatus());
    EXPECT_EQ(host.Receive(), broadcast);

    const Bytes unicast = TestFrame(1514, 5, {0x02, 0x00, 0x00, 0x00, 0x00, 0x99});
    ASSERT_EQ(tap->Transmit(PortId::kLeft, unicast), base::OkStatus());
    EXPECT_EQ(host.Receive(), unicast);

    const PortCounters counters = tap->Counters(PortId::kLeft);
    EXPECT_EQ(counters.tx_frames, 2u);
    EXPECT_EQ(counters.tx_octets, 60u + 1514u);
    EXPECT_EQ(counters.tx_errors, 0u);
    EXPECT_EQ(counters.rx_frames, 0u);
  });
}

TEST_F(TapFramePortTest, RefusesToTransmitInvalidFramesOrToMissingPorts) {
  Run({"ipet0"}, [] {
    std::unique_ptr<TapFramePort> tap = OpenTap({"ipet0"});
    ASSERT_NE(tap, nullptr);
    EXPECT_EQ(tap->Transmit(PortId::kRight, TestFrame(60, 0)), base::NotFound());
    EXPECT_EQ(tap->Transmit(PortId::kLeft, Bytes(kMinFrameBytes - 1, 0)), base::InvalidArgument());
    EXPECT_EQ(tap->Transmit(PortId::kLeft, Bytes(kMaxFrameBytes + 1, 0)), base::InvalidArgument());
    EXPECT_EQ(tap->SetPlugged(PortId::kRight, false), base::NotFound());
    EXPECT_FALSE(tap->Link(PortId::kRight).up);
    EXPECT_EQ(tap->Counters(PortId::kLeft).tx_errors, 0u);
  });
}

TEST_F(TapFramePortTest, LinkFollowsTheSimulatedCable) {
  Run({"ipet0"}, [] {
    std::unique_ptr<TapFramePort> tap = OpenTap({"ipet0"});
    ASSERT_NE(tap, nullptr);
    KernelSide host("ipet0");
    ASSERT_TRUE(host.ok());
    Bytes buffer(kMaxFrameBytes, 0);

    LinkState link = tap->Link(PortId::kLeft);
    EXPECT_TRUE(tap->Plugged(PortId::kLeft));
    EXPECT_TRUE(link.up);
    EXPECT_EQ(link.speed, LinkSpeed::k100Mbps);
    EXPECT_TRUE(link.full_duplex);
    EXPECT_TRUE(link.auto_negotiated);

    ASSERT_EQ(tap->SetPlugged(PortId::kLeft, false), base::OkStatus());
    link = tap->Link(PortId::kLeft);
    EXPECT_FALSE(link.up);
    EXPECT_EQ(link.speed, LinkSpeed::kNone);
    EXPECT_FALSE(link.full_duplex);

    // Unplugged: nothing goes out, and what the host sends is thrown away.
    EXPECT_EQ(tap->Transmit(PortId::kLeft, TestFrame(60, 6)), base::FailedPrecondition());
    EXPECT_EQ(host.Receive(/*wait_ms=*/100), std::nullopt);
    ASSERT_TRUE(host.Send(TestFrame(60, 7)));
    ASSERT_TRUE(WaitReadable(*tap));
    EXPECT_EQ(tap->Receive(buffer).status(), base::Unavailable());
    EXPECT_FALSE(AnythingReadable(*tap));  // read and discarded, not left queued

    // Frames sent while unplugged and never read are gone after plugging back in, too.
    ASSERT_TRUE(host.Send(TestFrame(60, 8)));
    ASSERT_TRUE(WaitReadable(*tap));
    ASSERT_EQ(tap->SetPlugged(PortId::kLeft, true), base::OkStatus());
    EXPECT_TRUE(tap->Link(PortId::kLeft).up);
    EXPECT_EQ(tap->Receive(buffer).status(), base::Unavailable());

    // Plugged again: traffic flows both ways.
    const Bytes frame = TestFrame(64, 9);
    ASSERT_TRUE(host.Send(frame));
    const base::Result<ReceivedFrame> got = ReceiveWaiting(*tap, buffer);
    ASSERT_TRUE(got.ok()) << base::StatusName(got.status());
    EXPECT_EQ(Bytes(buffer.begin(), buffer.begin() + 64), frame);
    ASSERT_EQ(tap->Transmit(PortId::kLeft, frame), base::OkStatus());
    EXPECT_EQ(host.Receive(), frame);

    const PortCounters counters = tap->Counters(PortId::kLeft);
    EXPECT_EQ(counters.rx_frames, 1u);  // the discarded frames never arrived
    EXPECT_EQ(counters.rx_errors, 0u);
    EXPECT_EQ(counters.tx_frames, 1u);
    EXPECT_EQ(counters.tx_errors, 1u);  // the refused transmit
  });
}

TEST_F(TapFramePortTest, TwoPortsAreServedRoundRobin) {
  Run({"ipet0", "ipet1"}, [] {
    std::unique_ptr<TapFramePort> tap = OpenTap({"ipet0", "ipet1"});
    ASSERT_NE(tap, nullptr);
    EXPECT_EQ(tap->PortCount(), 2u);
    EXPECT_EQ(tap->InterfaceName(PortId::kRight), "ipet1");
    KernelSide left("ipet0");
    KernelSide right("ipet1");
    ASSERT_TRUE(left.ok() && right.ok());

    // The poll set holds both descriptors.
    PollSet set;
    Micros deadline = 1234;
    tap->PrepareWait(set, deadline);
    EXPECT_EQ(deadline, 1234u);
    ASSERT_EQ(set.size(), 2u);
    EXPECT_EQ(set.data()[0].events, POLLIN);
    EXPECT_EQ(set.data()[1].events, POLLIN);

    // Two frames queue on each port before the card reads any.
    const Bytes l1 = TestFrame(60, 0x10), l2 = TestFrame(61, 0x20);
    const Bytes r1 = TestFrame(62, 0x30), r2 = TestFrame(63, 0x40);
    ASSERT_TRUE(left.Send(l1) && left.Send(l2) && right.Send(r1) && right.Send(r2));
    for (int i = 0; i < 100; ++i) {
      set.Clear();
      tap->PrepareWait(set, deadline);
      poll(set.data(), set.size(), 20);
      if ((set.Revents(0) & POLLIN) != 0 && (set.Revents(1) & POLLIN) != 0) break;
    }

    Bytes buffer(kMaxFrameBytes, 0);
    const std::vector<std::pair<PortId, Bytes>> expected = {
        {PortId::kLeft, l1}, {PortId::kRight, r1}, {PortId::kLeft, l2}, {PortId::kRight, r2}};
    for (const auto& [port, frame] : expected) {
      const base::Result<ReceivedFrame> got = ReceiveWaiting(*tap, buffer);
      ASSERT_TRUE(got.ok()) << base::StatusName(got.status());
      EXPECT_EQ(got->port, port);
      EXPECT_EQ(Bytes(buffer.begin(), buffer.begin() + static_cast<std::ptrdiff_t>(got->length)), frame);
    }
    EXPECT_EQ(tap->Receive(buffer).status(), base::Unavailable());

    // Each port transmits on its own interface, and unplugging one leaves the other alone.
    ASSERT_EQ(tap->SetPlugged(PortId::kLeft, false), base::OkStatus());
    EXPECT_TRUE(tap->Link(PortId::kRight).up);
    const Bytes out = TestFrame(70, 0x50);
    ASSERT_EQ(tap->Transmit(PortId::kRight, out), base::OkStatus());
    EXPECT_EQ(right.Receive(), out);
    EXPECT_EQ(tap->Transmit(PortId::kLeft, out), base::FailedPrecondition());

    EXPECT_EQ(tap->Counters(PortId::kLeft).rx_frames, 2u);
    EXPECT_EQ(tap->Counters(PortId::kLeft).rx_octets, 121u);
    EXPECT_EQ(tap->Counters(PortId::kRight).rx_frames, 2u);
    EXPECT_EQ(tap->Counters(PortId::kRight).rx_octets, 125u);
    EXPECT_EQ(tap->Counters(PortId::kRight).tx_frames, 1u);
    EXPECT_EQ(tap->Counters(PortId::kLeft).tx_errors, 1u);
  });
}

TEST_F(TapFramePortTest, OpenSaysWhyItFailed) {
  Run({"ipet0"}, [] {
    ASSERT_TRUE(CreateInterface("ipetun0", IFF_TUN));
    std::string error;
    const auto open = [&error](std::vector<std::string> names) {
      error.clear();
      return TapFramePort::Open(names, kCardMac, &error).status();
    };

    EXPECT_EQ(open({}), base::InvalidArgument());
    EXPECT_EQ(open({"ipet0", "ipet0", "ipet0"}), base::InvalidArgument());
    EXPECT_EQ(open({"a-name-far-too-long"}), base::InvalidArgument());

    EXPECT_EQ(open({"ipet9"}), base::NotFound());
    EXPECT_NE(error.find("'ipet9': no such device"), std::string::npos) << error;
    EXPECT_EQ(if_nametoindex("ipet9"), 0u) << "Open must never create an interface";

    EXPECT_EQ(open({"lo"}), base::FailedPrecondition());
    EXPECT_NE(error.find("not a single-queue TAP"), std::string::npos) << error;
    EXPECT_EQ(open({"ipetun0"}), base::FailedPrecondition());
    EXPECT_NE(error.find("not a single-queue TAP"), std::string::npos) << error;

    // A failure on port R must not leave port L attached.
    EXPECT_EQ(open({"ipet0", "ipet9"}), base::NotFound());
    std::unique_ptr<TapFramePort> first = OpenTap({"ipet0"});
    ASSERT_NE(first, nullptr);
    EXPECT_EQ(open({"ipet0"}), base::FailedPrecondition());
    EXPECT_NE(error.find("already attached"), std::string::npos) << error;
    first.reset();

    // Without root, neither /dev/net/tun nor a root-owned TAP is available. Irreversible, so last.
    ASSERT_EQ(setresgid(65534, 65534, 65534), 0);
    ASSERT_EQ(setresuid(65534, 65534, 65534), 0);
    EXPECT_EQ(open({"ipet0"}), base::PermissionDenied());
    EXPECT_NE(error.find("permission denied"), std::string::npos) << error;
  });
}

}  // namespace
}  // namespace hal::host
