#include "slirp_frame_port.h"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <slirp/libslirp.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <utility>

namespace hal::host {
namespace {

constexpr std::uint32_t kSlirpConfigVersion = 4;  // 4: disable_dhcp and timer_new_opaque exist
constexpr std::uint32_t kNoSlirpTimeout = UINT32_MAX;

void SetErrorText(std::string* error_text, std::string text) {
  if (error_text != nullptr) *error_text = std::move(text);
}

bool ParseIpv4(const std::string& text, in_addr* address) {
  return inet_pton(AF_INET, text.c_str(), address) == 1;
}

std::string FormatIpv4(in_addr address) {
  char text[INET_ADDRSTRLEN] = {};
  inet_ntop(AF_INET, &address, text, sizeof(text));
  return text;
}

// Host byte order, for address arithmetic.
std::uint32_t HostOrder(in_addr address) { return ntohl(address.s_addr); }
in_addr FromHostOrder(std::uint32_t value) {
  in_addr address{};
  address.s_addr = htonl(value);
  return address;
}

struct Addresses {
  in_addr network{};
  in_addr netmask{};
  in_addr gateway{};
  in_addr guest{};
  in_addr dns{};
  in_addr host{};
};

// Returns an empty string when the configuration is usable, else what is wrong with it.
std::string CheckConfig(const SlirpPortConfig& config, Addresses* out) {
  const std::pair<const std::string*, in_addr*> fields[] = {
      {&config.network, &out->network},       {&config.netmask, &out->netmask},
      {&config.gateway, &out->gateway},       {&config.guest_address, &out->guest},
      {&config.host_address, &out->host},
  };
  for (const auto& [text, address] : fields) {
    if (!ParseIpv4(*text, address)) return "'" + *text + "' is not an IPv4 address";
  }
  const std::uint32_t mask = HostOrder(out->netmask);
  const std::uint32_t net = HostOrder(out->network) & mask;
  if (mask == 0 || ((~mask + 1) & ~mask) != 0) return "netmask " + config.netmask + " is not contiguous";
  out->network = FromHostOrder(net);
  out->dns = FromHostOrder(net | 3);
  const std::uint32_t gateway = HostOrder(out->gateway);
  const std::uint32_t guest = HostOrder(out->guest);
  if ((gateway & mask) != net || (guest & mask) != net) {
    return "gateway " + config.gateway + " and card address " + config.guest_address +
           " must lie in " + FormatIpv4(out->network) + "/" + config.netmask;
  }
  if (guest == gateway || guest == HostOrder(out->dns) || gateway == HostOrder(out->dns)) {
    return "card address " + config.guest_address + ", gateway " + config.gateway +
           " and DNS proxy " + FormatIpv4(out->dns) + " must differ";
  }
  for (const ForwardRule& rule : config.forwards) {
    if (rule.guest_port == 0 || rule.host_port == 0) return "a forward has port 0";
  }
  if (config.rx_queue_frames == 0) return "the receive queue needs at least one frame";
  return {};
}

// Why a host socket could not be bound, and the status that goes with it.
std::string BindFailureText(int err) {
  switch (err) {
    case EADDRINUSE: return "in use";
    case EACCES:
    case EPERM: return "permission denied";
    case EADDRNOTAVAIL: return "is not an address of this host";
    default: return std::strerror(err);
  }
}

base::Status BindFailureStatus(int err) {
  switch (err) {
    case EADDRINUSE: return base::FailedPrecondition();
    case EACCES:
    case EPERM: return base::PermissionDenied();
    case EADDRNOTAVAIL: return base::InvalidArgument();
    default: return base::Internal();
  }
}

std::string Endpoint(Transport transport, in_addr address, std::uint16_t port) {
  return std::string(TransportName(transport)) + " " + FormatIpv4(address) + ":" + std::to_string(port);
}

short PollEventsFromSlirp(int events) {
  int result = 0;
  if ((events & SLIRP_POLL_IN) != 0) result |= POLLIN;
  if ((events & SLIRP_POLL_OUT) != 0) result |= POLLOUT;
  if ((events & SLIRP_POLL_PRI) != 0) result |= POLLPRI;
  if ((events & SLIRP_POLL_ERR) != 0) result |= POLLERR;
  if ((events & SLIRP_POLL_HUP) != 0) result |= POLLHUP;
  return static_cast<short>(result);
}

int SlirpEventsFromPoll(short revents) {
  int result = 0;
  if ((revents & POLLIN) != 0) result |= SLIRP_POLL_IN;
  if ((revents & POLLOUT) != 0) result |= SLIRP_POLL_OUT;
  if ((revents & POLLPRI) != 0) result |= SLIRP_POLL_PRI;
  if ((revents & (POLLERR | POLLNVAL)) != 0) result |= SLIRP_POLL_ERR;
  if ((revents & POLLHUP) != 0) result |= SLIRP_POLL_HUP;
  return result;
}

}  // namespace

// A slirp timer. slirp 4.7 creates them with timer_new_opaque (fired through slirp_handle_timer); the
// older timer_new style (a plain callback) is kept for completeness.
struct SlirpFramePort::Timer {
  SlirpTimerCb callback = nullptr;  // timer_new(); nullptr for timer_new_opaque()
  SlirpTimerId id = SLIRP_TIMER_RA;
  void* cb_opaque = nullptr;
  Micros due = kNever;
};

// libslirp's C callbacks. `opaque` is the SlirpFramePort, except for AddPoll (the PollSet).
struct SlirpCallbacks {
  static SlirpFramePort& Port(void* opaque) { return *static_cast<SlirpFramePort*>(opaque); }

