// The firmware's CIP providers (firmware/cip_providers.h) and the parameter writer behind them, against
// the register proxy and the real simulated inverter (register_proxy_fixture.h): what a Set of a TCP/IP
// or Ethernet Link attribute stores in the inverter, what the card's own store keeps, and the Identity
// status inputs.
#include "cip_providers.h"

#include <gtest/gtest.h>

#include <map>
#include <vector>

#include "card_addressing_harness.h"
#include "base/byte_reader.h"
#include "base/byte_writer.h"
#include "cip/tcpip_interface_object.h"
#include "fake_frame_port.h"
#include "lwip_fixture.h"
#include "memory_nv_store.h"
#include "parameter_writer.h"
#include "register_proxy_fixture.h"

namespace firmware {
namespace {

using drive_link::test::kMilli;
using drive_link::test::kSecond;

using hal::test::MemoryNvStore;

constexpr base::MacAddress kMac = {0x00, 0x80, 0xF4, 0x7D, 0x02, 0xC0};

class CipProvidersTest : public drive_link::test::RegisterProxyFixture {
 protected:
  CipProvidersTest() { hal::test::EnsureLwipInitialised(); }

  void StartCard() {
    StartLoaded();
    writer_ = std::make_unique<ParameterWriter>(*proxy_);
    identity_ = std::make_unique<CardIdentity>(port_, *proxy_);
    tcpip_ = std::make_unique<CardTcpIp>(netif_, addressing_, *writer_, store_);
    links_ = std::make_unique<CardEthernetLinks>(netif_, *writer_);
    ASSERT_TRUE(tcpip_->Configure(proxy_->config()).ok());
    ASSERT_TRUE(links_->Configure(proxy_->config()).ok());
  }

  // Runs the writer with the proxy and the inverter until its queue is empty (at most 5 s).
  void DrainWriter() {
    const hal::Micros end = Now() + 5 * kSecond;
    while (writer_->pending() > 0 && Now() < end) {
      writer_->Poll(Now());
      RunFor(2 * kMilli);
    }
    EXPECT_EQ(writer_->pending(), 0u);
  }

