// hal::FramePort on the host over Linux TAP interfaces: port L (and optionally R) is an existing TAP
// interface, so the card's frames enter the host's (or a network namespace's) IP stack, where tools
// such as an EtherNet/IP scanner, ping or tshark can reach them.
//
// The TAP interfaces must already exist (`ip tuntap add dev ipe0 mode tap user $USER`): opening never
// creates one, so a typo in a name is an error instead of a new, unconnected interface.
//
// A TAP interface has no cable, so each port carries a simulated "cable plugged" flag (the control
// socket's `link L down`). Link up means plugged; the link then reports 100 Mbit/s full duplex,
// auto-negotiated, like the card's PHYs against a switch. While unplugged, frames the host sends to that
// port are read and thrown away (an unplugged cable delivers nothing) and Transmit() refuses.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "base/status.h"
#include "hal/frame_port.h"
#include "poll_waiter.h"

namespace hal::host {

class TapFramePort final : public FramePort, public PollSource {
 public:
  // Opens one TAP interface per name: ifnames[0] is port L, ifnames[1] (if given) port R.
  // kInvalidArgument: not 1 or 2 names, or a name too long for an interface. kNotFound: no such
  // interface (or no /dev/net/tun). kPermissionDenied: the process may not attach to it (needs
  // CAP_NET_ADMIN or the interface's `user`). kFailedPrecondition: not a TAP, or already attached
  // elsewhere. `error_text` (optional) receives a sentence naming the interface and the cause.
  static base::Result<std::unique_ptr<TapFramePort>> Open(std::span<const std::string> ifnames,
                                                          base::MacAddress mac, std::string* error_text);

  ~TapFramePort() override;
  TapFramePort(const TapFramePort&) = delete;
  TapFramePort& operator=(const TapFramePort&) = delete;

  // hal::FramePort
  base::MacAddress Mac() const override { return mac_; }
  std::size_t PortCount() const override { return ports_.size(); }
  LinkState Link(PortId port) const override;
  PortCounters Counters(PortId port) const override;
  base::Result<ReceivedFrame> Receive(std::span<std::uint8_t> buffer) override;
  base::Status Transmit(PortId port, std::span<const std::uint8_t> frame) override;

  // Simulated cable. Plugging a cable back in discards whatever the host queued while it was out.
  // kNotFound: no such port.
  base::Status SetPlugged(PortId port, bool plugged);
  bool Plugged(PortId port) const;
  const std::string& InterfaceName(PortId port) const;

  // hal::host::PollSource: every TAP descriptor is watched for input, plugged or not, so that frames
  // arriving on an unplugged port wake the loop and are discarded instead of piling up.
  void PrepareWait(PollSet& set, Micros& deadline) override;
  void AfterWait(const PollSet& set) override;

 private:
  struct Port {
    int fd = -1;
    std::string ifname;
    bool plugged = true;
    PortCounters counters;
  };

  explicit TapFramePort(base::MacAddress mac);
  // Reads and throws away every frame waiting on an unplugged port's descriptor.
  void DrainUnplugged(Port& port);

  base::MacAddress mac_;
  std::vector<Port> ports_;
  std::size_t next_port_ = 0;  // round-robin start for the next Receive()
  // A TAP read must be given room for the largest frame the interface may hand over (its MTU can be
  // raised far beyond 1500), otherwise the kernel silently truncates it and an oversize frame would
  // look like a valid one. Frames are read here first, then checked and copied to the caller.
  std::vector<std::uint8_t> scratch_;
};

}  // namespace hal::host