  static ssize_t SendPacket(const void* buf, size_t len, void* opaque) {
    Port(opaque).OnSlirpFrame(std::span<const std::uint8_t>(static_cast<const std::uint8_t*>(buf), len));
    return static_cast<ssize_t>(len);
  }
  static void GuestError(const char* msg, void* /*opaque*/) {
    std::fprintf(stderr, "loopback port: slirp reports a bad frame from the card: %s\n", msg);
  }
  static int64_t ClockGetNs(void* opaque) {
    return static_cast<int64_t>(Port(opaque).clock_.NowMicros() * 1000);
  }
  static void* NewTimer(SlirpFramePort& port, std::unique_ptr<SlirpFramePort::Timer> timer) {
    port.timers_.push_back(std::move(timer));
    return port.timers_.back().get();
  }
  static void* TimerNew(SlirpTimerCb cb, void* cb_opaque, void* opaque) {
    auto timer = std::make_unique<SlirpFramePort::Timer>();
    timer->callback = cb;
    timer->cb_opaque = cb_opaque;
    return NewTimer(Port(opaque), std::move(timer));
  }
  static void* TimerNewOpaque(SlirpTimerId id, void* cb_opaque, void* opaque) {
    auto timer = std::make_unique<SlirpFramePort::Timer>();
    timer->id = id;
    timer->cb_opaque = cb_opaque;
    return NewTimer(Port(opaque), std::move(timer));
  }
  static void TimerFree(void* timer, void* opaque) {
    auto& timers = Port(opaque).timers_;
    std::erase_if(timers, [timer](const auto& t) { return t.get() == timer; });
  }
  // expire_time: milliseconds on the clock_get_ns() time base.
  static void TimerMod(void* timer, int64_t expire_time, void* /*opaque*/) {
    static_cast<SlirpFramePort::Timer*>(timer)->due =
        expire_time <= 0 ? 0 : static_cast<Micros>(expire_time) * kMicrosPerMilli;
  }
  // Descriptors are collected afresh by slirp_pollfds_fill() before every wait.
  static void RegisterPollFd(int /*fd*/, void* /*opaque*/) {}
  static void UnregisterPollFd(int /*fd*/, void* /*opaque*/) {}
  // Single-threaded: the loop polls slirp on every pass anyway.
  static void Notify(void* /*opaque*/) {}

  static int AddPoll(int fd, int events, void* opaque) {
    return static_cast<int>(static_cast<PollSet*>(opaque)->Add(fd, PollEventsFromSlirp(events)));
  }
  static int GetRevents(int idx, void* opaque) {
    const PollSet* set = Port(opaque).revents_set_;
    if (set == nullptr || idx < 0) return 0;
    return SlirpEventsFromPoll(set->Revents(static_cast<std::size_t>(idx)));
  }
  static int NoRevents(int /*idx*/, void* /*opaque*/) { return 0; }

