#include "card_status_publisher.h"

#include "drive_link/drive_registers.h"
#include "ipv4_lwip.h"
#include "lwip/netif.h"

namespace firmware {
namespace {

// FB05 model codes of the drives the simulator models (registers.csv: the VF-S11 pattern, 2007 -> 04H,
// 2037 -> 09H). The VF-MB1/S15 code table is not in our sources; another code is shown as its number.
struct KnownDrive {
  std::uint16_t fb05;
  const char* product_code;
  const char* product_name;
};
constexpr KnownDrive kKnownDrives[] = {
    {0x04, "VFMB1S-2007PL", "VF-MB1"},
    {0x09, "VFS15-2037PM", "VF-S15"},
};

char HexDigit(unsigned value) { return "0123456789ABCDEF"[value & 0xF]; }

}  // namespace

std::uint16_t PortRateCode(const hal::LinkState& link) {
  if (!link.up) return 0;
  switch (link.speed) {
    case hal::LinkSpeed::k10Mbps:
      return link.full_duplex ? 1 : 2;
    case hal::LinkSpeed::k100Mbps:
      return link.full_duplex ? 3 : 4;
    default:
      return 3;
  }
}

DriveIdentity DescribeDrive(std::uint16_t fb05, std::uint16_t fe08) {
  DriveIdentity identity;
  char version[4] = {HexDigit(fe08 >> 12), HexDigit(fe08 >> 8), HexDigit(fe08 >> 4), HexDigit(fe08)};
  identity.version.Set(std::string_view(version, sizeof version));
  for (const KnownDrive& drive : kKnownDrives) {
    if (drive.fb05 == fb05) {
      identity.product_code.Set(drive.product_code);
      identity.product_name.Set(drive.product_name);
      return identity;
    }
  }
  char code[7] = {'F', 'B', '0', '5', '=', HexDigit(fb05 >> 4), HexDigit(fb05)};
  identity.product_code.Set(std::string_view(code, sizeof code));
  identity.product_name.Set("VF-MB1/S15");
  return identity;
}

CardStatusPublisher::CardStatusPublisher(drive_link::RegisterProxy& proxy, modbus::Server& modbus_server,
                                         std::span<ConfigurableService* const> front_ends, CardNetif& netif,
                                         std::uint16_t firmware_version, DriveIdentitySink* identity_sink)
    : proxy_(proxy), modbus_server_(modbus_server), netif_(netif), identity_sink_(identity_sink) {
  for (ConfigurableService* front_end : front_ends) {
    if (front_end != nullptr && front_end_count_ < front_ends_.size()) front_ends_[front_end_count_++] = front_end;
  }
  board_.firmware_version = firmware_version;
}

base::Status CardStatusPublisher::AddFrontEnd(ConfigurableService& front_end) {
  if (front_end_count_ == front_ends_.size()) return base::ResourceExhausted();
  front_ends_[front_end_count_++] = &front_end;
  return base::OkStatus();
}

void CardStatusPublisher::ConfigureFrontEnds(bool only_pending) {
  for (std::size_t i = 0; i < front_end_count_; ++i) {
    if (only_pending && !pending_[i]) continue;
    pending_[i] = !front_ends_[i]->Configure(config_).ok();  // no PCB free: retried at each publish
  }
}

config::CardStatus CardStatusPublisher::CurrentStatus() {
  config::CardStatus status;
  hal::FramePort& port = netif_.port();
  bool carrier = false;
  for (std::size_t i = 0; i < status.port_rates.size(); ++i) {
    if (i < port.PortCount()) status.port_rates[i] = PortRateCode(port.Link(static_cast<hal::PortId>(i)));
    carrier = carrier || status.port_rates[i] != 0;
  }
  // c536 = 3 "loss of carrier" while no port has link; the proxy shows the last event (a loss report of
  // the front ends may follow and replace it), and 0 again when a link comes back.
  status.ethernet_error = carrier ? 0 : 3;
  status.mac = port.Mac();
  netif& nif = netif_.lwip_netif();
  status.ip = FromLwip(netif_ip4_addr(&nif));
  status.netmask = FromLwip(netif_ip4_netmask(&nif));
  status.gateway = FromLwip(netif_ip4_gw(&nif));
  return status;
}

void CardStatusPublisher::Poll(hal::Micros now) {
  if (now < next_publish_) return;
  next_publish_ = now + kPublishInterval;
  config::CardStatus status = CurrentStatus();
  proxy_.SetCardStatus(status);
  status.ethernet_error = proxy_.ethernet_error();
  board_.status = status;
  board_.drive_link = proxy_.link().state();
  modbus_server_.SetBoardData(board_);
  ConfigureFrontEnds(/*only_pending=*/true);
  if (identity_wanted_ && identity_token_ == drive_link::kNoAccess) RequestIdentity();
}

void CardStatusPublisher::OnConfigLoaded(const config::ParsedConfig& parsed) {
  config_ = parsed.config;
  // Closing one protocol's ports first frees PCBs for the other's listeners: the order of the front
  // ends does not matter, a refusal is retried at the next publish.
  ConfigureFrontEnds(/*only_pending=*/false);
  identity_wanted_ = true;
  identity_step_ = 0;
  next_publish_ = 0;  // publish at once: the inverter was reset and shows nothing of the card yet
}

void CardStatusPublisher::RequestIdentity() {
  const std::uint16_t number = identity_step_ == 0 ? drive_link::reg::kFb05 : drive_link::reg::kFe08;
  const base::Result<drive_link::AccessToken> token = proxy_.Read(number, *this);
  if (token.ok()) identity_token_ = *token;  // otherwise busy or link down: the next publish retries
}

void CardStatusPublisher::OnAccessDone(drive_link::AccessToken token, const drive_link::AccessResult& result) {
  if (token != identity_token_) return;
  identity_token_ = drive_link::kNoAccess;
  if (!result.ok()) return;  // retried at the next publish
  if (identity_step_ == 0) {
    fb05_ = result.value;
    identity_step_ = 1;
    RequestIdentity();
    return;
  }
  const DriveIdentity identity = DescribeDrive(fb05_, result.value);
  board_.drive_product_code = identity.product_code;
  board_.drive_version = identity.version;
  board_.drive_product_name = identity.product_name;
  identity_wanted_ = false;
  modbus_server_.SetBoardData(board_);
  if (identity_sink_ != nullptr) identity_sink_->OnDriveIdentity(fb05_, result.value);
}

}  // namespace firmware
