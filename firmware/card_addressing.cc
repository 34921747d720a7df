#include "card_addressing.h"

#include <algorithm>
#include <cstring>

#include "ipv4_lwip.h"
#include "lwip/pbuf.h"

namespace firmware {
namespace {

// RFC 2131 §3.1 step 5: after declining an address, wait at least ten seconds before starting again.
constexpr hal::Micros kDhcpRestartDelay = 10 * hal::kMicrosPerSecond;

// The largest BOOTP/DHCP datagram read (a reply larger than an Ethernet payload cannot arrive unfragmented,
// and lwIP reassembles nothing: IP_REASSEMBLY 0).
constexpr std::size_t kMaxBootReply = 1472;

// The manual configuration as the card uses it: no address when c505-c508 is not a usable unicast
// address; the classful mask when c509-c512 is 0 or not contiguous; no gateway outside the subnet.
Ipv4Config UsableManual(const Ipv4Config& given) {
  Ipv4Config config;
  if (!net::IsUsableUnicast(given.address)) return config;
  config.address = given.address;
  config.netmask = net::IsContiguousMask(given.netmask) ? given.netmask : ClassfulMask(given.address);
  const std::uint32_t mask = config.netmask.HostOrder();
  const bool gateway_on_link = (given.gateway.HostOrder() & mask) == (config.address.HostOrder() & mask);
  config.gateway = !given.gateway.IsUnspecified() && gateway_on_link ? given.gateway : base::Ipv4Address();
  return config;
}

}  // namespace

AddressingPlan PlanFromConfig(const config::CardConfig& config) {
  AddressingPlan plan;
  plan.mode = config.ip_mode;
  plan.manual = {config.ip, config.netmask, config.gateway};
  plan.host_name = config.device_name;
  return plan;
}

base::Ipv4Address ClassfulMask(base::Ipv4Address address) {
  const std::uint8_t first = address.octets()[0];
  if ((first >> 7) == 0) return base::Ipv4Address(255, 0, 0, 0);       // class A
  if ((first >> 6) == 0b10) return base::Ipv4Address(255, 255, 0, 0);  // class B
  return base::Ipv4Address(255, 255, 255, 0);                          // class C
}

const char* AddressPhaseName(AddressPhase phase) {
  switch (phase) {
    case AddressPhase::kNotConfigured:
      return "none";
    case AddressPhase::kAcquiring:
      return "acquiring";
    case AddressPhase::kProbing:
      return "probing";
    case AddressPhase::kInUse:
      return "in-use";
    case AddressPhase::kConflict:
      return "conflict";
  }
  return "?";
}

CardAddressing::CardAddressing(CardNetif& netif, const hal::Clock& clock, hal::RandomSource& random)
    : netif_(netif),
      clock_(clock),
      acd_(netif.port().Mac(), net::kEtherNetIpTimings, random, *this),
      bootp_(netif.port().Mac(), random) {}

CardAddressing::~CardAddressing() {
  StopAll();
  if (netif_dhcp_data(&netif_.lwip_netif()) == &dhcp_) dhcp_remove_struct(&netif_.lwip_netif());
}

base::Status CardAddressing::Configure(const config::CardConfig& config) {
  const AddressingPlan plan = PlanFromConfig(config);
  if (configured_ && plan == plan_) return base::OkStatus();
  plan_ = plan;
  configured_ = true;
  ++counters_.restarts;
  Restart(clock_.NowMicros());
  return base::OkStatus();
}

void CardAddressing::StopAll() {
  if (dhcp_running_) {
    dhcp_release_and_stop(&netif_.lwip_netif());
    dhcp_running_ = false;
  }
  dhcp_restart_at_ = hal::kNever;
  bootp_.Stop();
  if (bootp_pcb_ != nullptr) {
    udp_remove(bootp_pcb_);
    bootp_pcb_ = nullptr;
  }
  acd_.Stop();
  target_set_ = false;
  Uninstall();
}

void CardAddressing::Restart(hal::Micros now) {
  StopAll();
  acd_enabled_ = acd_selected_;
  acd_ran_ = false;
  netif& nif = netif_.lwip_netif();
  // The device name is the DHCP host name (and client identifier); an empty one sends neither.
  netif_set_hostname(&nif, plan_.host_name[0] != '\0' ? plan_.host_name.data() : nullptr);
  switch (plan_.mode) {
    case config::IpMode::kManual: {
      const Ipv4Config manual = UsableManual(plan_.manual);
      if (!manual.address.IsUnspecified()) UseAddress(manual, now);
      break;
    }
    case config::IpMode::kBootp:
      StartBootp(now);
      break;
    case config::IpMode::kDhcp:
      dhcp_restart_at_ = now;  // started from Poll, like a restart after a conflict
      break;
  }
}

void CardAddressing::UseAddress(const Ipv4Config& config, hal::Micros now) {
  target_ = config;
  target_set_ = true;
  if (acd_enabled_) {
    acd_.Start(config.address, now);
    acd_ran_ = true;
  }
  PollManualOrBootp();
}

void CardAddressing::Install(const Ipv4Config& config) {
  if (active() == config) return;
  const ip4_addr_t address = ToLwip(config.address);
  const ip4_addr_t netmask = ToLwip(config.netmask);
  const ip4_addr_t gateway = ToLwip(config.gateway);
  netif_set_addr(&netif_.lwip_netif(), &address, &netmask, &gateway);
  ++counters_.address_changes;
}

void CardAddressing::Uninstall() { Install(Ipv4Config{}); }

Ipv4Config CardAddressing::active() const {
  netif& nif = netif_.lwip_netif();
  return {FromLwip(netif_ip4_addr(&nif)), FromLwip(netif_ip4_netmask(&nif)), FromLwip(netif_ip4_gw(&nif))};
}

AddressPhase CardAddressing::phase() const {
  if (!configured_) return AddressPhase::kNotConfigured;
  if (has_address()) return AddressPhase::kInUse;
  if (target_set_ && acd_enabled_) {
    return acd_.State() == net::AcdState::kConflict ? AddressPhase::kConflict : AddressPhase::kProbing;
  }
  if (plan_.mode == config::IpMode::kManual) return AddressPhase::kNotConfigured;
  return AddressPhase::kAcquiring;
}

void CardAddressing::Poll(hal::Micros now) {
  if (!configured_) return;
  if (plan_.mode == config::IpMode::kDhcp) {
    PollDhcp(now);
    return;
  }
  if (plan_.mode == config::IpMode::kBootp) PollBootp(now);
  if (target_set_ && acd_enabled_) acd_.Poll(now);
  PollManualOrBootp();
}

hal::Micros CardAddressing::NextDeadline() const {
  hal::Micros deadline = dhcp_restart_at_;
  if (target_set_ && acd_enabled_) deadline = std::min(deadline, acd_.NextDeadline());
  if (bootp_.state() == net::BootpClient::State::kRequesting) deadline = std::min(deadline, bootp_.NextDeadline());
  return deadline;
}

// Manual and BOOTP: the address is in lwIP exactly while ACD allows it (or at once without ACD).
void CardAddressing::PollManualOrBootp() {
  if (target_set_ && (!acd_enabled_ || acd_.AddressUsable())) {
    Install(target_);
  } else {
    Uninstall();
  }
}

void CardAddressing::StartBootp(hal::Micros now) {
  bootp_.Start(now);
  PollBootp(now);
}

void CardAddressing::PollBootp(hal::Micros now) {
  if (bootp_.state() == net::BootpClient::State::kBound) {
    if (bootp_pcb_ != nullptr) {  // BOOTP has no lease to renew: the PCB is not needed any more
      udp_remove(bootp_pcb_);
      bootp_pcb_ = nullptr;
    }
    if (!target_set_) {
      const net::BootReply& lease = bootp_.Lease();
      Ipv4Config config{lease.your_address, lease.subnet_mask.value_or(base::Ipv4Address()),
                        lease.router.value_or(base::Ipv4Address())};
      UseAddress(UsableManual(config), now);
    }
    return;
  }
  if (bootp_.state() != net::BootpClient::State::kRequesting) return;
  if (bootp_pcb_ == nullptr) {
    // No PCB free: the request waits for the next poll (the retransmission timer keeps running).
    bootp_pcb_ = udp_new();
    if (bootp_pcb_ == nullptr) return;
    ip_set_option(bootp_pcb_, SOF_BROADCAST);
    if (udp_bind(bootp_pcb_, IP4_ADDR_ANY, net::kBootpClientPort) != ERR_OK) {
      udp_remove(bootp_pcb_);
      bootp_pcb_ = nullptr;
      return;
    }
    udp_recv(bootp_pcb_, &CardAddressing::BootpReceived, this);
  }
  std::array<std::uint8_t, net::kBootpMessageSize> request;
  const std::size_t size = bootp_.Poll(now, request);
  if (size == 0) return;
  pbuf* p = pbuf_alloc(PBUF_TRANSPORT, static_cast<u16_t>(size), PBUF_RAM);
  if (p == nullptr) return;  // lost like a frame on the wire: the next retransmission comes anyway
  pbuf_take(p, request.data(), static_cast<u16_t>(size));
  // From 0.0.0.0 to the limited broadcast, as lwIP's DHCP client sends before it has an address.
  if (udp_sendto_if_src(bootp_pcb_, p, IP_ADDR_BROADCAST, net::kBootpServerPort, &netif_.lwip_netif(),
                        IP4_ADDR_ANY) == ERR_OK) {
    ++counters_.bootp_requests;
  }
  pbuf_free(p);
}

void CardAddressing::BootpReceived(void* arg, udp_pcb* /*pcb*/, pbuf* p, const ip_addr_t* /*address*/,
                                   u16_t port) {
  auto* self = static_cast<CardAddressing*>(arg);
  std::array<std::uint8_t, kMaxBootReply> reply;
  const u16_t length = pbuf_copy_partial(p, reply.data(), static_cast<u16_t>(std::min<std::size_t>(p->tot_len, reply.size())), 0);
  pbuf_free(p);
  const bool from_server = port == net::kBootpServerPort;
  if (from_server && self->bootp_.OnReply(std::span<const std::uint8_t>(reply.data(), length)).ok()) {
    ++self->counters_.bootp_replies;
  } else {
    ++self->counters_.bootp_ignored;
  }
}

void CardAddressing::PollDhcp(hal::Micros now) {
  netif& nif = netif_.lwip_netif();
  if (!dhcp_running_ && now >= dhcp_restart_at_) {
    if (netif_dhcp_data(&nif) == nullptr) dhcp_set_struct(&nif, &dhcp_);
    if (dhcp_start(&nif) != ERR_OK) {
      dhcp_restart_at_ = now + kDhcpRestartDelay;  // no PCB: try again later
      return;
    }
    dhcp_running_ = true;
    dhcp_restart_at_ = hal::kNever;
  }
  if (!dhcp_running_) return;
  if (dhcp_supplied_address(&nif) != 0) {
    const Ipv4Config leased = active();
    if (!target_set_ || target_.address != leased.address) {
      target_ = leased;
      target_set_ = true;
      if (acd_enabled_) {
        acd_.Claim(leased.address, now);
        acd_ran_ = true;
      }
    }
  } else if (target_set_) {
    // The lease ended (not renewed): lwIP removed the address and looks for a new one.
    target_set_ = false;
    acd_.Stop();
  }
  if (!target_set_ || !acd_enabled_) return;
  acd_.Poll(now);
  if (acd_.State() == net::AcdState::kConflict) {
    // A second conflict in DEFEND_INTERVAL: give the lease back and ask again later.
    dhcp_release_and_stop(&nif);
    dhcp_running_ = false;
    acd_.Stop();
    target_set_ = false;
    dhcp_restart_at_ = now + kDhcpRestartDelay;
    ++counters_.dhcp_restarts;
  }
}

void CardAddressing::OnFrameToCard(std::span<const std::uint8_t> frame) {
  if (!target_set_ || !acd_enabled_) return;
  const hal::Micros now = clock_.NowMicros();
  const net::AcdEvent event = acd_.OnFrame(frame, now);
  if (event == net::AcdEvent::kNone) return;
  ++counters_.acd_conflicts;
  // A yielded address leaves lwIP before lwIP reads this very frame (RFC 5227 §2.4: stop using it at
  // once); otherwise lwIP would still answer the other host's ARP for it.
  if (event == net::AcdEvent::kYielded) Poll(now);
}

void CardAddressing::OnPortLinkUp(hal::PortId /*port*/) {
  if (target_set_ && acd_enabled_) acd_.LinkUp(clock_.NowMicros());
}

void CardAddressing::SendArp(std::span<const std::uint8_t, net::kArpFrameSize> frame) {
  if (netif_.SendFrame(frame)) ++counters_.acd_frames_sent;
}

}  // namespace firmware
