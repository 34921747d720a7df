#include "cip_providers.h"

#include <algorithm>

#include "base/byte_reader.h"
#include "base/byte_writer.h"
#include "drive_link/drive_registers.h"
#include "ipv4_lwip.h"
#include "lwip/netif.h"

namespace firmware {
namespace {

namespace reg = drive_link::reg;

constexpr std::uint8_t kExtrasVersion = 1;
// version, ttl, select_acd, allocation control, num_mcast, start, name servers, domain length + name
constexpr std::size_t kExtrasMaxBytes = 1 + 1 + 1 + 1 + 2 + 4 + 4 + 4 + 1 + cip::kMaxDomainName;

std::uint8_t Octet(std::uint32_t address, int index) {
  return static_cast<std::uint8_t>(address >> (24 - 8 * index));
}

// c081-c096 hold printable ASCII (seed 000 §3.2.1); the card reads 0 as the end of the name.
bool IsDeviceNameCharacter(std::uint8_t c) { return c >= 0x20 && c <= 0x7E; }

// The application settings of the card (not its communication settings): the scanner mapping and the
// loss reaction. "Configured" (Identity status bit 2) means one differs from the out-of-box default.
bool ApplicationConfigured(const config::CardConfig& config) {
  const config::CardConfig defaults;
  return config.command_menus != defaults.command_menus || config.monitor_menus != defaults.monitor_menus ||
         config.loss_delay_tenths != defaults.loss_delay_tenths || config.loss_action != defaults.loss_action ||
         config.loss_preset_speed != defaults.loss_preset_speed ||
         config.loss_condition != defaults.loss_condition;
}

}  // namespace

// ---- CardIdentity -----------------------------------------------------------------------------------

base::MacAddress CardIdentity::Mac() const { return port_.Mac(); }

void CardIdentity::OnDriveIdentity(std::uint16_t fb05, std::uint16_t fe08) {
  static_cast<void>(fe08);  // the Identity revision is the card's (§4.1: 1.8), not the drive's CPU version
  model_ = fb05 == kVfS15ModelCode ? cip::DriveModel::kVfS15 : cip::DriveModel::kVfMb1;
}

cip::DeviceStatus CardIdentity::Status() const {
  cip::DeviceStatus status;
  const bool loaded = proxy_.config_loaded();
  status.configured = loaded && ApplicationConfigured(proxy_.config());
  // A configuration value the card replaced by its default: the card runs, but not as set.
  status.minor_recoverable_fault = loaded && proxy_.parsed_config().problems_total > 0;
  // The drive unreachable (e-23) or tripped: the device cannot do its job until that is cleared.
  const bool link_fault = proxy_.link().state() == drive_link::LinkState::kFault;
  const bool tripped = proxy_.drive_status_known() && (proxy_.drive_status() & reg::status_bit::kTripped) != 0;
  status.major_recoverable_fault = link_fault || tripped;
  status.extended = status.major_recoverable_fault ? cip::ExtendedDeviceStatus::kMajorFault
                   : connections_ != nullptr       ? connections_->IoStatus()
                                                   : cip::ExtendedDeviceStatus::kNoIoConnections;
  return status;
}

// ---- CardTcpIp --------------------------------------------------------------------------------------

CardTcpIp::CardTcpIp(CardNetif& netif, CardAddressing& addressing, ParameterWriter& writer, hal::NvStore& store)
    : netif_(netif), addressing_(addressing), writer_(writer), store_(store) {
  LoadExtras();
}

cip::AcdConflict CardTcpIp::LastConflict() const {
  const net::AcdConflictRecord& record = addressing_.last_conflict();
  cip::AcdConflict conflict;
  conflict.acd_activity = static_cast<std::uint8_t>(record.activity);
  conflict.remote_mac = record.remote_mac;
  conflict.arp_pdu = record.arp_pdu;
  return conflict;
}

base::Status CardTcpIp::Configure(const config::CardConfig& config) {
  settings_.startup = static_cast<cip::StartupConfiguration>(config.ip_mode);
  settings_.static_configuration.ip_address = config.ip.HostOrder();
  settings_.static_configuration.network_mask = config.netmask.HostOrder();
  settings_.static_configuration.gateway = config.gateway.HostOrder();
  const std::string_view name(config.device_name.data());
  // c081-c096 hold at most 16 characters, exactly the attribute's capacity.
  static_cast<void>(settings_.host_name.Assign(name.substr(0, cip::kMaxHostName)));
  return base::OkStatus();
}

cip::InterfaceConfiguration CardTcpIp::ActiveConfiguration() const {
  netif& nif = netif_.lwip_netif();
  cip::InterfaceConfiguration active;
  active.ip_address = FromLwip(netif_ip4_addr(&nif)).HostOrder();
  active.network_mask = FromLwip(netif_ip4_netmask(&nif)).HostOrder();
  active.gateway = FromLwip(netif_ip4_gw(&nif)).HostOrder();
  // The card has no DNS client: the name servers and domain in use are the stored ones.
  active.name_server = settings_.static_configuration.name_server;
  active.name_server_2 = settings_.static_configuration.name_server_2;
  active.domain_name = settings_.static_configuration.domain_name;
  return active;
}

// CIP Vol. 2 §3-5.3: with allocation control 0 each device takes a block of 32 groups from 239.192.1.0,
// chosen by its host ID so that devices of one subnet do not share groups; with 1, the configured range.
std::uint32_t CardTcpIp::MulticastGroup(std::size_t index) const {
  const cip::MulticastConfiguration& multicast = settings_.multicast;
  if (multicast.allocation_control == 1) {
    return index < multicast.num_mcast ? multicast.start_address + static_cast<std::uint32_t>(index) : 0;
  }
  constexpr std::uint32_t kBase = 0xEFC00100;  // 239.192.1.0
  constexpr std::uint32_t kGroupsPerDevice = 32;
  if (index >= kGroupsPerDevice) return 0;
  const netif& nif = netif_.lwip_netif();
  const std::uint32_t host_id =
      FromLwip(netif_ip4_addr(&nif)).HostOrder() & ~FromLwip(netif_ip4_netmask(&nif)).HostOrder();
  return kBase + ((host_id - 1U) & 0x3FFU) * kGroupsPerDevice + static_cast<std::uint32_t>(index);
}

bool CardTcpIp::ConfigurationValid() const { return !FromLwip(netif_ip4_addr(&netif_.lwip_netif())).IsUnspecified(); }

base::Status CardTcpIp::StoreSettings(const cip::TcpIpSettings& settings) {
  for (const std::uint8_t c : settings.host_name.bytes()) {
    if (!IsDeviceNameCharacter(c)) return base::InvalidArgument();
  }
  // The inverter's part: only what changed, all in one request (stored completely or not at all).
  std::array<ParameterValue, ParameterWriter::kMaxQueued> writes{};
  std::size_t count = 0;
  const auto add = [&](std::uint16_t number, std::uint16_t value, std::uint16_t old_value) {
    if (value != old_value) writes[count++] = {number, value};
  };
  add(reg::kC504, static_cast<std::uint16_t>(settings.startup), static_cast<std::uint16_t>(settings_.startup));
  const cip::InterfaceConfiguration& now = settings.static_configuration;
  const cip::InterfaceConfiguration& old = settings_.static_configuration;
  const std::array<std::uint32_t, 3> new_addresses{now.ip_address, now.network_mask, now.gateway};
  const std::array<std::uint32_t, 3> old_addresses{old.ip_address, old.network_mask, old.gateway};
  for (unsigned a = 0; a < 3; ++a) {
    for (int i = 0; i < 4; ++i) {
      add(reg::CParameter(505 + 4 * a + static_cast<unsigned>(i)), Octet(new_addresses[a], i),
          Octet(old_addresses[a], i));
    }
  }
  for (unsigned i = 0; i < cip::kMaxHostName; ++i) {
    const std::uint8_t c = i < settings.host_name.size() ? settings.host_name.bytes()[i] : 0;
    const std::uint8_t was = i < settings_.host_name.size() ? settings_.host_name.bytes()[i] : 0;
    add(reg::CParameter(81 + i), c, was);
  }
  // The card's record first: it can fail and be put back, a queued write cannot be taken back.
  if (base::Status saved = SaveExtras(settings); !saved.ok()) return saved;
  if (count > 0) {
    if (base::Status queued = writer_.Enqueue(std::span<const ParameterValue>(writes.data(), count)); !queued.ok()) {
      SaveExtras(settings_).IgnoreError();  // back to what Get still reads; the refusal is the answer
      return queued;
    }
  }
  settings_ = settings;
  return base::OkStatus();
}

void CardTcpIp::LoadExtras() {
  std::array<std::uint8_t, kExtrasMaxBytes> record{};
  const base::Result<std::size_t> read = store_.Read(kNvTcpIpExtras, record);
  if (!read.ok()) return;  // never written, or damaged: the defaults
  base::ByteReader in(std::span<const std::uint8_t>(record.data(), *read));
  if (in.U8() != kExtrasVersion) return;
  cip::TcpIpSettings loaded = settings_;
  loaded.ttl = in.U8();
  loaded.select_acd = in.U8() != 0;
  loaded.multicast.allocation_control = in.U8();
  loaded.multicast.num_mcast = in.U16Le();
  loaded.multicast.start_address = in.U32Le();
  loaded.static_configuration.name_server = in.U32Le();
  loaded.static_configuration.name_server_2 = in.U32Le();
  const std::uint8_t domain_length = in.U8();
  const std::span<const std::uint8_t> domain = in.Bytes(domain_length);
  if (!in.ok() || !loaded.static_configuration.domain_name.Assign(domain)) return;
  settings_ = loaded;
}

base::Status CardTcpIp::SaveExtras(const cip::TcpIpSettings& settings) {
  std::array<std::uint8_t, kExtrasMaxBytes> record{};
  base::ByteWriter out(record);
  out.U8(kExtrasVersion);
  out.U8(settings.ttl);
  out.U8(settings.select_acd ? 1 : 0);
  out.U8(settings.multicast.allocation_control);
  out.U16Le(settings.multicast.num_mcast);
  out.U32Le(settings.multicast.start_address);
  out.U32Le(settings.static_configuration.name_server);
  out.U32Le(settings.static_configuration.name_server_2);
  const std::span<const std::uint8_t> domain = settings.static_configuration.domain_name.bytes();
  out.U8(static_cast<std::uint8_t>(domain.size()));
  out.Bytes(domain);
  if (!out.ok()) return base::Internal();
  // Unchanged extras are not written again (the store wears).
  std::array<std::uint8_t, kExtrasMaxBytes> stored{};
  const base::Result<std::size_t> read = store_.Read(kNvTcpIpExtras, stored);
  if (read.ok() && *read == out.size() && std::equal(record.begin(), record.begin() + out.size(), stored.begin())) {
    return base::OkStatus();
  }
  return store_.Write(kNvTcpIpExtras, std::span<const std::uint8_t>(record.data(), out.size()));
}

// ---- CardEthernetLinks ------------------------------------------------------------------------------

base::Status CardEthernetLinks::Configure(const config::CardConfig& config) {
  setting_ = static_cast<cip::LinkSetting>(config.rate_setting);
  return base::OkStatus();
}

cip::LinkState CardEthernetLinks::State(cip::LinkPort port) const {
  hal::FramePort& frames = netif_.port();
  const auto id = static_cast<hal::PortId>(port);
  cip::LinkState state;
  if (static_cast<std::size_t>(port) >= frames.PortCount()) return state;
  const hal::LinkState link = frames.Link(id);
  state.up = link.up;
  if (!link.up) return state;
  if (link.speed == hal::LinkSpeed::kNone) {
    // A host TAP or loopback port has no speed: show what the card negotiates with a switch.
    state.speed_mbps = 100;
    state.full_duplex = true;
    state.negotiation = cip::NegotiationStatus::kNegotiated;
    return state;
  }
  state.speed_mbps = static_cast<std::uint32_t>(link.speed);
  state.full_duplex = link.full_duplex;
  state.negotiation = link.auto_negotiated ? cip::NegotiationStatus::kNegotiated : cip::NegotiationStatus::kForced;
  return state;
}

cip::InterfaceCounters CardEthernetLinks::Raw(cip::LinkPort port) const {
  cip::InterfaceCounters counters;
  hal::FramePort& frames = netif_.port();
  if (static_cast<std::size_t>(port) >= frames.PortCount()) return counters;
  const auto id = static_cast<hal::PortId>(port);
  const hal::PortCounters hw = frames.Counters(id);
  const PortTraffic& traffic = netif_.traffic(id);
  // The attribute's counters are 32 bits wide and wrap, as on any device.
  counters.in_octets = static_cast<std::uint32_t>(hw.rx_octets);
  counters.in_ucast_packets = static_cast<std::uint32_t>(traffic.in_ucast);
  counters.in_nucast_packets = static_cast<std::uint32_t>(traffic.in_nucast);
  counters.in_discards = static_cast<std::uint32_t>(traffic.in_discards);
  counters.in_errors = static_cast<std::uint32_t>(hw.rx_errors);
  counters.out_octets = static_cast<std::uint32_t>(hw.tx_octets);
  counters.out_ucast_packets = static_cast<std::uint32_t>(traffic.out_ucast);
  counters.out_nucast_packets = static_cast<std::uint32_t>(traffic.out_nucast);
  counters.out_discards = static_cast<std::uint32_t>(traffic.out_discards);
  return counters;
}

cip::InterfaceCounters CardEthernetLinks::Counters(cip::LinkPort port) const {
  const cip::InterfaceCounters raw = Raw(port);
  const cip::InterfaceCounters& base = baseline_[static_cast<std::size_t>(port)];
  cip::InterfaceCounters c;
  c.in_octets = raw.in_octets - base.in_octets;
  c.in_ucast_packets = raw.in_ucast_packets - base.in_ucast_packets;
  c.in_nucast_packets = raw.in_nucast_packets - base.in_nucast_packets;
  c.in_discards = raw.in_discards - base.in_discards;
  c.in_errors = raw.in_errors - base.in_errors;
  c.in_unknown_protos = raw.in_unknown_protos - base.in_unknown_protos;
  c.out_octets = raw.out_octets - base.out_octets;
  c.out_ucast_packets = raw.out_ucast_packets - base.out_ucast_packets;
  c.out_nucast_packets = raw.out_nucast_packets - base.out_nucast_packets;
  c.out_discards = raw.out_discards - base.out_discards;
  c.out_errors = raw.out_errors - base.out_errors;
  return c;
}

cip::MediaCounters CardEthernetLinks::Media(cip::LinkPort port) const {
  static_cast<void>(port);
  return {};
}

void CardEthernetLinks::ClearCounters(cip::LinkPort port) {
  baseline_[static_cast<std::size_t>(port)] = Raw(port);
}

base::Status CardEthernetLinks::StoreSetting(cip::LinkSetting setting) {
  if (setting == setting_) return base::OkStatus();
  const ParameterValue write{reg::kC501, static_cast<std::uint16_t>(setting)};
  if (base::Status queued = writer_.Enqueue(std::span<const ParameterValue>(&write, 1)); !queued.ok()) return queued;
  setting_ = setting;
  return base::OkStatus();
}

}  // namespace firmware
