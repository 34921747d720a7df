// EtherNet/IP explicit-messaging load generator for tools/bench/eip-explicit: N sessions, each on its own
// TCP connection, all served by one poll loop (one thread). Each session sends RegisterSession, then,
// once every session is registered, SendRRData Get_Attribute_Single requests back to back (closed loop:
// one request outstanding per session) for a fixed time; the run prints requests/s and the latency
// distribution (send of the request to the last byte of its reply).
//
// usage: ipe_bench_eip_explicit_load --host ADDR --port N [--sessions N] [--seconds S] [--mix]
//   default: Identity class 1 instance 1 attribute 1 (vendor ID; the reply data must be 79 01)
//   --mix:   Identity attributes 1, 2, 3, 4, 6, 7 in turn (each reply must equal the first reply to the
//            same attribute byte for byte; attribute 1 must read 79 01)
// Every reply is checked: command, length, session handle, status 0, sender context (the request's
// sequence number), options 0, the Common Packet Format layout (null address + unconnected data item),
// reply service 0x8E, general status 0, no additional status, and the data. A wrong reply counts as an
// error and the session goes on; a closed connection, an encapsulation error or a reply missing for 2 s
// ends that session (failed_sessions).
// Prints one line: "sessions=N requests=R seconds=S rps=X p50_us=A p99_us=B errors=E max_us=C
// failed_sessions=F client_cpu_us_per_request=U" (seconds: the measured window, from the first request
// to the last reply; client CPU: this process's user+system time in that window).
// Bounded: no request is sent after --seconds (at most 60); replies still due are awaited for at most
// 2 s; whatever happens, an alarm ends the process with status 3 at --seconds + 10 s.
#include <netdb.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <sys/resource.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <string>
#include <vector>

#include "bench_util.h"

