// What the power-cut tests of the card's NV records share (nv_record_power_cut_test.cc on files,
// flash_nv_record_power_cut_test.cc on flash): a random source whose draws a test can predict, and the
// owner of the TCP/IP extras record with the loaded inverter configuration it needs.
#pragma once

#include <gtest/gtest.h>

#include <cstdint>
#include <memory>
#include <span>

#include "card_records.h"
#include "cip_providers.h"
#include "fake_frame_port.h"
#include "hal/nv_store.h"
#include "hal/random.h"
#include "lwip_fixture.h"
#include "parameter_writer.h"
#include "register_proxy_fixture.h"

namespace firmware::test {

// Fills with a counter, so every draw differs and a test can say what the next one is.
class CountingRandom final : public hal::RandomSource {
 public:
  void Fill(std::span<std::uint8_t> out) override {
    for (std::uint8_t& byte : out) byte = next_++;
  }
  std::uint8_t next_ = 0x40;
};

// The MAC record's power-cut check: the first start makes and keeps a MAC from CountingRandom's first
// draw (42:41:42:43:44:45). After a cut, a start must find that MAC when the record was committed
// (`new_expected`), or else make its own from another draw (92:91:...) and keep that.
inline void MacFirstStart(hal::NvStore& store) {
  CountingRandom random;
  LoadOrCreateMac(store, random);
}
inline void ExpectMacAfterRestart(hal::NvStore& store, bool new_expected) {
  CountingRandom random;
  random.next_ = 0x90;  // another draw than the interrupted start's
  const base::MacAddress mac = LoadOrCreateMac(store, random);
  const base::MacAddress expected = new_expected ? base::MacAddress{0x42, 0x41, 0x42, 0x43, 0x44, 0x45}
                                                : base::MacAddress{0x92, 0x91, 0x92, 0x93, 0x94, 0x95};
  EXPECT_EQ(mac, expected);
  CountingRandom unused;
  EXPECT_EQ(LoadOrCreateMac(store, unused), expected);  // and the next start keeps it
}

// The TCP/IP extras belong to CardTcpIp, which needs a loaded configuration from the inverter. A test
// calls StartLoaded() and then MakeWriter() before its first CardTcpIp.
class TcpIpExtrasFixture : public drive_link::test::RegisterProxyFixture {
 protected:
  TcpIpExtrasFixture() { hal::test::EnsureLwipInitialised(); }

  void MakeWriter() { writer_ = std::make_unique<ParameterWriter>(*proxy_); }

  // The settings a CardTcpIp started on `store` holds.
  cip::TcpIpSettings Restarted(hal::NvStore& store) {
    CardTcpIp tcpip(netif_, addressing_, *writer_, store);
    EXPECT_TRUE(tcpip.Configure(proxy_->config()).ok());
    return tcpip.StoredSettings();
  }

  hal::test::FakeFramePort port_{base::MacAddress{0x02, 0, 0, 0, 0, 1}, 2};
  CardNetif netif_{port_};
  CountingRandom random_;
  CardAddressing addressing_{netif_, clock_, random_};
  std::unique_ptr<ParameterWriter> writer_;
};

}  // namespace firmware::test
