// EtherNet/IP class 1 (implicit I/O) originator for tools/bench/eip-io: opens class 1 connections with
// Forward_Open over TCP 44818, sends O->T datagrams on UDP 2222 at the RPI (absolute deadlines), receives
// the card's T->O datagrams with kernel receive timestamps (SO_TIMESTAMPNS) and prints the T->O interval
// statistics per connection and over all connections, plus the I/O packet rates both ways.
//
// usage: ipe_bench_eip_io_load --host ADDR [--port N] [--udp-port N] [--rpi-us N] [--seconds S]
//                              [--warmup S] [--multiplier M] [--conn KIND:OT:TO[:OTBYTES[:TOBYTES]]]...
//   --udp-port the local UDP port for O->T and T->O (default 2222: the card sends T->O there)
//   --multiplier the timeout multiplier M (default 2: the card's watchdog is RPI x 4 x 2^M)
//   KIND  eo (exclusive owner: OT an output assembly 20/21/100/101/102/105, O->T with the 32-bit
//         run/idle header, run), io (input only: OT 199, heartbeat), lo (listen only: OT 198, heartbeat)
//   OT/TO the consumed and produced connection points; configuration point 1 (size 0) always.
//   OTBYTES/TOBYTES the data sizes (default: the assembly's one size, 16 for 100/150; heartbeats 0).
//   Default: one connection eo:21:71. Every connection uses the same RPI both ways (API = RPI).
// O->T: 32-bit encapsulation sequence +1 per datagram, 16-bit CIP sequence count +1 per datagram (new
// data each time), run/idle header with run = 1 (exclusive owner), data all zero (stop, no reference:
// nothing moves the simulated drive). Heartbeats (input only / listen only): connection size 2, the
// sequence count only.
// T->O: point-to-point to this host, port 2222 (the socket is bound to 0.0.0.0:2222). Each datagram is
// checked (CPF layout, a known T->O connection ID, the connection's size) and timestamped by the kernel
// when it enters the host's IP stack (on TAP: inside the card's write(), i.e. the card's send instant);
// a user-space receive time (CLOCK_MONOTONIC after recvmsg) is kept as well for comparison.
// Measured window: from --warmup seconds after the O->T streams start (default 0.5) for --seconds.
// Statistics per connection (T->O intervals between consecutive received datagrams, kernel stamps):
// count, mean, p50, p99, max, min, jitter = |interval - API| (p99, max), missing = gaps in the CIP
// sequence count (datagrams the card sent that never arrived; a production slot the card skipped does
// not advance the count: it shows as an interval of 2 x API and in the card's cip.missed_productions),
// late = each arrival's offset from the grid t0 + k x API (t0 the window's first arrival) less the
// median offset, folded into [-0.1, 0.9) x API: how late the card's sends are against its own absolute
// grid (the interval statistics count a late send twice: a long interval, then a short one).
// Output: one "conn ..." line per connection, one "all ..." line (every interval of every connection),
// one "user ..." line (the same intervals from user-space receive times) and one "rates ..." line.
// Bounded: an alarm ends the process with status 3 at warmup + seconds + 15 s whatever happens.
#include <arpa/inet.h>
#include <netdb.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cerrno>
#include <cmath>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "bench_util.h"

