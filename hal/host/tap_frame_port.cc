#include "tap_frame_port.h"

#include <fcntl.h>
#include <linux/if_tun.h>
#include <net/if.h>
#include <sys/ioctl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <utility>

namespace hal::host {
namespace {

// Larger than any frame a TAP interface can deliver (its MTU is at most 64 KiB plus the header).
constexpr std::size_t kScratchBytes = 65536 + 64;

void SetErrorText(std::string* error_text, std::string text) {
  if (error_text != nullptr) *error_text = std::move(text);
}

base::Status StatusFromOpenErrno(int err) {
  switch (err) {
    case EPERM:
    case EACCES: return base::PermissionDenied();
    case ENOENT:
    case ENODEV: return base::NotFound();
    case EINVAL:
    case EBUSY: return base::FailedPrecondition();
    default: return base::Internal();
  }
}

std::string ExplainOpenErrno(const std::string& ifname, int err) {
  const std::string prefix = "TAP interface '" + ifname + "': ";
  switch (err) {
    case EPERM:
    case EACCES:
      return prefix + "permission denied (run as root, or create it with `ip tuntap add dev " + ifname +
             " mode tap user <you>`)";
    case ENOENT:
    case ENODEV: return prefix + "cannot open /dev/net/tun (no TUN/TAP support in this kernel?)";
    case EINVAL: return prefix + "exists but is not a single-queue TAP interface";
    case EBUSY: return prefix + "is already attached to another process";
    default: return prefix + std::strerror(err);
  }
}

bool InterfaceExists(const std::string& ifname) {
  return if_nametoindex(ifname.c_str()) != 0;
}

// Attaches a new non-blocking descriptor to the existing TAP interface `ifname`. Returns the fd, or -1
// with errno set.
int AttachTap(const std::string& ifname) {
  const int fd = open("/dev/net/tun", O_RDWR | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) return -1;
  ifreq ifr{};
  // IFF_NO_PI: whole Ethernet frames, without the 4-byte packet-information prefix.
  ifr.ifr_flags = IFF_TAP | IFF_NO_PI;
  std::memcpy(ifr.ifr_name, ifname.c_str(), ifname.size() + 1);
  if (ioctl(fd, TUNSETIFF, &ifr) < 0) {
    const int err = errno;
    close(fd);
    errno = err;
    return -1;
  }
  return fd;
}

}  // namespace

TapFramePort::TapFramePort(base::MacAddress mac) : mac_(mac), scratch_(kScratchBytes) {}

TapFramePort::~TapFramePort() {
  for (Port& port : ports_) {
    if (port.fd >= 0) close(port.fd);
  }
}

base::Result<std::unique_ptr<TapFramePort>> TapFramePort::Open(std::span<const std::string> ifnames,
                                                               base::MacAddress mac,
                                                               std::string* error_text) {
  if (ifnames.empty() || ifnames.size() > kMaxPorts) {
    SetErrorText(error_text, "a TAP frame port needs 1 or 2 interface names, got " +
                                 std::to_string(ifnames.size()));
    return base::InvalidArgument();
  }
  std::unique_ptr<TapFramePort> tap(new TapFramePort(mac));
  for (const std::string& ifname : ifnames) {
    if (ifname.empty() || ifname.size() >= IFNAMSIZ) {
      SetErrorText(error_text, "TAP interface name '" + ifname + "' must be 1 to " +
                                   std::to_string(IFNAMSIZ - 1) + " characters");
      return base::InvalidArgument();
    }
    // TUNSETIFF with an unknown name would create a fresh interface that nothing is connected to.
    if (!InterfaceExists(ifname)) {
      SetErrorText(error_text, "TAP interface '" + ifname +
                                   "': no such device (create it with `ip tuntap add dev " + ifname +
                                   " mode tap`)");
      return base::NotFound();
    }
    const int fd = AttachTap(ifname);
    if (fd < 0) {
      const int err = errno;
      SetErrorText(error_text, ExplainOpenErrno(ifname, err));
      return StatusFromOpenErrno(err);
    }
    Port port;
    port.fd = fd;
    port.ifname = ifname;
    tap->ports_.push_back(std::move(port));
  }
  return tap;
}

LinkState TapFramePort::Link(PortId port) const {
  if (PortIndex(port) >= ports_.size() || !ports_[PortIndex(port)].plugged) return LinkState{};
  return LinkState{
      .up = true, .speed = LinkSpeed::k100Mbps, .full_duplex = true, .auto_negotiated = true};
}

PortCounters TapFramePort::Counters(PortId port) const {
  if (PortIndex(port) >= ports_.size()) return PortCounters{};
  return ports_[PortIndex(port)].counters;
}

base::Result<ReceivedFrame> TapFramePort::Receive(std::span<std::uint8_t> buffer) {
  // Round-robin: start with the port after the one that delivered last, so a busy port cannot starve
  // the other one.
  for (std::size_t tried = 0; tried < ports_.size(); ++tried) {
    const std::size_t index = (next_port_ + tried) % ports_.size();
    Port& port = ports_[index];
    if (!port.plugged) {
      DrainUnplugged(port);
      continue;
    }
    const ssize_t n = read(port.fd, scratch_.data(), scratch_.size());
    if (n < 0) {
      if (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR) continue;
      return base::Internal();
    }
    next_port_ = (index + 1) % ports_.size();
    const auto length = static_cast<std::size_t>(n);
    if (length < kMinFrameBytes || length > kMaxFrameBytes || length > buffer.size()) {
      ++port.counters.rx_errors;
      return base::OutOfRange();
    }
    std::memcpy(buffer.data(), scratch_.data(), length);
    ++port.counters.rx_frames;
    port.counters.rx_octets += length;
    return ReceivedFrame{.length = length, .port = static_cast<PortId>(index)};
  }
  return base::Unavailable();
}

base::Status TapFramePort::Transmit(PortId port_id, std::span<const std::uint8_t> frame) {
  if (PortIndex(port_id) >= ports_.size()) return base::NotFound();
  if (frame.size() < kMinFrameBytes || frame.size() > kMaxFrameBytes) return base::InvalidArgument();
  Port& port = ports_[PortIndex(port_id)];
  if (!port.plugged) {
    ++port.counters.tx_errors;
    return base::FailedPrecondition();
  }
  // One write() is one frame on a TAP descriptor; it is never split.
  ssize_t n = -1;
  do {
    n = write(port.fd, frame.data(), frame.size());
  } while (n < 0 && errno == EINTR);
  if (n < 0) {
    ++port.counters.tx_errors;
    if (errno == EAGAIN || errno == EWOULDBLOCK || errno == ENOBUFS) return base::ResourceExhausted();
    // EIO: the host side of the interface is administratively down; the frame goes nowhere.
    return errno == EIO ? base::FailedPrecondition() : base::Internal();
  }
  ++port.counters.tx_frames;
  port.counters.tx_octets += frame.size();
  return base::OkStatus();
}

base::Status TapFramePort::SetPlugged(PortId port_id, bool plugged) {
  if (PortIndex(port_id) >= ports_.size()) return base::NotFound();
  Port& port = ports_[PortIndex(port_id)];
  // Frames the host queued while the cable was out were never delivered; drop them before going live.
  if (plugged && !port.plugged) DrainUnplugged(port);
  port.plugged = plugged;
  return base::OkStatus();
}

bool TapFramePort::Plugged(PortId port) const {
  return PortIndex(port) < ports_.size() && ports_[PortIndex(port)].plugged;
}

const std::string& TapFramePort::InterfaceName(PortId port) const {
  static const std::string kNone;
  return PortIndex(port) < ports_.size() ? ports_[PortIndex(port)].ifname : kNone;
}

void TapFramePort::DrainUnplugged(Port& port) {
  while (read(port.fd, scratch_.data(), scratch_.size()) > 0) {
  }
}

void TapFramePort::PrepareWait(PollSet& set, Micros& /*deadline*/) {
  for (const Port& port : ports_) set.Add(port.fd, POLLIN);
}

void TapFramePort::AfterWait(const PollSet& /*set*/) {
  // Nothing to do: Receive() reads the descriptors directly, and the event loop calls it every pass.
}

}  // namespace hal::host