namespace {

using bench::CpuSeconds;
using bench::Get16;
using bench::Get32;
using bench::Put16;
using bench::Put32;

using Clock = std::chrono::steady_clock;

constexpr std::size_t kHeaderSize = 24;
constexpr std::uint16_t kRegisterSession = 0x0065;
constexpr std::uint16_t kSendRRData = 0x006F;
constexpr std::size_t kMaxMessage = 24 + 600;
constexpr auto kReplyTimeout = std::chrono::seconds(2);
constexpr std::array<std::uint8_t, 6> kMixAttributes = {1, 2, 3, 4, 6, 7};

struct Options {
  std::string host = "127.0.0.1";
  int port = 44818;
  int sessions = 1;
  double seconds = 5;
  bool mix = false;
};


// The 24-byte encapsulation header; the sender context carries a 64-bit sequence number.
void PutHeader(std::uint8_t* p, std::uint16_t command, std::uint16_t length, std::uint32_t session,
               std::uint64_t context) {
  Put16(p, command);
  Put16(p + 2, length);
  Put32(p + 4, session);
  Put32(p + 8, 0);  // status
  Put32(p + 12, static_cast<std::uint32_t>(context));
  Put32(p + 16, static_cast<std::uint32_t>(context >> 32));
  Put32(p + 20, 0);  // options
}

// RegisterSession: protocol version 1, options 0.
std::size_t BuildRegisterSession(std::uint8_t* out) {
  PutHeader(out, kRegisterSession, 4, 0, 0);
  Put16(out + 24, 1);
  Put16(out + 26, 0);
  return 28;
}

// SendRRData: interface handle 0, timeout 0, 2 items: null address, unconnected data carrying
// Get_Attribute_Single (0x0E) with path 20 01 24 01 30 <attribute>.
std::size_t BuildGetAttribute(std::uint8_t* out, std::uint32_t session, std::uint64_t context,
                              std::uint8_t attribute) {
  std::uint8_t* d = out + kHeaderSize;
  Put32(d, 0);       // interface handle
  Put16(d + 4, 0);   // timeout
  Put16(d + 6, 2);   // item count
  Put16(d + 8, 0x0000);
  Put16(d + 10, 0);  // null address item
  Put16(d + 12, 0x00B2);
  Put16(d + 14, 8);  // unconnected data item
  const std::uint8_t request[8] = {0x0E, 0x03, 0x20, 0x01, 0x24, 0x01, 0x30, attribute};
  std::memcpy(d + 16, request, sizeof request);
  PutHeader(out, kSendRRData, 24, session, context);
  return kHeaderSize + 24;
}

struct Session {
  int fd = -1;
  std::uint32_t handle = 0;
  bool registered = false;
  bool failed = false;
  bool waiting = false;  // a request is outstanding
  bool replied = false;  // a SendRRData reply came in since the main loop last looked
  std::uint64_t sequence = 0;
  std::uint8_t attribute = 1;
  std::size_t attribute_index = 0;
  Clock::time_point sent;
  Clock::time_point replied_at;
  std::array<std::uint8_t, kMaxMessage> in{};
  std::size_t in_size = 0;
  std::array<std::uint8_t, 64> out{};
  std::size_t out_size = 0;
  std::string failure;
};

struct Totals {
  std::vector<std::uint32_t> latencies_us;
  std::uint64_t errors = 0;
  // The expected reply data per attribute (learnt from the first reply; attribute 1 is fixed).
  std::array<std::optional<std::vector<std::uint8_t>>, 256> expected;
};

int Connect(const Options& options, std::string& error) {
  addrinfo hints{};
  hints.ai_family = AF_INET;
  hints.ai_socktype = SOCK_STREAM;
  addrinfo* found = nullptr;
  const std::string port = std::to_string(options.port);
  if (const int rc = getaddrinfo(options.host.c_str(), port.c_str(), &hints, &found); rc != 0) {
    error = std::string("resolve: ") + gai_strerror(rc);
    return -1;
  }
  const int fd = socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  if (fd < 0) {
    error = std::string("socket: ") + std::strerror(errno);
    freeaddrinfo(found);
    return -1;
  }
  timeval timeout{2, 0};
  setsockopt(fd, SOL_SOCKET, SO_SNDTIMEO, &timeout, sizeof timeout);  // bounds connect()
  const int rc = connect(fd, found->ai_addr, found->ai_addrlen);
  freeaddrinfo(found);
  if (rc != 0) {
    error = std::string("connect: ") + std::strerror(errno);
    close(fd);
    return -1;
  }
  const int one = 1;
  setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
  return fd;
}

bool SendAll(Session& s) {
  std::size_t done = 0;
  while (done < s.out_size) {
    const ssize_t n = send(s.fd, s.out.data() + done, s.out_size - done, MSG_NOSIGNAL);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      s.failure = std::string("send: ") + std::strerror(errno);
      return false;
    }
    done += static_cast<std::size_t>(n);
  }
  return true;
}

void Fail(Session& s, const std::string& why) {
  if (s.failed) return;
  s.failed = true;
  s.waiting = false;
  if (s.failure.empty()) s.failure = why;
}

void SendRequest(Session& s, bool mix) {
  if (mix) {
    s.attribute = kMixAttributes[s.attribute_index];
    s.attribute_index = (s.attribute_index + 1) % kMixAttributes.size();
  }
  ++s.sequence;
  s.out_size = BuildGetAttribute(s.out.data(), s.handle, s.sequence, s.attribute);
  s.sent = Clock::now();
  s.waiting = true;
  if (!SendAll(s)) Fail(s, s.failure);
}

// Checks a complete SendRRData reply (header included); true when it is the expected one.
bool CheckReply(const Session& s, const std::uint8_t* m, std::size_t size, Totals& totals) {
  if (Get16(m) != kSendRRData || Get32(m + 4) != s.handle || Get32(m + 8) != 0 || Get32(m + 20) != 0) return false;
  if (Get32(m + 12) != static_cast<std::uint32_t>(s.sequence) ||
      Get32(m + 16) != static_cast<std::uint32_t>(s.sequence >> 32)) {
    return false;
  }
  const std::uint8_t* d = m + kHeaderSize;
  const std::size_t length = size - kHeaderSize;
  // interface handle, timeout, 2 items: null address (length 0), unconnected data.
  if (length < 16 + 4 || Get32(d) != 0 || Get16(d + 6) != 2 || Get16(d + 8) != 0 || Get16(d + 10) != 0 ||
      Get16(d + 12) != 0x00B2 || Get16(d + 14) != length - 16) {
    return false;
  }
  const std::uint8_t* r = d + 16;
  const std::size_t r_size = length - 16;
  if (r[0] != 0x8E || r[1] != 0 || r[2] != 0 || r[3] != 0) return false;
  std::vector<std::uint8_t> data(r + 4, r + r_size);
  auto& expected = totals.expected[s.attribute];
  if (!expected) {
    if (s.attribute == 1 && data != std::vector<std::uint8_t>{0x79, 0x01}) return false;
    if (data.empty()) return false;
    expected = std::move(data);
    return true;
  }
  return data == *expected;
}