  hal::test::FakeFramePort port_{kMac, 2};
  CardNetif netif_{port_};
  hal::test::CountingRandom random_;
  CardAddressing addressing_{netif_, clock_, random_};
  MemoryNvStore store_;
  std::unique_ptr<ParameterWriter> writer_;
  std::unique_ptr<CardIdentity> identity_;
  std::unique_ptr<CardTcpIp> tcpip_;
  std::unique_ptr<CardEthernetLinks> links_;
};

TEST_F(CipProvidersTest, StoredSettings_ReadFromTheInvertersParameters) {
  SetEeprom({{0xC504, 0}, {0xC505, 192}, {0xC506, 168}, {0xC507, 0}, {0xC508, 10}, {0xC509, 255},
             {0xC510, 255}, {0xC511, 255}, {0xC512, 0}, {0xC081, 'V'}, {0xC082, 'F'}});
  StartCard();
  const cip::TcpIpSettings stored = tcpip_->StoredSettings();
  EXPECT_EQ(stored.startup, cip::StartupConfiguration::kStored);
  EXPECT_EQ(stored.static_configuration.ip_address, 0xC0A8000Au);
  EXPECT_EQ(stored.static_configuration.network_mask, 0xFFFFFF00u);
  EXPECT_EQ(std::string(stored.host_name.bytes().begin(), stored.host_name.bytes().end()), "VF");
}

TEST_F(CipProvidersTest, StoreInterfaceConfiguration_WritesC504ToC516InDecimalTitles) {
  StartCard();
  cip::TcpIpSettings settings = tcpip_->StoredSettings();
  settings.startup = cip::StartupConfiguration::kDhcp;
  settings.static_configuration.ip_address = 0xC0A8010C;    // 192.168.1.12
  settings.static_configuration.network_mask = 0xFFFF0000;  // 255.255.0.0
  settings.static_configuration.gateway = 0xC0A80101;       // 192.168.1.1
  ASSERT_TRUE(tcpip_->StoreSettings(settings).ok());
  EXPECT_EQ(tcpip_->StoredSettings(), settings);  // read back at once, before the inverter has it
  DrainWriter();
  EXPECT_EQ(Reg(0xC504), 2);
  EXPECT_EQ(Reg(0xC505), 192);
  EXPECT_EQ(Reg(0xC506), 168);
  EXPECT_EQ(Reg(0xC507), 1);
  EXPECT_EQ(Reg(0xC508), 12);
  EXPECT_EQ(Reg(0xC509), 255);
  EXPECT_EQ(Reg(0xC510), 255);  // c510 follows c509: the titles count in decimal
  EXPECT_EQ(Reg(0xC511), 0);
  EXPECT_EQ(Reg(0xC512), 0);
  EXPECT_EQ(Reg(0xC513), 192);
  EXPECT_EQ(Reg(0xC516), 1);
  EXPECT_EQ(writer_->counters().failed, 0u);
}

TEST_F(CipProvidersTest, StoreHostName_OneCharacterPerParameterZeroAfterTheEnd) {
  SetEeprom({{0xC081, 'O'}, {0xC082, 'L'}, {0xC083, 'D'}, {0xC084, 'N'}, {0xC085, 'A'}, {0xC086, 'M'},
             {0xC087, 'E'}, {0xC088, 'X'}, {0xC089, 'Y'}, {0xC090, 'Z'}});
  StartCard();
  cip::TcpIpSettings settings = tcpip_->StoredSettings();
  ASSERT_TRUE(settings.host_name.Assign(std::string_view("PUMP-7")));
  ASSERT_TRUE(tcpip_->StoreSettings(settings).ok());
  DrainWriter();
  const std::vector<std::uint16_t> expected = {'P', 'U', 'M', 'P', '-', '7', 0, 0, 0, 0, 0, 0, 0, 0, 0, 0};
  const std::vector<std::uint16_t> numbers = {0xC081, 0xC082, 0xC083, 0xC084, 0xC085, 0xC086, 0xC087, 0xC088,
                                              0xC089, 0xC090, 0xC091, 0xC092, 0xC093, 0xC094, 0xC095, 0xC096};
  for (std::size_t i = 0; i < numbers.size(); ++i) EXPECT_EQ(Reg(numbers[i]), expected[i]) << std::hex << numbers[i];
}

TEST_F(CipProvidersTest, StoreUnchangedSettings_WritesNothing) {
  StartCard();
  const std::uint64_t before = proxy_->counters().accesses;
  ASSERT_TRUE(tcpip_->StoreSettings(tcpip_->StoredSettings()).ok());
  EXPECT_EQ(writer_->pending(), 0u);
  DrainWriter();
  EXPECT_EQ(proxy_->counters().accesses, before);
  EXPECT_EQ(store_.writes, 1);  // the card's record once (it did not exist)
  ASSERT_TRUE(tcpip_->StoreSettings(tcpip_->StoredSettings()).ok());
  EXPECT_EQ(store_.writes, 1);  // unchanged: not written again
}

TEST_F(CipProvidersTest, HostNameWithControlCharacter_InvalidArgumentNothingStored) {
  StartCard();
  cip::TcpIpSettings settings = tcpip_->StoredSettings();
  ASSERT_TRUE(settings.host_name.Assign(std::string_view("A\x01")));
  settings.ttl = 5;
  EXPECT_EQ(tcpip_->StoreSettings(settings).code(), base::StatusCode::kInvalidArgument);
  EXPECT_EQ(writer_->pending(), 0u);
  EXPECT_EQ(tcpip_->StoredSettings().ttl, 1);
  EXPECT_TRUE(store_.records.empty());
}

TEST_F(CipProvidersTest, ExtrasKeptInTheCardsStoreAcrossARestart) {
  StartCard();
  cip::TcpIpSettings settings = tcpip_->StoredSettings();
  settings.ttl = 16;
  settings.select_acd = false;
  settings.multicast = {1, 8, 0xEFC00120};
  settings.static_configuration.name_server = 0x0A000001;
  settings.static_configuration.name_server_2 = 0x0A000002;
  ASSERT_TRUE(settings.static_configuration.domain_name.Assign(std::string_view("plant.example")));
  ASSERT_TRUE(tcpip_->StoreSettings(settings).ok());
  CardTcpIp restarted(netif_, addressing_, *writer_, store_);
  ASSERT_TRUE(restarted.Configure(proxy_->config()).ok());
  EXPECT_EQ(restarted.StoredSettings(), settings);
}

TEST_F(CipProvidersTest, DamagedExtrasRecord_Defaults) {
  store_.records[kNvTcpIpExtras] = {0x01, 0x10};  // cut short
  StartCard();
  EXPECT_EQ(tcpip_->StoredSettings().ttl, 1);
  EXPECT_TRUE(tcpip_->StoredSettings().select_acd);
}

TEST_F(CipProvidersTest, DriveLinkDown_StoreRefused) {
  Start();  // the configuration is not read yet
  writer_ = std::make_unique<ParameterWriter>(*proxy_);
  CardTcpIp tcpip(netif_, addressing_, *writer_, store_);
  cip::TcpIpSettings settings = tcpip.StoredSettings();
  settings.startup = cip::StartupConfiguration::kBootp;
  EXPECT_EQ(tcpip.StoreSettings(settings).code(), base::StatusCode::kFailedPrecondition);
  EXPECT_EQ(tcpip.StoredSettings().startup, cip::StartupConfiguration::kStored);
}

TEST_F(CipProvidersTest, WriterQueueFull_StoreRefusedCardsRecordUnchanged) {
  StartCard();
  ASSERT_TRUE(tcpip_->StoreSettings(tcpip_->StoredSettings()).ok());  // the record with the defaults
  const std::vector<std::uint8_t> record = store_.records.at(kNvTcpIpExtras);
  std::vector<ParameterValue> filler;
  for (unsigned title = 1; title <= ParameterWriter::kMaxQueued; ++title) {
    filler.push_back({drive_link::reg::CParameter(title), 0});
  }
  ASSERT_TRUE(writer_->Enqueue(filler).ok());
  cip::TcpIpSettings settings = tcpip_->StoredSettings();
  settings.ttl = 9;
  settings.startup = cip::StartupConfiguration::kDhcp;
  EXPECT_EQ(tcpip_->StoreSettings(settings).code(), base::StatusCode::kResourceExhausted);
  EXPECT_EQ(store_.records.at(kNvTcpIpExtras), record);
  EXPECT_EQ(tcpip_->StoredSettings().ttl, 1);
  EXPECT_EQ(tcpip_->StoredSettings().startup, cip::StartupConfiguration::kStored);
}

TEST_F(CipProvidersTest, ParameterWriter_QueueFull_NothingQueued) {
  StartCard();
  std::vector<ParameterValue> many;
  for (std::uint16_t i = 0; i < ParameterWriter::kMaxQueued + 1; ++i) many.push_back({0xC081, i});
  // Repeats of one number take one slot.
  EXPECT_TRUE(writer_->Enqueue(many).ok());
  EXPECT_EQ(writer_->pending(), 1u);
  std::vector<ParameterValue> distinct;
  for (unsigned title = 1; title <= ParameterWriter::kMaxQueued; ++title) {
    distinct.push_back({drive_link::reg::CParameter(title), 0});
  }
  EXPECT_EQ(writer_->Enqueue(distinct).code(), base::StatusCode::kResourceExhausted);
  EXPECT_EQ(writer_->pending(), 1u);
  EXPECT_EQ(writer_->queue_pool(), (base::PoolStats{1, ParameterWriter::kMaxQueued, 1, 1}));
  distinct.pop_back();  // 31 new ones and the one queued: exactly full
  EXPECT_TRUE(writer_->Enqueue(distinct).ok());
  constexpr std::size_t kMax = ParameterWriter::kMaxQueued;
  EXPECT_EQ(writer_->queue_pool(), (base::PoolStats{kMax, kMax, kMax, 1}));
  DrainWriter();
  EXPECT_EQ(writer_->queue_pool(), (base::PoolStats{0, kMax, kMax, 1}));
}

TEST_F(CipProvidersTest, ParameterWriter_RefusedWriteCountedQueueGoesOn) {
  StartCard();
  const std::vector<ParameterValue> writes = {{0xC504, 9}, {0xC505, 172}};  // c504 is 0-2
  ASSERT_TRUE(writer_->Enqueue(writes).ok());
  DrainWriter();
  EXPECT_EQ(writer_->counters().failed, 1u);
  EXPECT_EQ(writer_->counters().last_error, drive_link::AccessError::kOutOfRange);
  EXPECT_EQ(writer_->counters().written, 1u);
  EXPECT_EQ(Reg(0xC505), 172);
}

TEST_F(CipProvidersTest, LinkSetting_StoredInC501) {
  StartCard();
  EXPECT_EQ(links_->StoredSetting(), cip::LinkSetting::kAuto);
  ASSERT_TRUE(links_->StoreSetting(cip::LinkSetting::k10Half).ok());
  EXPECT_EQ(links_->StoredSetting(), cip::LinkSetting::k10Half);
  DrainWriter();
  EXPECT_EQ(Reg(0xC501), 2);
}

TEST_F(CipProvidersTest, LinkState_PerPortFromTheFramePort) {
  StartCard();
  port_.SetLink(hal::PortId::kRight, false);
  const cip::LinkState left = links_->State(cip::LinkPort::kLeft);
  EXPECT_TRUE(left.up);
  EXPECT_EQ(left.speed_mbps, 100u);
  EXPECT_TRUE(left.full_duplex);
  EXPECT_EQ(left.negotiation, cip::NegotiationStatus::kNegotiated);
  const cip::LinkState right = links_->State(cip::LinkPort::kRight);
  EXPECT_FALSE(right.up);
  EXPECT_EQ(right.speed_mbps, 0u);
}

TEST_F(CipProvidersTest, Counters_ByDestinationKindAndClearedByBaseline) {
  StartCard();
  netif_.Start(Ipv4Config{base::Ipv4Address(0xC0A8010C), base::Ipv4Address(0xFFFFFF00), {}}, "card");
  std::vector<std::uint8_t> unicast(60, 0);
  std::copy(kMac.begin(), kMac.end(), unicast.begin());
  std::vector<std::uint8_t> broadcast(60, 0xFF);
  port_.Inject(unicast, hal::PortId::kLeft);
  port_.Inject(broadcast, hal::PortId::kLeft);
  port_.Inject(broadcast, hal::PortId::kRight);
  netif_.PumpReceive(8);
  EXPECT_EQ(links_->Counters(cip::LinkPort::kLeft).in_ucast_packets, 1u);
  EXPECT_EQ(links_->Counters(cip::LinkPort::kLeft).in_nucast_packets, 1u);
  EXPECT_EQ(links_->Counters(cip::LinkPort::kRight).in_nucast_packets, 1u);
  links_->ClearCounters(cip::LinkPort::kLeft);
  EXPECT_EQ(links_->Counters(cip::LinkPort::kLeft).in_ucast_packets, 0u);
  EXPECT_EQ(links_->Counters(cip::LinkPort::kLeft).in_nucast_packets, 0u);
  EXPECT_EQ(links_->Counters(cip::LinkPort::kRight).in_nucast_packets, 1u);  // the other port keeps its own
  port_.Inject(broadcast, hal::PortId::kLeft);
  netif_.PumpReceive(8);
  EXPECT_EQ(links_->Counters(cip::LinkPort::kLeft).in_nucast_packets, 1u);
}

TEST_F(CipProvidersTest, Identity_DefaultsNotConfiguredNoIoConnections) {
  StartCard();
  const cip::DeviceStatus status = identity_->Status();
  EXPECT_FALSE(status.configured);
  EXPECT_FALSE(status.minor_recoverable_fault);
  EXPECT_FALSE(status.major_recoverable_fault);
  EXPECT_EQ(status.extended, cip::ExtendedDeviceStatus::kNoIoConnections);
  EXPECT_EQ(identity_->Mac(), kMac);
  EXPECT_EQ(identity_->Model(), cip::DriveModel::kVfMb1);
}

TEST_F(CipProvidersTest, Identity_ScannerMappingChangedIsConfigured) {
  SetEeprom({{0xC001, 2}});
  StartCard();
  EXPECT_TRUE(identity_->Status().configured);
}

TEST_F(CipProvidersTest, Identity_ReservedMenuIsAMinorRecoverableFault) {
  SetEeprom({{0xC001, 4}});  // menu 4 is "-" in the manual: replaced by the default and reported
  StartCard();
  EXPECT_TRUE(identity_->Status().minor_recoverable_fault);
}

TEST_F(CipProvidersTest, Identity_DriveModelFromFb05) {
  StartCard();
  identity_->OnDriveIdentity(0x09, 0x0110);
  EXPECT_EQ(identity_->Model(), cip::DriveModel::kVfS15);
  identity_->OnDriveIdentity(0x04, 0x0110);
  EXPECT_EQ(identity_->Model(), cip::DriveModel::kVfMb1);
}

// ---- CardTcpIp: status bit 6 and attribute 11 from the card's ACD ----------------------------------

class CardTcpIpAcdTest : public CipProvidersTest {
 protected:
  CardTcpIpAcdTest() {
    netif_.Start(Ipv4Config{}, nullptr);
    netif_.SetObserver(&addressing_);
  }
  ~CardTcpIpAcdTest() override { netif_.SetObserver(nullptr); }

