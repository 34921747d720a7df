// How the card gets and keeps its IP address (NET-1, NET-2, NET-4; docs/network.md "Addressing"):
//
//   c504 = 0 manual  c505-c516 (an unusable address: none; mask 0 or non-contiguous: the classful mask)
//   c504 = 1 BOOTP   net::BootpClient on a raw UDP PCB (port 68), until a server answers for our MAC
//   c504 = 2 DHCP    lwIP's client; host name and client identifier (option 61) = the device name
//                    (c081-c096)
//
// With ACD on (TCP/IP attribute 10, the default), a manual or BOOTP address is probed first and installed
// in lwIP only once net::Acd says it is usable; a DHCP address (already ARP-checked by lwIP's client) is
// claimed and announced. While the address is in use a conflict is defended once; a second one within
// DEFEND_INTERVAL makes the card drop it (manual, BOOTP: ACD probes again a minute later; DHCP: the lease
// is released and DHCP starts again after 10 s, RFC 2131 §3.1 step 5).
//
// Configure() runs after each configuration load (start-up, f899 = 1, link recovery): when the addressing
// parameters changed (or nothing runs yet) the network side restarts with them: the address goes (lwIP
// aborts the TCP connections bound to it), BOOTP/DHCP/ACD stop, the new mode starts. An unchanged
// configuration leaves the address and every connection alone.
//
// Device-path code: no allocation (the DHCP client state is ours, dhcp_set_struct), one UDP PCB.
#pragma once

#include <array>
#include <cstdint>
#include <span>

#include "base/status.h"
#include "card_netif.h"
#include "configurable_service.h"
#include "config/card_config.h"
#include "event_loop.h"
#include "hal/clock.h"
#include "hal/random.h"
#include "lwip/prot/dhcp.h"
#include "lwip/dhcp.h"
#include "lwip/udp.h"
#include "net/acd.h"
#include "net/bootp_client.h"

namespace firmware {

// What Configure takes from the configuration; a change of any of it restarts the addressing.
struct AddressingPlan {
  config::IpMode mode = config::IpMode::kManual;
  Ipv4Config manual;                  // c505-c516 as given (validated when used)
  std::array<char, 17> host_name{};  // c081-c096, NUL-terminated

  bool operator==(const AddressingPlan&) const = default;
};

AddressingPlan PlanFromConfig(const config::CardConfig& config);

// The mask a manual or BOOTP address gets when none (or a non-contiguous one) is given: class A, B or C.
base::Ipv4Address ClassfulMask(base::Ipv4Address address);

enum class AddressPhase : std::uint8_t {
  kNotConfigured,  // no configuration yet, or manual mode without a usable address
  kAcquiring,      // BOOTP or DHCP running, no answer yet
  kProbing,        // ACD checks the address before use
  kInUse,          // installed in lwIP
  kConflict,       // ACD found it in use elsewhere: not used (retried later)
};
const char* AddressPhaseName(AddressPhase phase);

struct AddressingCounters {
  std::uint32_t restarts = 0;         // Configure() with a changed plan
  std::uint32_t bootp_requests = 0;   // BOOTREQUESTs sent
  std::uint32_t bootp_replies = 0;    // BOOTREPLYs accepted
  std::uint32_t bootp_ignored = 0;    // datagrams on port 68 that were not our answer
  std::uint32_t dhcp_restarts = 0;    // DHCP started again after ACD gave the lease up
  std::uint32_t acd_frames_sent = 0;  // probes, announcements and defences
  std::uint32_t acd_conflicts = 0;    // probe conflicts, defences and yields
  std::uint32_t address_changes = 0;  // the address in lwIP changed
};

class CardAddressing final : public Service, public ConfigurableService, public NetifObserver, private net::ArpSink {
 public:
  CardAddressing(CardNetif& netif, const hal::Clock& clock, hal::RandomSource& random);
  ~CardAddressing() override;
  CardAddressing(const CardAddressing&) = delete;
  CardAddressing& operator=(const CardAddressing&) = delete;

  // TCP/IP attribute 10 as stored; applied at the next restart of the addressing (set it before the first
  // configuration load).
  void SetAcdEnabled(bool enabled) { acd_selected_ = enabled; }

  base::Status Configure(const config::CardConfig& config) override;
  void Poll(hal::Micros now) override;
  hal::Micros NextDeadline() const override;

  // NetifObserver
  void OnFrameToCard(std::span<const std::uint8_t> frame) override;
  void OnPortLinkUp(hal::PortId port) override;

  AddressPhase phase() const;
  config::IpMode mode() const { return plan_.mode; }
  bool configured() const { return configured_; }
  // The address in lwIP (host order; 0.0.0.0 when none).
  Ipv4Config active() const;
  bool has_address() const { return !active().address.IsUnspecified(); }
  bool acquiring() const { return phase() == AddressPhase::kAcquiring; }
  // A conflict found since the last restart (one found for the plan before is not this plan's).
  bool duplicate_detected() const { return acd_ran_ && acd_.DuplicateDetected(); }
  const net::AcdConflictRecord& last_conflict() const { return acd_.LastConflict(); }
  void ClearLastConflict() { acd_.ClearLastConflict(); }
  const AddressingCounters& counters() const { return counters_; }

 private:
  void Restart(hal::Micros now);
  void StopAll();
  void Install(const Ipv4Config& config);
  void Uninstall();
  void StartBootp(hal::Micros now);
  void PollBootp(hal::Micros now);
  void PollDhcp(hal::Micros now);
  void PollManualOrBootp();
  void UseAddress(const Ipv4Config& config, hal::Micros now);
  void SendArp(std::span<const std::uint8_t, net::kArpFrameSize> frame) override;
  static void BootpReceived(void* arg, udp_pcb* pcb, pbuf* p, const ip_addr_t* address, u16_t port);

  CardNetif& netif_;
  const hal::Clock& clock_;
  net::Acd acd_;
  net::BootpClient bootp_;
  udp_pcb* bootp_pcb_ = nullptr;
  dhcp dhcp_{};  // lwIP's client state, ours (no allocation)
  bool dhcp_running_ = false;
  hal::Micros dhcp_restart_at_ = hal::kNever;

  AddressingPlan plan_;
  bool configured_ = false;
  bool acd_selected_ = true;  // as set (attribute 10)
  bool acd_enabled_ = true;   // in force since the last restart
  bool acd_ran_ = false;      // ACD started or claimed an address since the last restart
  Ipv4Config target_;      // the address ACD probes or guards (manual, BOOTP lease, DHCP lease)
  bool target_set_ = false;
  AddressingCounters counters_;
};

}  // namespace firmware
