// Class 1 implicit I/O (cip::ConnectionManager) bound to lwIP's raw UDP API on port 2222.
//
// - Open while c500 = 1 (EtherNet/IP), closed otherwise (Configure), like the encapsulation ports.
// - Every datagram is copied out of its pbuf and handed to the connection manager at once; a longer
//   one than any connection's data is dropped and counted (the manager drops anything else it cannot
//   use and counts it too).
// - Poll sends every production that is due: point-to-point to the originator, multicast to the
//   connection's group with the TTL of TCP/IP attribute 8. Production needs no IGMP membership (the
//   card does not consume multicast); lwIP sends IGMP reports only for groups it joined.
// - Each production's IP header carries the DSCP the QoS object gives the T->O priority of its
//   connection (set_qos: the values in force; none: DSCP 0).
// - NextDeadline is the manager's, so the event loop wakes for each production slot; the host waiter
//   sleeps with microsecond resolution (hal/host/poll_waiter.cc) so slots are met to well under an RPI.
#pragma once

#include <array>
#include <cstdint>

#include "base/status.h"
#include "cip/connection_manager.h"
#include "cip/providers.h"
#include "configurable_service.h"
#include "config/card_config.h"
#include "event_loop.h"
#include "hal/clock.h"
#include "lwip/udp.h"

namespace firmware {

struct IoCounters {
  std::uint32_t received = 0;    // datagrams on UDP 2222
  std::uint32_t too_long = 0;    // ... longer than any connection's data: dropped here
  std::uint32_t sent = 0;        // productions sent
  std::uint32_t send_failed = 0; // no pbuf, or lwIP refused the datagram (e.g. no route, no ARP entry yet)
};

// TTL of multicast productions (TCP/IP object attribute 8).
class MulticastTtlSource {
 public:
  virtual ~MulticastTtlSource() = default;
  virtual std::uint8_t MulticastTtl() const = 0;
};

class IoService final : public Service, public ConfigurableService {
 public:
  IoService(cip::ConnectionManager& manager, const hal::Clock& clock, const MulticastTtlSource& ttl,
            std::uint16_t port = cip::kIoPort)
      : manager_(manager), clock_(clock), ttl_(ttl), port_(port) {}
  ~IoService() override { Stop(); }
  IoService(const IoService&) = delete;
  IoService& operator=(const IoService&) = delete;

  base::Status Configure(const config::CardConfig& config) override;
  base::Status Start();
  void Stop();
  bool running() const { return pcb_ != nullptr; }
  // The QoS values productions are marked with (outliving the service; null: DSCP 0).
  void set_qos(const cip::QosSettings* qos) { qos_ = qos; }

  void Poll(hal::Micros now) override;
  hal::Micros NextDeadline() const override;

  const IoCounters& counters() const { return counters_; }

 private:
  static void OnUdp(void* arg, udp_pcb* pcb, pbuf* p, const ip_addr_t* address, u16_t port);
  void Receive(pbuf* p, const ip_addr_t* address, u16_t port);
  void Send(const cip::IoDatagram& datagram);

  cip::ConnectionManager& manager_;
  const hal::Clock& clock_;
  const MulticastTtlSource& ttl_;
  const cip::QosSettings* qos_ = nullptr;
  std::uint16_t port_;
  udp_pcb* pcb_ = nullptr;
  IoCounters counters_;
  std::array<std::uint8_t, cip::kMaxIoDatagram> datagram_{};
};

}  // namespace firmware