namespace {

using bench::CpuSeconds;
using bench::Get16;
using bench::Get32;
using bench::Put16;
using bench::Put32;

constexpr std::size_t kHeaderSize = 24;
constexpr std::uint16_t kRegisterSession = 0x0065;
constexpr std::uint16_t kUnRegisterSession = 0x0066;
constexpr std::uint16_t kSendRRData = 0x006F;
constexpr std::uint8_t kForwardOpen = 0x54;
constexpr std::uint8_t kForwardClose = 0x4E;
constexpr std::uint16_t kVendor = 0x1234;  // the originator's vendor ID (any)
constexpr std::uint32_t kOriginatorSerial = 0x0E1B0001;

struct ConnSpec {
  std::string kind = "eo";
  std::uint32_t ot = 21;
  std::uint32_t to = 71;
  int ot_bytes = -1;  // data bytes; -1: the point's default
  int to_bytes = -1;
};

struct Options {
  std::string host;
  int port = 44818;
  int udp_port = 2222;
  std::uint32_t rpi_us = 2000;
  double seconds = 10;
  double warmup = 0.5;
  int multiplier = 2;
  std::vector<ConnSpec> conns;
};


std::int64_t MonotonicNs() {
  timespec t{};
  clock_gettime(CLOCK_MONOTONIC, &t);
  return static_cast<std::int64_t>(t.tv_sec) * 1000000000 + t.tv_nsec;
}

// The default data size of an assembly point (docs/drive-profile.md "Assemblies"); heartbeats 0.
int DefaultSize(std::uint32_t point) {
  switch (point) {
    case 20:
    case 21:
    case 70:
    case 71:
      return 4;
    case 100:
    case 150:
      return 16;
    case 101:
    case 151:
      return 8;
    case 102:
    case 152:
      return 12;
    case 105:
    case 155:
      return 18;
    default:
      return 0;
  }
}

// One connection: its Forward_Open parameters, its O->T stream and what was received.
struct Sample {
  std::int64_t kernel_ns;  // CLOCK_REALTIME (SO_TIMESTAMPNS); 0 when the kernel gave none
  std::int64_t user_ns;    // CLOCK_MONOTONIC after recvmsg
  std::uint32_t encapsulation_sequence;
  std::uint16_t sequence;
};

struct Connection {
  ConnSpec spec;
  bool heartbeat = false;
  std::uint16_t ot_size = 0;  // connection sizes (sequence count and header included)
  std::uint16_t to_size = 0;
  std::uint16_t serial = 0;
  std::uint32_t to_id = 0;  // chosen here (point-to-point T->O)
  std::uint32_t ot_id = 0;  // chosen by the card
  std::uint32_t ot_api = 0;
  std::uint32_t to_api = 0;
  std::atomic<bool> open{false};  // read by the receiving thread
  // O->T stream.
  std::uint32_t encapsulation_sequence = 0;
  std::uint16_t sequence = 0;
  std::int64_t next_send_ns = 0;
  std::uint64_t sent = 0;
  std::uint64_t late_sends = 0;  // sent more than half an RPI after its slot
  std::uint64_t skipped_sends = 0;
  // T->O, filled by the receiving thread only.
  std::vector<Sample> samples;
  std::uint64_t wrong_size = 0;
};

class Session {
 public:
  bool Connect(const Options& options, std::string& error) {
    addrinfo hints{};
    hints.ai_family = AF_INET;
    hints.ai_socktype = SOCK_STREAM;
    addrinfo* found = nullptr;
    const std::string port = std::to_string(options.port);
    if (const int rc = getaddrinfo(options.host.c_str(), port.c_str(), &hints, &found); rc != 0) {
      error = std::string("resolve: ") + gai_strerror(rc);
      return false;
    }
    card_ = *reinterpret_cast<sockaddr_in*>(found->ai_addr);
    fd_ = socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
    timeval timeout{3, 0};
    setsockopt(fd_, SOL_SOCKET, SO_SNDTIMEO, &timeout, sizeof timeout);
    setsockopt(fd_, SOL_SOCKET, SO_RCVTIMEO, &timeout, sizeof timeout);
    const int rc = connect(fd_, found->ai_addr, found->ai_addrlen);
    freeaddrinfo(found);
    if (rc != 0) {
      error = std::string("connect: ") + std::strerror(errno);
      return false;
    }
    const int one = 1;
    setsockopt(fd_, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
    std::uint8_t m[28];
    Header(m, kRegisterSession, 4);
    Put16(m + 24, 1);
    Put16(m + 26, 0);
    std::vector<std::uint8_t> reply;
    if (!Exchange(m, sizeof m, reply, error)) return false;
    if (Get16(reply.data()) != kRegisterSession || Get32(reply.data() + 8) != 0 || Get32(reply.data() + 4) == 0) {
      error = "RegisterSession refused";
      return false;
    }
    handle_ = Get32(reply.data() + 4);
    return true;
  }

  // SendRRData carrying a message router request to the Connection Manager (20 06 24 01); the reply's
  // message router reply (service, reserved, general status, additional size, ...) goes to `reply`.
  bool ConnectionManagerRequest(std::uint8_t service, const std::vector<std::uint8_t>& data,
                                std::vector<std::uint8_t>& reply, std::string& error) {
    std::vector<std::uint8_t> mr = {service, 0x02, 0x20, 0x06, 0x24, 0x01};
    mr.insert(mr.end(), data.begin(), data.end());
    std::vector<std::uint8_t> m(kHeaderSize + 16 + mr.size());
    Header(m.data(), kSendRRData, static_cast<std::uint16_t>(16 + mr.size()));
    std::uint8_t* d = m.data() + kHeaderSize;
    Put32(d, 0);
    Put16(d + 4, 0);
    Put16(d + 6, 2);
    Put16(d + 8, 0x0000);
    Put16(d + 10, 0);
    Put16(d + 12, 0x00B2);
    Put16(d + 14, static_cast<std::uint16_t>(mr.size()));
    std::memcpy(d + 16, mr.data(), mr.size());
    std::vector<std::uint8_t> whole;
    if (!Exchange(m.data(), m.size(), whole, error)) return false;
    if (Get16(whole.data()) != kSendRRData || Get32(whole.data() + 8) != 0) {
      error = "SendRRData refused (encapsulation status " + std::to_string(Get32(whole.data() + 8)) + ")";
      return false;
    }
    // Items: find the unconnected data item (0xB2).
    const std::uint8_t* p = whole.data() + kHeaderSize;
    const std::size_t size = whole.size() - kHeaderSize;
    if (size < 8) {
      error = "short SendRRData reply";
      return false;
    }
    const std::uint16_t count = Get16(p + 6);
    std::size_t at = 8;
    for (std::uint16_t i = 0; i < count && at + 4 <= size; ++i) {
      const std::uint16_t type = Get16(p + at);
      const std::uint16_t length = Get16(p + at + 2);
      if (at + 4 + length > size) break;
      if (type == 0x00B2) {
        reply.assign(p + at + 4, p + at + 4 + length);
        return true;
      }
      at += 4 + length;
    }
    error = "no unconnected data item in the reply";
    return false;
  }

  void Close() {
    if (fd_ < 0) return;
    std::uint8_t m[24];
    Header(m, kUnRegisterSession, 0);
    static_cast<void>(send(fd_, m, sizeof m, MSG_NOSIGNAL));
    close(fd_);
    fd_ = -1;
  }

  sockaddr_in card() const { return card_; }

 private:
  void Header(std::uint8_t* p, std::uint16_t command, std::uint16_t length) {
    Put16(p, command);
    Put16(p + 2, length);
    Put32(p + 4, handle_);
    Put32(p + 8, 0);
    ++context_;
    Put32(p + 12, static_cast<std::uint32_t>(context_));
    Put32(p + 16, static_cast<std::uint32_t>(context_ >> 32));
    Put32(p + 20, 0);
  }

  bool Exchange(const std::uint8_t* m, std::size_t size, std::vector<std::uint8_t>& reply, std::string& error) {
    std::size_t done = 0;
    while (done < size) {
      const ssize_t n = send(fd_, m + done, size - done, MSG_NOSIGNAL);
      if (n <= 0) {
        error = std::string("send: ") + std::strerror(errno);
        return false;
      }
      done += static_cast<std::size_t>(n);
    }
    reply.assign(kHeaderSize, 0);
    if (!ReadExactly(reply.data(), kHeaderSize, error)) return false;
    const std::size_t length = Get16(reply.data() + 2);
    reply.resize(kHeaderSize + length);
    return ReadExactly(reply.data() + kHeaderSize, length, error);
  }

  bool ReadExactly(std::uint8_t* p, std::size_t size, std::string& error) {
    std::size_t done = 0;
    while (done < size) {
      const ssize_t n = recv(fd_, p + done, size - done, 0);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) {
        error = n == 0 ? "connection closed by the card" : std::string("recv: ") + std::strerror(errno);
        return false;
      }
      done += static_cast<std::size_t>(n);
    }
    return true;
  }

