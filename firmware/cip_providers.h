// The card's implementations of the CIP provider interfaces (cip/providers.h): what the Identity,
// TCP/IP Interface and Ethernet Link objects show and store. docs/ethernetip.md "In the firmware".
//
// - CardIdentity: the MAC, the drive model (from the inverter's model code FB05, read at each
//   configuration load) and the Identity status word inputs.
// - CardTcpIp: the address in use (lwIP's netif) and the stored settings: c504-c516 and the device name
//   c081-c096 in the inverter (written through ParameterWriter), TTL, multicast, SelectAcd, name servers
//   and domain name in the card's own store. Stored settings take effect after a reset (§3.2.2).
// - CardEthernetLinks: per port link state and counters (the frame port and CardNetif), Get_and_Clear
//   by baselines, and c501 as the stored interface control.
//
// Device-path code: no allocation; the composition root owns every object referenced here.
#pragma once

#include <array>
#include <cstdint>

#include "card_addressing.h"
#include "card_netif.h"
#include "cip/providers.h"
#include "cip/io_connection.h"
#include "configurable_service.h"
#include "io_service.h"
#include "drive_link/register_proxy.h"
#include "hal/nv_store.h"
#include "parameter_writer.h"

namespace firmware {

// The card's NV record holding the TCP/IP settings that have no c-parameter.
inline constexpr hal::NvRecordId kNvTcpIpExtras = 0x0010;

class CardIdentity final : public cip::DeviceInfoProvider, public DriveIdentitySink {
 public:
  CardIdentity(hal::FramePort& port, const drive_link::RegisterProxy& proxy) : port_(port), proxy_(proxy) {}

  // FB05 as read from the inverter: 0x09 is a VF-S15, anything else is shown as a VF-MB1 (the
  // default until the code is read; docs/ethernetip.md).
  void OnDriveIdentity(std::uint16_t fb05, std::uint16_t fe08) override;
  // The CIP connections, for the I/O bits of the status word (none: "no I/O connections").
  void set_connections(const cip::ConnectionTable* connections) { connections_ = connections; }

  base::MacAddress Mac() const override;
  cip::DriveModel Model() const override { return model_; }
  cip::DeviceStatus Status() const override;

  static constexpr std::uint16_t kVfS15ModelCode = 0x09;

 private:
  hal::FramePort& port_;
  const drive_link::RegisterProxy& proxy_;
  const cip::ConnectionTable* connections_ = nullptr;
  cip::DriveModel model_ = cip::DriveModel::kVfMb1;
};

class CardTcpIp final : public cip::TcpIpProvider,
                        public cip::MulticastAddressProvider,
                        public MulticastTtlSource,
                        public ConfigurableService {
 public:
  CardTcpIp(CardNetif& netif, CardAddressing& addressing, ParameterWriter& writer, hal::NvStore& store);

  // The inverter's part of the stored settings, from each configuration load.
  base::Status Configure(const config::CardConfig& config) override;

  cip::InterfaceConfiguration ActiveConfiguration() const override;
  bool ConfigurationValid() const override;
  // Status bit 6 and attribute 11 come from the card's ACD (docs/network.md "Address Conflict Detection").
  bool AddressConflictDetected() const override { return addressing_.duplicate_detected(); }
  cip::AcdConflict LastConflict() const override;
  void ClearLastConflict() override { addressing_.ClearLastConflict(); }
  cip::TcpIpSettings StoredSettings() const override { return settings_; }
  base::Status StoreSettings(const cip::TcpIpSettings& settings) override;

  // Multicast productions (TCP/IP attributes 8 and 9): docs/ethernetip.md "Multicast".
  std::uint32_t MulticastGroup(std::size_t index) const override;
  std::uint8_t MulticastTtl() const override { return settings_.ttl; }

 private:
  void LoadExtras();
  base::Status SaveExtras(const cip::TcpIpSettings& settings);

  CardNetif& netif_;
  CardAddressing& addressing_;
  ParameterWriter& writer_;
  hal::NvStore& store_;
  cip::TcpIpSettings settings_;
};

class CardEthernetLinks final : public cip::EthernetLinkProvider, public ConfigurableService {
 public:
  CardEthernetLinks(CardNetif& netif, ParameterWriter& writer) : netif_(netif), writer_(writer) {}

  // c501, from each configuration load.
  base::Status Configure(const config::CardConfig& config) override;

  cip::LinkState State(cip::LinkPort port) const override;
  cip::InterfaceCounters Counters(cip::LinkPort port) const override;
  cip::MediaCounters Media(cip::LinkPort port) const override;
  void ClearCounters(cip::LinkPort port) override;
  void ClearMedia(cip::LinkPort /*port*/) override {}  // the ports have no media counters: all stay 0
  cip::LinkSetting StoredSetting() const override { return setting_; }
  base::Status StoreSetting(cip::LinkSetting setting) override;

 private:
  cip::InterfaceCounters Raw(cip::LinkPort port) const;

  CardNetif& netif_;
  ParameterWriter& writer_;
  cip::LinkSetting setting_ = cip::LinkSetting::kAuto;
  std::array<cip::InterfaceCounters, hal::kMaxPorts> baseline_{};
};

}  // namespace firmware