  static const SlirpCb& Table() {
    static const SlirpCb table = [] {
      SlirpCb cb{};
      cb.send_packet = &SendPacket;
      cb.guest_error = &GuestError;
      cb.clock_get_ns = &ClockGetNs;
      cb.timer_new = &TimerNew;
      cb.timer_free = &TimerFree;
      cb.timer_mod = &TimerMod;
      cb.register_poll_fd = &RegisterPollFd;
      cb.unregister_poll_fd = &UnregisterPollFd;
      cb.notify = &Notify;
      cb.init_completed = nullptr;
      cb.timer_new_opaque = &TimerNewOpaque;
      return cb;
    }();
    return table;
  }
};

const char* TransportName(Transport transport) { return transport == Transport::kUdp ? "UDP" : "TCP"; }

std::vector<ForwardRule> DefaultForwardRules() {
  return {
      {Transport::kTcp, 502, 502, 5020},     // Modbus TCP
      {Transport::kTcp, 44818, 44818, 0},    // EtherNet/IP explicit messaging
      {Transport::kUdp, 44818, 44818, 0},    // EtherNet/IP ListIdentity
      {Transport::kUdp, 2222, 2222, 0},      // Class 1 I/O
      {Transport::kTcp, 80, 80, 8080},       // HTTP
  };
}

std::string FormatForward(const ActiveForward& forward) {
  return std::string(TransportName(forward.transport)) + " " + forward.host_address + ":" +
         std::to_string(forward.host_port) + " -> " + forward.guest_address + ":" +
         std::to_string(forward.guest_port);
}

SlirpFramePort::SlirpFramePort(base::MacAddress mac, const Clock& clock, std::size_t rx_queue_frames)
    : mac_(mac), clock_(clock), rx_ring_(rx_queue_frames) {}

SlirpFramePort::~SlirpFramePort() {
  // slirp_cleanup() closes slirp's sockets and frees its timers through the callbacks, so it runs
  // while every member is still alive.
  if (slirp_ != nullptr) slirp_cleanup(slirp_);
}

base::Result<std::unique_ptr<SlirpFramePort>> SlirpFramePort::Create(const SlirpPortConfig& config,
                                                                     const Clock& clock,
                                                                     std::string* error_text) {
  Addresses addr;
  if (std::string problem = CheckConfig(config, &addr); !problem.empty()) {
    SetErrorText(error_text, "loopback port: " + problem);
    return base::InvalidArgument();
  }
  std::unique_ptr<SlirpFramePort> port(new SlirpFramePort(config.mac, clock, config.rx_queue_frames));
  port->guest_address_ = FormatIpv4(addr.guest);

  ::SlirpConfig cfg{};
  cfg.version = kSlirpConfigVersion;
  cfg.restricted = 0;
  cfg.in_enabled = true;
  cfg.vnetwork = addr.network;
  cfg.vnetmask = addr.netmask;
  cfg.vhost = addr.gateway;
  cfg.in6_enabled = false;
  cfg.vdhcp_start = addr.guest;
  cfg.vnameserver = addr.dns;
  cfg.disable_host_loopback = false;  // 10.0.2.2 must reach the host's 127.0.0.1
  cfg.enable_emu = false;
  cfg.disable_dns = false;
  cfg.disable_dhcp = !config.dhcp_server;
  port->slirp_ = slirp_new(&cfg, &SlirpCallbacks::Table(), port.get());
  if (port->slirp_ == nullptr) {
    SetErrorText(error_text, "loopback port: libslirp refused to start");
    return base::Internal();
  }

  for (const ForwardRule& rule : config.forwards) {
    const int is_udp = rule.transport == Transport::kUdp ? 1 : 0;
    std::uint16_t host_port = rule.host_port;
    bool fallback = false;
    int rc = slirp_add_hostfwd(port->slirp_, is_udp, addr.host, host_port, addr.guest, rule.guest_port);
    int err = errno;
    std::string failure;
    if (rc < 0) {
      failure = Endpoint(rule.transport, addr.host, host_port) + " " + BindFailureText(err);
      if (rule.fallback_host_port != 0 && rule.fallback_host_port != rule.host_port) {
        host_port = rule.fallback_host_port;
        fallback = true;
        rc = slirp_add_hostfwd(port->slirp_, is_udp, addr.host, host_port, addr.guest, rule.guest_port);
        err = errno;
        if (rc < 0) {
          failure += ", fallback " + Endpoint(rule.transport, addr.host, host_port) + " " +
                     BindFailureText(err);
        }
      }
    }
    if (rc < 0) {
      SetErrorText(error_text, "loopback port: " + failure);
      return BindFailureStatus(err);
    }
    port->forwards_.push_back(ActiveForward{rule.transport, FormatIpv4(addr.host), host_port,
                                            port->guest_address_, rule.guest_port, fallback});
  }
  return port;
}

LinkState SlirpFramePort::Link(PortId port) const {
  if (port != PortId::kLeft || !plugged_) return LinkState{};
  return LinkState{true, LinkSpeed::k100Mbps, true, true};
}

PortCounters SlirpFramePort::Counters(PortId port) const {
  return port == PortId::kLeft ? counters_ : PortCounters{};
}

base::Status SlirpFramePort::SetPlugged(PortId port, bool plugged) {
  if (port != PortId::kLeft) return base::NotFound();
  plugged_ = plugged;
  if (!plugged) {  // frames still waiting at the MAC are lost with the cable
    rx_head_ = 0;
    rx_count_ = 0;
  }
  return base::OkStatus();
}

bool SlirpFramePort::Plugged(PortId port) const { return port == PortId::kLeft && plugged_; }

base::Result<ReceivedFrame> SlirpFramePort::Receive(std::span<std::uint8_t> buffer) {
  if (rx_count_ == 0) return base::Unavailable();
  const RxSlot& slot = rx_ring_[rx_head_];
  rx_head_ = (rx_head_ + 1) % rx_ring_.size();
  --rx_count_;
  if (slot.length > buffer.size()) {
    ++counters_.rx_errors;
    return base::OutOfRange();
  }
  std::copy_n(slot.bytes.begin(), slot.length, buffer.begin());
  ++counters_.rx_frames;
  counters_.rx_octets += slot.length;
  return ReceivedFrame{slot.length, PortId::kLeft};
}

base::Status SlirpFramePort::Transmit(PortId port, std::span<const std::uint8_t> frame) {
  if (port != PortId::kLeft) return base::NotFound();
  if (!plugged_) {
    ++counters_.tx_errors;
    return base::FailedPrecondition();
  }
  if (frame.size() < kMinFrameBytes || frame.size() > kMaxFrameBytes) {
    ++counters_.tx_errors;
    return base::OutOfRange();
  }
  ++counters_.tx_frames;
  counters_.tx_octets += frame.size();
  // slirp may answer from inside this call (ARP, ICMP echo): the answer lands in the ring.
  slirp_input(slirp_, frame.data(), static_cast<int>(frame.size()));
  return base::OkStatus();
}

void SlirpFramePort::OnSlirpFrame(std::span<const std::uint8_t> frame) {
  if (!plugged_) return;  // nothing arrives over an unplugged cable
  if (frame.size() < kMinFrameBytes || frame.size() > kMaxFrameBytes || rx_count_ == rx_ring_.size()) {
    ++counters_.rx_errors;
    return;
  }
  RxSlot& slot = rx_ring_[(rx_head_ + rx_count_) % rx_ring_.size()];
  std::copy(frame.begin(), frame.end(), slot.bytes.begin());
  slot.length = frame.size();
  ++rx_count_;
}

void SlirpFramePort::PrepareWait(PollSet& set, Micros& deadline) {
  const Micros now = clock_.NowMicros();
  std::uint32_t timeout_ms = kNoSlirpTimeout;
  slirp_pollfds_fill(slirp_, &timeout_ms, &SlirpCallbacks::AddPoll, &set);
  prepared_ = true;
  if (timeout_ms != kNoSlirpTimeout) {
    deadline = std::min(deadline, now + static_cast<Micros>(timeout_ms) * kMicrosPerMilli);
  }
  for (const auto& timer : timers_) deadline = std::min(deadline, timer->due);
  if (rx_count_ > 0) deadline = std::min(deadline, now);  // frames wait: do not sleep
}

void SlirpFramePort::AfterWait(const PollSet& set) {
  if (prepared_) {
    revents_set_ = &set;
    slirp_pollfds_poll(slirp_, 0, &SlirpCallbacks::GetRevents, this);
    revents_set_ = nullptr;
  } else {
    // No descriptors were handed out: let slirp run its TCP timers and output queue only.
    slirp_pollfds_poll(slirp_, 0, &SlirpCallbacks::NoRevents, this);
  }
  prepared_ = false;
  FireDueTimers();
}

void SlirpFramePort::FireDueTimers() {
  const Micros now = clock_.NowMicros();
  // A callback may re-arm, create or free timers, so look again after each one; each pass fires at
  // most as many timers as existed when it began (a timer re-armed into the past waits for the next).
  const std::size_t limit = timers_.size();
  for (std::size_t fired = 0; fired < limit; ++fired) {
    auto due = std::find_if(timers_.begin(), timers_.end(),
                            [now](const auto& timer) { return timer->due <= now; });
    if (due == timers_.end()) return;
    Timer& timer = **due;
    timer.due = kNever;
    if (timer.callback != nullptr) {
      timer.callback(timer.cb_opaque);
    } else {
      slirp_handle_timer(slirp_, timer.id, timer.cb_opaque);
    }
  }
}

}  // namespace hal::host