std::string Hex(std::uint32_t value) {
  char text[16];
  std::snprintf(text, sizeof text, "0x%04X", value);
  return text;
}

// Reads what is there; on a complete message, handles it. Returns false when the session ended.
bool OnReadable(Session& s, bool measuring, Totals& totals) {
  const ssize_t n = recv(s.fd, s.in.data() + s.in_size, s.in.size() - s.in_size, 0);
  if (n < 0 && (errno == EINTR || errno == EAGAIN)) return true;
  if (n <= 0) {
    Fail(s, n == 0 ? "connection closed by the card" : std::string("recv: ") + std::strerror(errno));
    return false;
  }
  s.in_size += static_cast<std::size_t>(n);
  if (s.in_size < kHeaderSize) return true;
  const std::size_t size = kHeaderSize + Get16(s.in.data() + 2);
  if (size > s.in.size()) {
    Fail(s, "reply longer than any expected");
    return false;
  }
  if (s.in_size < size) return true;
  if (s.in_size > size || !s.waiting) {
    Fail(s, "bytes the card was not asked for");
    return false;
  }
  const Clock::time_point now = Clock::now();
  s.waiting = false;
  s.in_size = 0;
  const std::uint8_t* m = s.in.data();
  if (!s.registered) {
    if (Get16(m) != kRegisterSession || Get32(m + 8) != 0 || size != 28 || Get32(m + 4) == 0) {
      Fail(s, "RegisterSession refused (status " + Hex(Get32(m + 8)) + ")");
      return false;
    }
    s.handle = Get32(m + 4);
    s.registered = true;
    return true;
  }
  if (Get32(m + 8) != 0) {
    Fail(s, "encapsulation status " + Hex(Get32(m + 8)));
    return false;
  }
  s.replied = true;
  s.replied_at = now;
  if (!CheckReply(s, m, size, totals)) {
    ++totals.errors;
  } else if (measuring) {
    totals.latencies_us.push_back(static_cast<std::uint32_t>(
        std::chrono::duration_cast<std::chrono::microseconds>(now - s.sent).count()));
  }
  return true;
}

std::uint32_t Percentile(const std::vector<std::uint32_t>& sorted, double p) {
  if (sorted.empty()) return 0;
  const std::size_t index =
      std::min(sorted.size() - 1, static_cast<std::size_t>(p * static_cast<double>(sorted.size() - 1) + 0.5));
  return sorted[index];
}

int Usage() {
  std::fprintf(stderr,
               "usage: ipe_bench_eip_explicit_load --host ADDR --port N [--sessions N] [--seconds S] [--mix]\n");
  return 2;
}

// Waits for readable sessions until `deadline`; handles what arrives. With one session a blocking recv
// would do, but the same loop keeps the client's cost per request alike for 1 and N sessions.
void PollOnce(std::vector<Session>& sessions, std::vector<pollfd>& fds, Clock::time_point deadline,
              bool measuring, Totals& totals) {
  fds.clear();
  for (const Session& s : sessions) {
    if (!s.failed && s.waiting) fds.push_back({s.fd, POLLIN, 0});
  }
  if (fds.empty()) return;
  const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()).count();
  const int rc = poll(fds.data(), fds.size(), static_cast<int>(std::clamp<long long>(left + 1, 0, 1000)));
  if (rc <= 0) return;
  std::size_t k = 0;
  for (Session& s : sessions) {
    if (s.failed || !s.waiting) continue;
    const pollfd& p = fds[k++];
    if (p.revents == 0) continue;
    OnReadable(s, measuring, totals);
  }
}

}  // namespace

