// hal::FramePort on the host over libslirp (user-mode networking): the "loopback port". It needs no
// root, no TAP interface and no capabilities; the card is reached through forwarded host ports.
//
// Addressing scheme (defaults; every address and port is configurable):
//   - The card (slirp's "guest") lives alone in slirp's virtual network 10.0.2.0/24 with the static
//     address 10.0.2.15. 10.0.2.2 is slirp's gateway and stands for the host; 10.0.2.3 is slirp's DNS
//     proxy. IPv6 is off. slirp's DHCP server stays on and hands out exactly the card's address (first
//     lease = 10.0.2.15), so a card configured for DHCP ends up where the forwards point; a card with a
//     static address never asks. The network is not restricted: the card may also reach the outside.
//   - Host ports on ONE loopback address, 127.0.0.2 by default (all of 127.0.0.0/8 is local on Linux,
//     no setup needed), are forwarded to the card:
//       TCP 127.0.0.2:502   -> 10.0.2.15:502    Modbus TCP     (5020 when binding 502 is refused)
//       TCP 127.0.0.2:44818 -> 10.0.2.15:44818  EtherNet/IP explicit messaging
//       UDP 127.0.0.2:44818 -> 10.0.2.15:44818  EtherNet/IP ListIdentity & co.
//       UDP 127.0.0.2:2222  -> 10.0.2.15:2222   Class 1 I/O, O->T
//       TCP 127.0.0.2:80    -> 10.0.2.15:80     web pages      (8080 when binding 80 is refused)
//     A forward whose preferred host port cannot be bound (privileged, in use) uses its fallback port;
//     when that fails too, Create() fails with a sentence such as "UDP 127.0.0.2:2222 in use".
//     ActiveForwards() tells which host endpoints were really bound (for the ready line).
//   - Why 127.0.0.2 and not 127.0.0.1: a scanner (PLC simulator) on the same host must bind its own
//     UDP port 2222 to receive T->O data. Two sockets bound to different specific addresses of the same
//     port coexist, so the card's forward holds 127.0.0.2:2222 and the scanner binds 127.0.0.1:2222. The
//     scanner must bind the specific address 127.0.0.1, not 0.0.0.0: a wildcard bind of 2222 conflicts
//     with the forward (unless both sockets set SO_REUSEADDR).
//   - Card -> host (verified against libslirp 4.7 by hal/host/test/slirp_frame_port_test.cc): slirp
//     rewrites a datagram the card sends to 10.0.2.2:P (any virtual address except the DNS proxy) to
//     127.0.0.1:P. If the card sends from a forwarded guest port (UDP 2222), slirp sends it through that
//     forward's own host socket, so the scanner sees T->O data coming from 127.0.0.2:2222; from any other
//     guest port it comes from 127.0.0.1:<ephemeral>. So T->O to 10.0.2.2:2222 lands on the scanner's
//     127.0.0.1:2222. The other way, datagrams from 127.0.0.1 and TCP connections from any 127.x.y.z
//     reach the card as coming from 10.0.2.2 (source port kept), so the card answers via its gateway;
//     a datagram from another 127.x.y.z source keeps that address.
//
// Port model: one port (L). A simulated cable ("plugged" flag, the control socket's `link L down`):
// plugged = link up, 100 Mbit/s full duplex, auto-negotiated; unplugged = link down, frames from slirp
// are dropped, Transmit() refuses with kFailedPrecondition, and frames still waiting are discarded.
// Frames from slirp wait in a fixed ring allocated at creation (a full ring drops and counts rx_errors).
//
// Event loop: register the port with the PollWaiter. PrepareWait() hands slirp's sockets to poll() and
// lowers the deadline to slirp's next TCP timer (slirp asks to be polled at least once a second), to the
// earliest slirp timer, and to "now" while frames wait in the ring. AfterWait() lets slirp read and write
// its sockets, then fires due timers. Transmit() feeds slirp directly; slirp may answer at once (an ARP
// reply is in the ring when Transmit() returns). Time comes from the injected hal::Clock. No threads.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "base/status.h"
#include "hal/clock.h"
#include "hal/frame_port.h"
#include "poll_waiter.h"

struct Slirp;  // libslirp's opaque state (libslirp.h stays out of this header)

