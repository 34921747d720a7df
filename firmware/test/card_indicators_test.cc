// CardIndicators: MS, NS and LNK L/R from the card's real sources (the register proxy against the
// simulated inverter, CardAddressing on lwIP and a fake two-port frame port, a fake connection table),
// sampled at exact instants: the power-up test on all four LEDs, then the §2.4 rows for both protocols.
#include "card_indicators.h"

#include <gtest/gtest.h>

#include <memory>

#include "card_addressing_harness.h"
#include "register_proxy_fixture.h"

namespace firmware::test {
namespace {

using drive_link::test::kMilli;
using drive_link::test::kSecond;
using hal::Led;
using hal::LedColor;
using hal::PortId;

constexpr LedColor kOff = LedColor::kOff;
constexpr LedColor kGreen = LedColor::kGreen;
constexpr LedColor kRed = LedColor::kRed;
constexpr LedColor kYellow = LedColor::kYellow;

class FakeConnections final : public cip::ConnectionTable {
 public:
  std::size_t ListConnections(std::span<cip::ConnectionInfo> out) const override {
    return std::min(open, out.size());
  }
  bool IsOwned(std::uint32_t) const override { return false; }
  bool OwnedByAnotherOriginator(base::Ipv4Address) const override { return false; }
  cip::ExtendedDeviceStatus IoStatus() const override { return status; }

  std::size_t open = 0;
  cip::ExtendedDeviceStatus status = cip::ExtendedDeviceStatus::kNoIoConnections;
};

class RecordingLeds final : public hal::Leds {
 public:
  void Set(Led led, LedColor color) override { colors[hal::LedIndex(led)] = color; }
  std::array<LedColor, hal::kLedCount> colors{};
};

config::CardConfig ProtocolConfig(config::Protocol protocol) {
  config::CardConfig config;
  config.protocol = protocol;
  return config;
}

class CardIndicatorsTest : public drive_link::test::RegisterProxyFixture {
 protected:
  CardIndicatorsTest() {
    hal::test::EnsureLwipInitialised();
    netif_.Start(Ipv4Config{}, nullptr);
    netif_.SetObserver(&addressing_);
  }
  ~CardIndicatorsTest() override { netif_.SetObserver(nullptr); }

  // The indicators from now on (the power-up test starts now), for `protocol`.
  void Build(config::Protocol protocol) {
    start_ = Now();
    const IndicatorSources sources{port_, *proxy_, addressing_, &connections_};
    indicators_ = std::make_unique<CardIndicators>(sources, leds_, start_);
    ASSERT_TRUE(indicators_->Configure(ProtocolConfig(protocol)).ok());
    Step();
  }
  // A manual address in lwIP at once (ACD off).
  void GiveAddress() {
    addressing_.SetAcdEnabled(false);
    ASSERT_TRUE(addressing_.Configure(ManualConfig({192, 168, 1, 12}, {255, 255, 255, 0})).ok());
    ASSERT_TRUE(addressing_.has_address());
  }

  void Step() {
    netif_.SyncLinkState();
    netif_.PumpReceive(8);
    addressing_.Poll(Now());
    indicators_->Poll(Now());
  }
  // Polls at every deadline of the indicators and the addressing up to `t`, then at `t`.
  void AdvanceTo(hal::Micros t) {
    for (int i = 0; i < 10000; ++i) {
      const hal::Micros next = std::min(indicators_->NextDeadline(), addressing_.NextDeadline());
      if (next > t) break;
      if (next > Now()) clock_.Set(next);
      Step();
    }
    clock_.Set(t);
    Step();
  }
  LedColor At(Led led, hal::Micros t) {
    AdvanceTo(t);
    return leds_.colors[hal::LedIndex(led)];
  }
  LedColor Color(Led led) const { return leds_.colors[hal::LedIndex(led)]; }

  // The instant the power-up test ends: patterns start here.
  hal::Micros TestEnd() const { return start_ + net::kPowerUpTestDuration; }

  // Checks `led` against "flashing N times" from `origin`: N x (200 ms on, 200 ms off), 800 ms more off.
  void ExpectCountedFlashes(Led led, hal::Micros origin, int n, LedColor color) {
    for (int k = 0; k < n; ++k) {
      const hal::Micros on = origin + k * 400 * kMilli;
      EXPECT_EQ(At(led, on), color) << "flash " << k;
      EXPECT_EQ(At(led, on + 199 * kMilli), color) << "flash " << k;
      EXPECT_EQ(At(led, on + 200 * kMilli), kOff) << "flash " << k;
    }
    const hal::Micros period = n * 400 * kMilli + 800 * kMilli;
    EXPECT_EQ(At(led, origin + period - 1), kOff);
    EXPECT_EQ(At(led, origin + period), color) << "the next group";
  }