  int fd_ = -1;
  std::uint32_t handle_ = 0;
  std::uint64_t context_ = 0;
  sockaddr_in card_{};
};

// 8-bit logical segments: class 0x04, instance 1 (configuration), connection points OT and TO (8- or
// 16-bit connection point segments).
std::vector<std::uint8_t> ConnectionPath(const ConnSpec& spec) {
  std::vector<std::uint8_t> path = {0x20, 0x04, 0x24, 0x01};
  for (const std::uint32_t point : {spec.ot, spec.to}) {
    if (point < 256) {
      path.push_back(0x2C);
      path.push_back(static_cast<std::uint8_t>(point));
    } else {
      path.push_back(0x2D);
      path.push_back(0x00);
      path.push_back(static_cast<std::uint8_t>(point));
      path.push_back(static_cast<std::uint8_t>(point >> 8));
    }
  }
  return path;
}

std::vector<std::uint8_t> ForwardOpenData(const Connection& c, std::uint32_t rpi_us, int multiplier) {
  std::vector<std::uint8_t> d(36);
  d[0] = 0x0A;            // priority/time tick
  d[1] = 0x0E;            // timeout ticks
  Put32(&d[2], 0);        // O->T ID: the card chooses
  Put32(&d[6], c.to_id);  // T->O ID: ours (point-to-point)
  Put16(&d[10], c.serial);
  Put16(&d[12], kVendor);
  Put32(&d[14], kOriginatorSerial);
  d[18] = static_cast<std::uint8_t>(multiplier);
  Put32(&d[22], rpi_us);
  // Point-to-point (bits 14-13 = 2), scheduled priority (bits 11-10 = 2), fixed size.
  Put16(&d[26], static_cast<std::uint16_t>(0x4000 | 0x0800 | c.ot_size));
  Put32(&d[28], rpi_us);
  Put16(&d[32], static_cast<std::uint16_t>(0x4000 | 0x0800 | c.to_size));
  d[34] = 0x01;  // class 1, cyclic, client
  const std::vector<std::uint8_t> path = ConnectionPath(c.spec);
  d[35] = static_cast<std::uint8_t>(path.size() / 2);
  d.insert(d.end(), path.begin(), path.end());
  return d;
}

std::vector<std::uint8_t> ForwardCloseData(const Connection& c) {
  std::vector<std::uint8_t> d(12);
  d[0] = 0x0A;
  d[1] = 0x0E;
  Put16(&d[2], c.serial);
  Put16(&d[4], kVendor);
  Put32(&d[6], kOriginatorSerial);
  const std::vector<std::uint8_t> path = ConnectionPath(c.spec);
  d[10] = static_cast<std::uint8_t>(path.size() / 2);
  d[11] = 0;
  d.insert(d.end(), path.begin(), path.end());
  return d;
}

std::string Hex16(unsigned v) {
  char text[16];
  std::snprintf(text, sizeof text, "0x%04X", v);
  return text;
}

// "general 0x01 extended 0x0127 ..." of a message router error reply.
std::string DescribeError(const std::vector<std::uint8_t>& r) {
  if (r.size() < 4) return "short reply";
  std::string text = "general " + Hex16(r[2]);
  const std::size_t words = r[3];
  for (std::size_t i = 0; i < words && 4 + 2 * i + 1 < r.size(); ++i) text += " " + Hex16(Get16(&r[4 + 2 * i]));
  return text;
}

std::atomic<bool> g_stop{false};

// Receives T->O datagrams until g_stop; every datagram is parsed and stored with its timestamps.
void Receive(int fd, std::vector<Connection>& conns, std::uint64_t& unknown, std::uint64_t& malformed,
             std::uint64_t& no_kernel_stamp) {
  std::array<std::uint8_t, 1024> buffer{};
  std::array<char, 256> control{};
  while (!g_stop.load(std::memory_order_relaxed)) {
    iovec iov{buffer.data(), buffer.size()};
    msghdr msg{};
    msg.msg_iov = &iov;
    msg.msg_iovlen = 1;
    msg.msg_control = control.data();
    msg.msg_controllen = control.size();
    const ssize_t n = recvmsg(fd, &msg, 0);
    const std::int64_t user_ns = MonotonicNs();
    if (n < 0) continue;  // timeout (SO_RCVTIMEO) or EINTR: look at g_stop
    std::int64_t kernel_ns = 0;
    for (cmsghdr* c = CMSG_FIRSTHDR(&msg); c != nullptr; c = CMSG_NXTHDR(&msg, c)) {
      if (c->cmsg_level == SOL_SOCKET && c->cmsg_type == SCM_TIMESTAMPNS) {
        timespec t{};
        std::memcpy(&t, CMSG_DATA(c), sizeof t);
        kernel_ns = static_cast<std::int64_t>(t.tv_sec) * 1000000000 + t.tv_nsec;
      }
    }
    if (kernel_ns == 0) ++no_kernel_stamp;
    const std::uint8_t* p = buffer.data();
    const std::size_t size = static_cast<std::size_t>(n);
    // item count 2, 0x8002 length 8 (ID, encapsulation sequence), 0x00B1 length L (sequence count, data)
    if (size < 2 + 12 + 4 + 2 || Get16(p) != 2 || Get16(p + 2) != 0x8002 || Get16(p + 4) != 8 ||
        Get16(p + 14) != 0x00B1 || Get16(p + 16) != size - 18) {
      ++malformed;
      continue;
    }
    const std::uint32_t id = Get32(p + 6);
    Connection* conn = nullptr;
    for (Connection& c : conns) {
      if (c.open && c.to_id == id) conn = &c;
    }
    if (conn == nullptr) {
      ++unknown;
      continue;
    }
    if (size - 18 != conn->to_size) {
      ++conn->wrong_size;
      continue;
    }
    conn->samples.push_back({kernel_ns, user_ns, Get32(p + 10), Get16(p + 18)});
  }
}

void SendOtoT(int fd, const sockaddr_in& to, Connection& c) {
  std::array<std::uint8_t, 64 + 2 + 4 + 32> d{};
  ++c.encapsulation_sequence;
  ++c.sequence;
  Put16(&d[0], 2);
  Put16(&d[2], 0x8002);
  Put16(&d[4], 8);
  Put32(&d[6], c.ot_id);
  Put32(&d[10], c.encapsulation_sequence);
  Put16(&d[14], 0x00B1);
  Put16(&d[16], c.ot_size);
  Put16(&d[18], c.sequence);
  if (!c.heartbeat) Put32(&d[20], 1);  // run; the data stays zero
  const std::size_t size = 18 + c.ot_size;
  if (sendto(fd, d.data(), size, 0, reinterpret_cast<const sockaddr*>(&to), sizeof to) == static_cast<ssize_t>(size)) {
    ++c.sent;
  }
}

struct Stats {
  std::size_t count = 0;
  double mean = 0, p50 = 0, p99 = 0, max = 0, min = 0, jitter_p99 = 0, jitter_max = 0;
};

double Percentile(const std::vector<double>& sorted, double p) {
  if (sorted.empty()) return 0;
  const std::size_t index =
      std::min(sorted.size() - 1, static_cast<std::size_t>(p * static_cast<double>(sorted.size() - 1) + 0.5));
  return sorted[index];
}

// intervals_us: µs, any order; api_us: the nominal period (for the jitter).
Stats Summarize(std::vector<double> intervals_us, std::vector<double> jitter_us) {
  Stats s;
  s.count = intervals_us.size();
  if (intervals_us.empty()) return s;
  std::sort(intervals_us.begin(), intervals_us.end());
  std::sort(jitter_us.begin(), jitter_us.end());
  double sum = 0;
  for (double v : intervals_us) sum += v;
  s.mean = sum / static_cast<double>(intervals_us.size());
  s.p50 = Percentile(intervals_us, 0.50);
  s.p99 = Percentile(intervals_us, 0.99);
  s.max = intervals_us.back();
  s.min = intervals_us.front();
  s.jitter_p99 = Percentile(jitter_us, 0.99);
  s.jitter_max = jitter_us.back();
  return s;
}

int Usage() {
  std::fprintf(stderr,
               "usage: ipe_bench_eip_io_load --host ADDR [--port N] [--udp-port N] [--rpi-us N] [--seconds S]\n"
               "                             [--warmup S] [--multiplier M] [--conn KIND:OT:TO[:OTBYTES[:TOBYTES]]]...\n"
               "  KIND eo (exclusive owner), io (input only, OT 199), lo (listen only, OT 198)\n");
  return 2;
}

bool ParseConn(const std::string& text, ConnSpec& spec) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  for (;;) {
    const std::size_t colon = text.find(':', start);
    parts.push_back(text.substr(start, colon == std::string::npos ? std::string::npos : colon - start));
    if (colon == std::string::npos) break;
    start = colon + 1;
  }
  if (parts.size() < 3 || parts.size() > 5) return false;
  if (parts[0] != "eo" && parts[0] != "io" && parts[0] != "lo") return false;
  spec.kind = parts[0];
  spec.ot = static_cast<std::uint32_t>(std::strtoul(parts[1].c_str(), nullptr, 0));
  spec.to = static_cast<std::uint32_t>(std::strtoul(parts[2].c_str(), nullptr, 0));
  if (parts.size() > 3) spec.ot_bytes = std::atoi(parts[3].c_str());
  if (parts.size() > 4) spec.to_bytes = std::atoi(parts[4].c_str());
  return spec.ot != 0 && spec.to != 0;
}

}  // namespace