namespace hal::host {

enum class Transport : std::uint8_t { kTcp, kUdp };
const char* TransportName(Transport transport);  // "TCP", "UDP"

// One forward from a host port to a card port. fallback_host_port 0 = no fallback.
struct ForwardRule {
  Transport transport = Transport::kTcp;
  std::uint16_t guest_port = 0;
  std::uint16_t host_port = 0;
  std::uint16_t fallback_host_port = 0;
};

// The card's default forwards: Modbus, EtherNet/IP (TCP and UDP), Class 1 I/O, HTTP (see above).
std::vector<ForwardRule> DefaultForwardRules();

// A forward as it was really bound.
struct ActiveForward {
  Transport transport = Transport::kTcp;
  std::string host_address;  // dotted quad, e.g. "127.0.0.2"
  std::uint16_t host_port = 0;
  std::string guest_address;
  std::uint16_t guest_port = 0;
  bool fallback = false;  // host_port is the rule's fallback port
};

// "TCP 127.0.0.2:5020 -> 10.0.2.15:502"
std::string FormatForward(const ActiveForward& forward);

struct SlirpPortConfig {
  base::MacAddress mac = {0x02, 0x00, 0x00, 0x00, 0x00, 0x01};  // the firmware passes the card's own MAC
  // slirp's virtual network. The DNS proxy is the network's address .3 (must differ from the others).
  std::string network = "10.0.2.0";
  std::string netmask = "255.255.255.0";
  std::string gateway = "10.0.2.2";  // slirp itself; stands for the host
  std::string guest_address = "10.0.2.15";
  // Host address every forward binds to.
  std::string host_address = "127.0.0.2";
  std::vector<ForwardRule> forwards = DefaultForwardRules();
  bool dhcp_server = true;  // first lease = guest_address
  std::size_t rx_queue_frames = 64;
};

class SlirpFramePort final : public FramePort, public PollSource {
 public:
  // Starts slirp and binds every forward. `clock` must outlive the port. kInvalidArgument: a malformed
  // or inconsistent address, a zero port, an empty ring. kFailedPrecondition / kPermissionDenied: a
  // forward could not be bound (in use / privileged), neither on its preferred nor on its fallback port.
  // kInternal: slirp would not start. `error_text` (optional) receives a sentence naming the cause.
  static base::Result<std::unique_ptr<SlirpFramePort>> Create(const SlirpPortConfig& config,
                                                              const Clock& clock,
                                                              std::string* error_text);

  ~SlirpFramePort() override;
  SlirpFramePort(const SlirpFramePort&) = delete;
  SlirpFramePort& operator=(const SlirpFramePort&) = delete;

  // hal::FramePort
  base::MacAddress Mac() const override { return mac_; }
  std::size_t PortCount() const override { return 1; }
  LinkState Link(PortId port) const override;
  PortCounters Counters(PortId port) const override;
  base::Result<ReceivedFrame> Receive(std::span<std::uint8_t> buffer) override;
  base::Status Transmit(PortId port, std::span<const std::uint8_t> frame) override;

  // Simulated cable. kNotFound: no such port.
  base::Status SetPlugged(PortId port, bool plugged);
  bool Plugged(PortId port) const;

  const std::vector<ActiveForward>& ActiveForwards() const { return forwards_; }
  const std::string& GuestAddress() const { return guest_address_; }

  // hal::host::PollSource
  void PrepareWait(PollSet& set, Micros& deadline) override;
  void AfterWait(const PollSet& set) override;

 private:
  friend struct SlirpCallbacks;  // libslirp's C callbacks (slirp_frame_port.cc)
  struct Timer;
  struct RxSlot {
    std::array<std::uint8_t, kMaxFrameBytes> bytes;
    std::size_t length = 0;
  };

  SlirpFramePort(base::MacAddress mac, const Clock& clock, std::size_t rx_queue_frames);
  // A frame from slirp to the card.
  void OnSlirpFrame(std::span<const std::uint8_t> frame);
  void FireDueTimers();

  base::MacAddress mac_;
  const Clock& clock_;
  ::Slirp* slirp_ = nullptr;
  std::string guest_address_;
  std::vector<ActiveForward> forwards_;
  bool plugged_ = true;
  PortCounters counters_;
  std::vector<RxSlot> rx_ring_;  // allocated once
  std::size_t rx_head_ = 0;      // oldest waiting frame
  std::size_t rx_count_ = 0;
  std::vector<std::unique_ptr<Timer>> timers_;
  bool prepared_ = false;                // slirp_pollfds_fill() ran since the last AfterWait()
  const PollSet* revents_set_ = nullptr;  // only during slirp_pollfds_poll()
};

}  // namespace hal::host