int main(int argc, char** argv) {
  Options options;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--mix") {
      options.mix = true;
      continue;
    }
    if (i + 1 >= argc) return Usage();
    const char* value = argv[++i];
    if (arg == "--host") options.host = value;
    else if (arg == "--port") options.port = std::atoi(value);
    else if (arg == "--sessions") options.sessions = std::atoi(value);
    else if (arg == "--seconds") options.seconds = std::atof(value);
    else return Usage();
  }
  if (options.sessions < 1 || options.sessions > 64 || options.seconds <= 0 || options.seconds > 60 ||
      options.port < 1 || options.port > 65535) {
    return Usage();
  }
  // Whatever happens (a card that stops answering mid-connect), the run ends by itself.
  std::signal(SIGALRM, [](int) { _exit(3); });
  alarm(static_cast<unsigned>(options.seconds) + 10);

  std::vector<Session> sessions(static_cast<std::size_t>(options.sessions));
  Totals totals;
  totals.latencies_us.reserve(static_cast<std::size_t>(options.seconds * 200000));
  std::vector<pollfd> fds;

  // Connect and register every session before the clock starts.
  const Clock::time_point setup_deadline = Clock::now() + kReplyTimeout;
  for (Session& s : sessions) {
    s.fd = Connect(options, s.failure);
    if (s.fd < 0) {
      s.failed = true;
      continue;
    }
    s.out_size = BuildRegisterSession(s.out.data());
    s.waiting = true;
    if (!SendAll(s)) Fail(s, s.failure);
  }
  while (Clock::now() < setup_deadline &&
         std::any_of(sessions.begin(), sessions.end(), [](const Session& s) { return s.waiting; })) {
    PollOnce(sessions, fds, setup_deadline, false, totals);
  }
  for (Session& s : sessions) {
    if (s.waiting) Fail(s, "no RegisterSession reply within 2 s");
  }

  const double cpu_start = CpuSeconds();
  const Clock::time_point start = Clock::now();
  const Clock::time_point end = start + std::chrono::microseconds(static_cast<long long>(options.seconds * 1e6));
  for (Session& s : sessions) {
    if (!s.failed) SendRequest(s, options.mix);
  }
  Clock::time_point last_reply = start;
  for (;;) {
    const Clock::time_point now = Clock::now();
    bool any_waiting = false;
    Clock::time_point deadline = now + kReplyTimeout;
    for (Session& s : sessions) {
      if (s.failed || !s.waiting) continue;
      if (now - s.sent > kReplyTimeout) {
        Fail(s, "no reply within 2 s");
        continue;
      }
      any_waiting = true;
      deadline = std::min(deadline, s.sent + kReplyTimeout);
    }
    if (!any_waiting) break;
    PollOnce(sessions, fds, deadline, true, totals);
    for (Session& s : sessions) {
      if (s.failed || !s.replied) continue;
      s.replied = false;
      last_reply = std::max(last_reply, s.replied_at);
      if (s.replied_at < end) SendRequest(s, options.mix);  // closed loop: the next request once the reply is in
    }
  }
  const double cpu_used = CpuSeconds() - cpu_start;
  const double window = std::chrono::duration<double>(last_reply - start).count();

  int failed = 0;
  for (Session& s : sessions) {
    if (s.failed) {
      std::fprintf(stderr, "session: %s\n", s.failure.c_str());
      ++failed;
    }
    if (s.fd >= 0) close(s.fd);
  }
  std::vector<std::uint32_t>& all = totals.latencies_us;
  std::sort(all.begin(), all.end());
  const double requests = static_cast<double>(all.size());
  std::printf("sessions=%d requests=%zu seconds=%.2f rps=%.0f p50_us=%u p99_us=%u errors=%llu max_us=%u "
              "failed_sessions=%d client_cpu_us_per_request=%.2f\n",
              options.sessions, all.size(), window, window > 0 ? requests / window : 0.0, Percentile(all, 0.50),
              Percentile(all, 0.99), static_cast<unsigned long long>(totals.errors), all.empty() ? 0u : all.back(),
              failed, requests > 0 ? cpu_used * 1e6 / requests : 0.0);
  return all.empty() ? 1 : 0;
}