int main(int argc, char** argv) {
  Options options;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (i + 1 >= argc) return Usage();
    const std::string value = argv[++i];
    if (arg == "--host")
      options.host = value;
    else if (arg == "--port")
      options.port = std::atoi(value.c_str());
    else if (arg == "--udp-port")
      options.udp_port = std::atoi(value.c_str());
    else if (arg == "--rpi-us")
      options.rpi_us = static_cast<std::uint32_t>(std::strtoul(value.c_str(), nullptr, 0));
    else if (arg == "--seconds")
      options.seconds = std::atof(value.c_str());
    else if (arg == "--warmup")
      options.warmup = std::atof(value.c_str());
    else if (arg == "--multiplier")
      options.multiplier = std::atoi(value.c_str());
    else if (arg == "--conn") {
      ConnSpec spec;
      if (!ParseConn(value, spec)) return Usage();
      options.conns.push_back(spec);
    } else {
      return Usage();
    }
  }
  if (options.conns.empty()) options.conns.push_back(ConnSpec{});
  if (options.host.empty() || options.seconds <= 0 || options.seconds > 60 || options.warmup < 0 ||
      options.warmup > 10 || options.rpi_us < 100 || options.rpi_us > 10000000 || options.multiplier < 0 ||
      options.multiplier > 7 || options.conns.size() > 16) {
    return Usage();
  }
  std::signal(SIGALRM, [](int) { _exit(3); });
  alarm(static_cast<unsigned>(options.warmup + options.seconds) + 15);
  // Wake-ups of the O->T sender as close to their slots as the kernel gives them.
  static_cast<void>(prctl(PR_SET_TIMERSLACK, 1UL, 0UL, 0UL, 0UL));

  std::vector<Connection> conns(options.conns.size());
  const std::size_t expected_samples =
      static_cast<std::size_t>((options.warmup + options.seconds + 5) * 1e6 / options.rpi_us) + 16;
  for (std::size_t i = 0; i < conns.size(); ++i) {
    Connection& c = conns[i];
    c.spec = options.conns[i];
    c.heartbeat = c.spec.kind != "eo";
    const int ot_bytes = c.heartbeat ? 0 : (c.spec.ot_bytes >= 0 ? c.spec.ot_bytes : DefaultSize(c.spec.ot));
    const int to_bytes = c.spec.to_bytes >= 0 ? c.spec.to_bytes : DefaultSize(c.spec.to);
    c.ot_size = static_cast<std::uint16_t>(c.heartbeat ? 2 : 2 + 4 + ot_bytes);
    c.to_size = static_cast<std::uint16_t>(2 + to_bytes);
    c.serial = static_cast<std::uint16_t>(0x4000 + (getpid() & 0xFFF) * 16 + i);
    c.to_id = 0x7E000000u + (static_cast<std::uint32_t>(getpid() & 0xFFFF) << 4) + static_cast<std::uint32_t>(i);
    c.samples.reserve(expected_samples);
  }

  // The UDP socket: T->O arrives on port 2222 (point-to-point to the Forward_Open's peer); O->T leaves
  // from it. Bound before any Forward_Open: the first production is due when the connection opens.
  const int udp = socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
  sockaddr_in local{};
  local.sin_family = AF_INET;
  local.sin_port = htons(static_cast<std::uint16_t>(options.udp_port));
  local.sin_addr.s_addr = htonl(INADDR_ANY);
  const int one = 1;
  setsockopt(udp, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
  if (bind(udp, reinterpret_cast<const sockaddr*>(&local), sizeof local) != 0) {
    std::fprintf(stderr, "eip-io: bind UDP %d: %s\n", options.udp_port, std::strerror(errno));
    return 1;
  }
  setsockopt(udp, SOL_SOCKET, SO_TIMESTAMPNS, &one, sizeof one);
  const int rcvbuf = 4 << 20;
  setsockopt(udp, SOL_SOCKET, SO_RCVBUF, &rcvbuf, sizeof rcvbuf);
  timeval rcv_timeout{0, 100000};
  setsockopt(udp, SOL_SOCKET, SO_RCVTIMEO, &rcv_timeout, sizeof rcv_timeout);

  std::uint64_t unknown = 0, malformed = 0, no_kernel_stamp = 0;
  std::thread receiver(Receive, udp, std::ref(conns), std::ref(unknown), std::ref(malformed),
                       std::ref(no_kernel_stamp));

  Session session;
  std::string error;
  int status = 0;
  if (!session.Connect(options, error)) {
    std::fprintf(stderr, "eip-io: session: %s\n", error.c_str());
    g_stop = true;
    receiver.join();
    return 1;
  }
  sockaddr_in card_io = session.card();
  card_io.sin_port = htons(static_cast<std::uint16_t>(options.udp_port));

  // Open every connection. The receiving thread looks at `open` (atomic) and `to_id` (set before the
  // thread started): a connection's T->O is taken from the moment its Forward_Open is sent, since the
  // card may produce before its reply is read here.
  for (Connection& c : conns) {
    std::vector<std::uint8_t> reply;
    c.open = true;  // accept its T->O from now on (the ID is ours)
    if (!session.ConnectionManagerRequest(kForwardOpen, ForwardOpenData(c, options.rpi_us, options.multiplier), reply,
                                          error)) {
      std::fprintf(stderr, "eip-io: Forward_Open %s:%u:%u: %s\n", c.spec.kind.c_str(), c.spec.ot, c.spec.to,
                   error.c_str());
      c.open = false;
      status = 1;
      break;
    }
    if (reply.size() < 4 || reply[0] != (kForwardOpen | 0x80) || reply[2] != 0 || reply.size() < 4 + 26) {
      std::fprintf(stderr, "eip-io: Forward_Open %s:%u:%u refused: %s\n", c.spec.kind.c_str(), c.spec.ot, c.spec.to,
                   DescribeError(reply).c_str());
      c.open = false;
      status = 1;
      break;
    }
    const std::uint8_t* r = reply.data() + 4;
    c.ot_id = Get32(r);
    if (Get32(r + 4) != c.to_id) {
      std::fprintf(stderr, "eip-io: Forward_Open reply names T->O ID 0x%08X, asked 0x%08X\n", Get32(r + 4), c.to_id);
    }
    c.ot_api = Get32(r + 16);
    c.to_api = Get32(r + 20);
  }

  const std::int64_t start_ns = MonotonicNs();
  const std::int64_t window_start_ns = start_ns + static_cast<std::int64_t>(options.warmup * 1e9);
  const std::int64_t window_end_ns = window_start_ns + static_cast<std::int64_t>(options.seconds * 1e9);
  double cpu_window_start = -1;
  double cpu_window_end = -1;
  std::uint64_t sent_at_window_start = 0;
  std::uint64_t sent_in_window = 0;
  if (status == 0) {
    // O->T: each connection on its own grid start + k x RPI (absolute deadlines, no drift); a slot missed
    // by a whole RPI or more is skipped, not sent as a burst.
    const std::int64_t rpi_ns = static_cast<std::int64_t>(options.rpi_us) * 1000;
    for (std::size_t i = 0; i < conns.size(); ++i) {
      conns[i].next_send_ns =
          start_ns + static_cast<std::int64_t>(i) * rpi_ns / static_cast<std::int64_t>(conns.size());
    }
    bool in_window = false;
    for (;;) {
      std::int64_t next = window_end_ns;
      for (const Connection& c : conns) next = std::min(next, c.next_send_ns);
      if (next >= window_end_ns) break;
      timespec t{static_cast<time_t>(next / 1000000000), static_cast<long>(next % 1000000000)};
      while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &t, nullptr) == EINTR) {
      }
      const std::int64_t now = MonotonicNs();
      if (!in_window && now >= window_start_ns) {
        in_window = true;
        cpu_window_start = CpuSeconds();
        for (const Connection& c : conns) sent_at_window_start += c.sent;
      }
      for (Connection& c : conns) {
        if (c.next_send_ns > now) continue;
        if (now - c.next_send_ns > rpi_ns / 2) ++c.late_sends;
        SendOtoT(udp, card_io, c);
        c.next_send_ns += rpi_ns;
        if (c.next_send_ns <= now) {
          const std::int64_t skipped = (now - c.next_send_ns) / rpi_ns + 1;
          c.skipped_sends += static_cast<std::uint64_t>(skipped);
          c.next_send_ns += skipped * rpi_ns;
        }
      }
    }
    cpu_window_end = CpuSeconds();
    std::uint64_t sent_total = 0;
    for (const Connection& c : conns) sent_total += c.sent;
    sent_in_window = sent_total - sent_at_window_start;
  }

  // Close every open connection (Forward_Close), last opened first: a listen-only connection closes by
  // itself with the last connection producing its point (then its own Forward_Close would be 0x0107).
  // The T->O of the window is already in.
  for (auto it = conns.rbegin(); it != conns.rend(); ++it) {
    Connection& c = *it;
    if (c.ot_id == 0) continue;
    std::vector<std::uint8_t> reply;
    if (!session.ConnectionManagerRequest(kForwardClose, ForwardCloseData(c), reply, error) || reply.size() < 4 ||
        reply[2] != 0) {
      std::fprintf(stderr, "eip-io: Forward_Close %s:%u:%u failed: %s\n", c.spec.kind.c_str(), c.spec.ot, c.spec.to,
                   error.empty() ? DescribeError(reply).c_str() : error.c_str());
    }
  }
  usleep(20000);
  g_stop = true;
  receiver.join();
  session.Close();
  close(udp);
  if (status != 0) return status;

  // Statistics over the window (by user-space arrival time; the kernel stamps give the intervals).
  const double window_s = static_cast<double>(window_end_ns - window_start_ns) / 1e9;
  std::vector<double> all_intervals, all_jitter, all_user_intervals, all_user_jitter, all_late;
  std::uint64_t received_total = 0, missing_total = 0, late_sends = 0, skipped_sends = 0, wrong_size = 0;
  std::vector<std::string> lines;
  for (std::size_t i = 0; i < conns.size(); ++i) {
    const Connection& c = conns[i];
    const double api_us = c.to_api;
    std::vector<double> intervals, jitter, user_intervals, user_jitter, late;
    std::uint64_t missing = 0, received = 0, reordered = 0;
    const Sample* previous = nullptr;
    const Sample* first = nullptr;
    std::vector<double> offsets;
    for (const Sample& s : c.samples) {
      if (s.user_ns < window_start_ns || s.user_ns >= window_end_ns) continue;
      ++received;
      if (previous != nullptr) {
        const std::uint16_t step = static_cast<std::uint16_t>(s.sequence - previous->sequence);
        if (step == 0 || step >= 0x8000) {
          ++reordered;
          continue;
        }
        missing += step - 1u;
        const double interval = static_cast<double>(s.kernel_ns - previous->kernel_ns) / 1e3;
        const double user_interval = static_cast<double>(s.user_ns - previous->user_ns) / 1e3;
        intervals.push_back(interval);
        jitter.push_back(std::fabs(interval - api_us));
        user_intervals.push_back(user_interval);
        user_jitter.push_back(std::fabs(user_interval - api_us));
      } else {
        first = &s;
      }
      // Offset from the grid first + k x API, k the nearest slot (the card's grid is exact in µs, and its
      // clock, CLOCK_MONOTONIC, runs at the rate of the kernel stamps' CLOCK_REALTIME).
      const double since_first = static_cast<double>(s.kernel_ns - first->kernel_ns) / 1e3;
      offsets.push_back(since_first - std::round(since_first / api_us) * api_us);
      previous = &s;
    }
    double late_p99 = 0, late_max = 0;
    if (!offsets.empty()) {
      // Relative to the median offset (the card's usual send instant in its period), folded into
      // [-0.1, 0.9) x API: the card is never early by much, so a large offset is lateness.
      std::vector<double> sorted = offsets;
      std::sort(sorted.begin(), sorted.end());
      const double median = Percentile(sorted, 0.5);
      for (double& o : offsets) {
        double d = std::fmod(o - median + 0.1 * api_us, api_us);
        if (d < 0) d += api_us;
        o = d - 0.1 * api_us;
      }
      late = offsets;
      std::sort(late.begin(), late.end());
      late_p99 = Percentile(late, 0.99);
      late_max = late.back();
      all_late.insert(all_late.end(), late.begin(), late.end());
    }
    const Stats st = Summarize(intervals, jitter);
    char line[640];
    std::snprintf(line, sizeof line,
                  "conn=%zu kind=%s points=1/%u/%u sizes=%u/%u rpi_us=%u api_us=%u/%u received=%llu intervals=%zu "
                  "mean_us=%.1f p50_us=%.1f p99_us=%.1f max_us=%.1f min_us=%.1f jitter_p99_us=%.1f jitter_max_us=%.1f "
                  "missing=%llu reordered=%llu late_p99_us=%.1f late_max_us=%.1f o_to_t_sent=%llu o_to_t_late=%llu "
                  "o_to_t_skipped=%llu",
                  i + 1, c.spec.kind.c_str(), c.spec.ot, c.spec.to, c.ot_size, c.to_size, options.rpi_us, c.ot_api,
                  c.to_api, static_cast<unsigned long long>(received), st.count, st.mean, st.p50, st.p99, st.max,
                  st.min, st.jitter_p99, st.jitter_max, static_cast<unsigned long long>(missing),
                  static_cast<unsigned long long>(reordered), late_p99, late_max,
                  static_cast<unsigned long long>(c.sent), static_cast<unsigned long long>(c.late_sends),
                  static_cast<unsigned long long>(c.skipped_sends));
    lines.emplace_back(line);
    all_intervals.insert(all_intervals.end(), intervals.begin(), intervals.end());
    all_jitter.insert(all_jitter.end(), jitter.begin(), jitter.end());
    all_user_intervals.insert(all_user_intervals.end(), user_intervals.begin(), user_intervals.end());
    all_user_jitter.insert(all_user_jitter.end(), user_jitter.begin(), user_jitter.end());
    received_total += received;
    missing_total += missing;
    late_sends += c.late_sends;
    skipped_sends += c.skipped_sends;
    wrong_size += c.wrong_size;
  }
  for (const std::string& line : lines) std::printf("%s\n", line.c_str());
  const Stats all = Summarize(all_intervals, all_jitter);
  std::sort(all_late.begin(), all_late.end());
  std::printf(
      "all connections=%zu rpi_us=%u seconds=%.2f intervals=%zu mean_us=%.1f p50_us=%.1f p99_us=%.1f "
      "max_us=%.1f min_us=%.1f jitter_p99_us=%.1f jitter_max_us=%.1f missing=%llu late_p99_us=%.1f "
      "late_max_us=%.1f stamps=%s\n",
      conns.size(), options.rpi_us, window_s, all.count, all.mean, all.p50, all.p99, all.max, all.min, all.jitter_p99,
      all.jitter_max, static_cast<unsigned long long>(missing_total), Percentile(all_late, 0.99),
      all_late.empty() ? 0.0 : all_late.back(), no_kernel_stamp == 0 ? "kernel" : "kernel-incomplete");
  const Stats user = Summarize(all_user_intervals, all_user_jitter);
  std::printf(
      "user intervals=%zu p50_us=%.1f p99_us=%.1f max_us=%.1f min_us=%.1f jitter_p99_us=%.1f "
      "jitter_max_us=%.1f\n",
      user.count, user.p50, user.p99, user.max, user.min, user.jitter_p99, user.jitter_max);
  const double client_cpu = cpu_window_end - cpu_window_start;
  std::printf(
      "rates o_to_t_pps=%.0f t_to_o_pps=%.0f total_pps=%.0f o_to_t_late=%llu o_to_t_skipped=%llu "
      "unknown=%llu malformed=%llu wrong_size=%llu no_kernel_stamp=%llu client_cpu_pct=%.1f\n",
      static_cast<double>(sent_in_window) / window_s, static_cast<double>(received_total) / window_s,
      static_cast<double>(sent_in_window + received_total) / window_s, static_cast<unsigned long long>(late_sends),
      static_cast<unsigned long long>(skipped_sends), static_cast<unsigned long long>(unknown),
      static_cast<unsigned long long>(malformed), static_cast<unsigned long long>(wrong_size),
      static_cast<unsigned long long>(no_kernel_stamp), 100.0 * client_cpu / window_s);
  return all.count == 0 ? 1 : 0;
}