  hal::test::FakeFramePort port_{kCardMac, 2};
  CardNetif netif_{port_};
  hal::test::CountingRandom random_;
  CardAddressing addressing_{netif_, clock_, random_};
  FakeConnections connections_;
  RecordingLeds leds_;
  std::unique_ptr<CardIndicators> indicators_;
  hal::Micros start_ = 0;
};

TEST_F(CardIndicatorsTest, PowerUpTestOnAllFourLeds_ThenModbusReadyAndLinkColours) {
  StartLoaded();
  GiveAddress();
  port_.SetSpeed(PortId::kRight, hal::LinkSpeed::k10Mbps);
  Build(config::Protocol::kModbusTcp);

  struct Sample {
    hal::Micros at;
    LedColor ms, ns, lnk;
  };
  // 0.25 s steps: MS green, MS red (NS off), then NS green, NS red with MS green; LNK green, red, off.
  const Sample steps[] = {{0, kGreen, kOff, kGreen},
                        {249 * kMilli, kGreen, kOff, kGreen},
                        {250 * kMilli, kRed, kOff, kRed},
                        {500 * kMilli, kGreen, kGreen, kOff},
                        {750 * kMilli, kGreen, kRed, kOff},
                        {999 * kMilli, kGreen, kRed, kOff}};
  for (const Sample& step : steps) {
    SCOPED_TRACE(step.at);
    AdvanceTo(start_ + step.at);
    EXPECT_EQ(Color(Led::kModuleStatus), step.ms);
    EXPECT_EQ(Color(Led::kNetworkStatus), step.ns);
    EXPECT_EQ(Color(Led::kLinkLeft), step.lnk);
    EXPECT_EQ(Color(Led::kLinkRight), step.lnk);
  }

  // Then the inputs: Modbus TCP ready (MS green), a port linked with an address (NS green), LNK green at
  // 100 Mbit/s and yellow at 10 Mbit/s.
  AdvanceTo(TestEnd());
  EXPECT_EQ(Color(Led::kModuleStatus), kGreen);
  EXPECT_EQ(Color(Led::kNetworkStatus), kGreen);
  EXPECT_EQ(Color(Led::kLinkLeft), kGreen);
  EXPECT_EQ(Color(Led::kLinkRight), kYellow);
  EXPECT_EQ(indicators_->NextDeadline(), hal::kNever);  // all steady
  AdvanceTo(TestEnd() + 5 * kSecond);
  EXPECT_EQ(Color(Led::kNetworkStatus), kGreen);

  // A cable out: its LNK goes off; both out: Modbus NS "flashing 3 times", MS green flashing.
  port_.SetLink(PortId::kLeft, false);
  EXPECT_EQ(At(Led::kLinkLeft, Now()), kOff);
  EXPECT_EQ(Color(Led::kNetworkStatus), kGreen);
  port_.SetLink(PortId::kRight, false);
  const hal::Micros unplugged = Now() + 1;
  AdvanceTo(unplugged);
  EXPECT_EQ(Color(Led::kLinkRight), kOff);
  ExpectCountedFlashes(Led::kNetworkStatus, unplugged, 3, kGreen);
}

TEST_F(CardIndicatorsTest, EtherNetIpNotConfigured_MsGreenFlashing_NsOffWithoutAddress) {
  Start();  // the configuration has not been read from the inverter yet
  Build(config::Protocol::kEtherNetIp);
  const net::LedInputs in = indicators_->Gather();
  EXPECT_FALSE(in.configured);
  EXPECT_FALSE(in.has_address);
  EXPECT_EQ(in.protocol, net::Protocol::kEtherNetIp);
  EXPECT_EQ(At(Led::kModuleStatus, TestEnd()), kGreen);
  EXPECT_EQ(At(Led::kModuleStatus, TestEnd() + 499 * kMilli), kGreen);
  EXPECT_EQ(At(Led::kModuleStatus, TestEnd() + 500 * kMilli), kOff);
  EXPECT_EQ(At(Led::kModuleStatus, TestEnd() + 1000 * kMilli), kGreen);
  EXPECT_EQ(Color(Led::kNetworkStatus), kOff);
}

TEST_F(CardIndicatorsTest, ModbusNotReadyWithAddress_MsGreenFlashing) {
  Start();
  GiveAddress();
  Build(config::Protocol::kModbusTcp);
  EXPECT_EQ(At(Led::kModuleStatus, TestEnd() + 100 * kMilli), kGreen);
  EXPECT_EQ(At(Led::kModuleStatus, TestEnd() + 600 * kMilli), kOff);
  EXPECT_EQ(At(Led::kNetworkStatus, TestEnd() + 600 * kMilli), kGreen);
}

TEST_F(CardIndicatorsTest, BootpRunning_ModbusNsFlashesFiveTimes_EtherNetIpNsOff) {
  StartLoaded();
  ASSERT_TRUE(addressing_.Configure(ModeConfig(config::IpMode::kBootp)).ok());
  Build(config::Protocol::kModbusTcp);
  EXPECT_TRUE(indicators_->Gather().acquiring_address);
  ExpectCountedFlashes(Led::kNetworkStatus, TestEnd(), 5, kGreen);  // period 2.8 s
  EXPECT_EQ(Color(Led::kModuleStatus), kOff);                         // Modbus MS: no address

  // The same condition under EtherNet/IP: NS off (no address), MS green (configured).
  ASSERT_TRUE(indicators_->Configure(ProtocolConfig(config::Protocol::kEtherNetIp)).ok());
  AdvanceTo(Now() + 1);
  EXPECT_EQ(Color(Led::kNetworkStatus), kOff);
  EXPECT_EQ(Color(Led::kModuleStatus), kGreen);
}

class DuplicateIndicatorsTest : public CardIndicatorsTest {
 protected:
  // Manual address with ACD; another host answers one of the probes during the power-up test.
  void ConflictDuringTest(config::Protocol protocol) {
    StartLoaded();
    ASSERT_TRUE(addressing_.Configure(ManualConfig({192, 168, 1, 12}, {255, 255, 255, 0})).ok());
    Build(protocol);
    AdvanceTo(start_ + 300 * kMilli);  // the first probe is out (PROBE_WAIT <= 200 ms)
    ASSERT_EQ(addressing_.phase(), AddressPhase::kProbing);
    port_.Inject(ArpFrameBytes(2, kCardMac, kOtherMac, kOtherMac, 0xC0A8010C, kCardMac, 0));
    Step();
    ASSERT_TRUE(addressing_.duplicate_detected());
    EXPECT_TRUE(indicators_->Gather().duplicate_address);
  }
};

TEST_F(DuplicateIndicatorsTest, Modbus_NsFlashesFourTimes) {
  ConflictDuringTest(config::Protocol::kModbusTcp);
  ExpectCountedFlashes(Led::kNetworkStatus, TestEnd(), 4, kGreen);  // period 2.4 s
}

TEST_F(DuplicateIndicatorsTest, EtherNetIp_NsRedSteady) {
  ConflictDuringTest(config::Protocol::kEtherNetIp);
  EXPECT_EQ(At(Led::kNetworkStatus, TestEnd()), kRed);
  EXPECT_EQ(At(Led::kNetworkStatus, TestEnd() + 3 * kSecond), kRed);
  EXPECT_EQ(Color(Led::kModuleStatus), kGreen);
}

TEST_F(CardIndicatorsTest, EtherNetIpConnections_NoneEstablishedTimedOut) {
  StartLoaded();
  GiveAddress();
  Build(config::Protocol::kEtherNetIp);
  // No connection: NS green flashing.
  EXPECT_EQ(At(Led::kNetworkStatus, TestEnd() + 100 * kMilli), kGreen);
  EXPECT_EQ(At(Led::kNetworkStatus, TestEnd() + 600 * kMilli), kOff);
  EXPECT_EQ(Color(Led::kModuleStatus), kGreen);

  // One established: green steady.
  connections_.open = 1;
  connections_.status = cip::ExtendedDeviceStatus::kIoConnectionInRunMode;
  EXPECT_EQ(At(Led::kNetworkStatus, Now() + 1), kGreen);
  EXPECT_EQ(At(Led::kNetworkStatus, Now() + 700 * kMilli), kGreen);
  EXPECT_EQ(indicators_->Gather().connections, net::ConnectionState::kEstablished);

  // The exclusive owner timed out: red flashing from that instant (red first).
  connections_.open = 0;
  connections_.status = cip::ExtendedDeviceStatus::kFaultedIoConnection;
  const hal::Micros timed_out = Now() + 1;
  EXPECT_EQ(At(Led::kNetworkStatus, timed_out), kRed);
  EXPECT_EQ(At(Led::kNetworkStatus, timed_out + 499 * kMilli), kRed);
  EXPECT_EQ(At(Led::kNetworkStatus, timed_out + 500 * kMilli), kOff);
  EXPECT_EQ(At(Led::kNetworkStatus, timed_out + 1000 * kMilli), kRed);
  EXPECT_EQ(Color(Led::kModuleStatus), kGreen);
}

}  // namespace
}  // namespace firmware::test