  // Polls the addressing at its deadlines up to `duration` from now on the fixture's clock (ACD's time
  // base here).
  void RunAddressing(hal::Micros duration) {
    const hal::Micros end = Now() + duration;
    for (int i = 0; i < 1000 && addressing_.NextDeadline() <= end; ++i) {
      clock_.Set(std::max(Now(), addressing_.NextDeadline()));
      netif_.PumpReceive(8);
      addressing_.Poll(Now());
    }
    clock_.Set(end);
    netif_.PumpReceive(8);
    addressing_.Poll(Now());
  }
  void Receive(const std::vector<std::uint8_t>& frame) {
    port_.Inject(frame);
    netif_.PumpReceive(8);
    addressing_.Poll(Now());
  }
  std::vector<std::uint8_t> Attribute(std::uint16_t id) {
    cip::TcpIpInterfaceObject object(*tcpip_);
    std::array<std::uint8_t, 64> buffer{};
    base::ByteWriter out(buffer);
    object.GetInstanceAttribute(1, id, out);
    EXPECT_TRUE(out.ok());
    return {out.written().begin(), out.written().end()};
  }

  void StartAndClaim() {
    StartCard();
    ASSERT_TRUE(addressing_.Configure(test::ManualConfig({192, 168, 1, 12}, {255, 255, 255, 0})).ok());
    RunAddressing(1100 * kMilli);
    ASSERT_TRUE(addressing_.has_address());
  }
};

constexpr base::MacAddress kIntruder = {0x02, 0x12, 0x34, 0x56, 0x78, 0x9A};

// The intruder's gratuitous ARP for 192.168.1.12, and the 28-byte ARP PDU inside it.
std::vector<std::uint8_t> IntruderAnnouncement() {
  return test::ArpFrameBytes(1, base::kBroadcastMac, kIntruder, kIntruder, 0xC0A8010C, base::kZeroMac, 0xC0A8010C);
}
const std::vector<std::uint8_t> kIntruderPdu = {0x00, 0x01, 0x08, 0x00, 0x06, 0x04, 0x00, 0x01,        // request
                                                0x02, 0x12, 0x34, 0x56, 0x78, 0x9A, 192,  168, 1, 12,  // sender
                                                0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 192,  168, 1, 12};

TEST_F(CardTcpIpAcdTest, NoConflict_StatusBit6ClearAttribute11Zero) {
  StartAndClaim();
  EXPECT_FALSE(tcpip_->AddressConflictDetected());
  EXPECT_EQ(Attribute(1), (std::vector<std::uint8_t>{0x01, 0x00, 0x00, 0x00}));  // valid configuration
  EXPECT_EQ(Attribute(11), std::vector<std::uint8_t>(35, 0));
}

TEST_F(CardTcpIpAcdTest, YieldedInUse_Bit6AndAttribute11Exact_ClearedBySet) {
  StartAndClaim();
  RunAddressing(5 * kSecond);
  Receive(IntruderAnnouncement());  // defended: a conflict is recorded, the address kept
  EXPECT_FALSE(tcpip_->AddressConflictDetected());
  EXPECT_EQ(Attribute(1), (std::vector<std::uint8_t>{0x01, 0x00, 0x00, 0x00}));
  RunAddressing(2 * kSecond);
  Receive(IntruderAnnouncement());  // yielded
  ASSERT_FALSE(addressing_.has_address());
  EXPECT_TRUE(tcpip_->AddressConflictDetected());
  // Bit 6 (address conflict); bits 0-3 are 0: no valid configuration in use.
  EXPECT_EQ(Attribute(1), (std::vector<std::uint8_t>{0x40, 0x00, 0x00, 0x00}));

  const cip::AcdConflict conflict = tcpip_->LastConflict();
  EXPECT_EQ(conflict.acd_activity, 2);  // OngoingDetection
  EXPECT_EQ(conflict.remote_mac, kIntruder);
  EXPECT_EQ(std::vector<std::uint8_t>(conflict.arp_pdu.begin(), conflict.arp_pdu.end()), kIntruderPdu);
  std::vector<std::uint8_t> expected = {0x02, 0x02, 0x12, 0x34, 0x56, 0x78, 0x9A};
  expected.insert(expected.end(), kIntruderPdu.begin(), kIntruderPdu.end());
  ASSERT_EQ(expected.size(), 35u);
  EXPECT_EQ(Attribute(11), expected);

  // Set_Attribute_Single 11 with 35 zeros clears the record; the conflict itself (bit 6) stays until
  // the address is claimed again.
  cip::TcpIpInterfaceObject object(*tcpip_);
  const std::vector<std::uint8_t> zeros(35, 0);
  base::ByteReader value(zeros);
  EXPECT_TRUE(object.SetInstanceAttribute(1, 11, value).ok());
  EXPECT_EQ(Attribute(11), zeros);
  EXPECT_EQ(addressing_.last_conflict(), net::AcdConflictRecord{});
  EXPECT_TRUE(tcpip_->AddressConflictDetected());

  // A minute later ACD probes again; the intruder has gone: the address is back and bit 6 clear.
  RunAddressing(61 * kSecond);
  EXPECT_TRUE(addressing_.has_address());
  EXPECT_FALSE(tcpip_->AddressConflictDetected());
  EXPECT_EQ(Attribute(1), (std::vector<std::uint8_t>{0x01, 0x00, 0x00, 0x00}));
}

TEST_F(CardTcpIpAcdTest, ConflictWhileProbing_Activity1_ClearLastConflict) {
  StartCard();
  ASSERT_TRUE(addressing_.Configure(test::ManualConfig({192, 168, 1, 12}, {255, 255, 255, 0})).ok());
  RunAddressing(300 * kMilli);
  Receive(IntruderAnnouncement());
  EXPECT_TRUE(tcpip_->AddressConflictDetected());
  EXPECT_EQ(Attribute(1), (std::vector<std::uint8_t>{0x40, 0x00, 0x00, 0x00}));
  const std::vector<std::uint8_t> attribute = Attribute(11);
  ASSERT_EQ(attribute.size(), 35u);
  EXPECT_EQ(attribute[0], 1);  // ProbeIpv4Address
  EXPECT_EQ(std::vector<std::uint8_t>(attribute.begin() + 1, attribute.begin() + 7),
            std::vector<std::uint8_t>(kIntruder.begin(), kIntruder.end()));
  EXPECT_EQ(std::vector<std::uint8_t>(attribute.begin() + 7, attribute.end()), kIntruderPdu);
  tcpip_->ClearLastConflict();
  EXPECT_EQ(tcpip_->LastConflict().acd_activity, 0);
  EXPECT_EQ(tcpip_->LastConflict().remote_mac, base::MacAddress{});
  EXPECT_EQ(tcpip_->LastConflict().arp_pdu, (std::array<std::uint8_t, 28>{}));
  EXPECT_EQ(Attribute(11), std::vector<std::uint8_t>(35, 0));
}

}  // namespace
}  // namespace firmware
