// Fakes of the providers the CIP objects read from and store to, with the values the tests expect.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "cip/cip_device.h"
#include "cip/providers.h"
#include "cip_test_support.h"
#include "hal/reset.h"

namespace cip::test {

class FakeDeviceInfo final : public DeviceInfoProvider {
 public:
  base::MacAddress Mac() const override { return mac; }
  DriveModel Model() const override { return model; }
  DeviceStatus Status() const override { return status; }

  base::MacAddress mac = {0x00, 0x80, 0xF4, 0x7D, 0x02, 0xC0};  // the manual's example MAC (§10.1)
  DriveModel model = DriveModel::kVfMb1;
  DeviceStatus status;
};

class FakeTcpIp final : public TcpIpProvider {
 public:
  FakeTcpIp() {
    active.ip_address = 0x0A00020F;  // 10.0.2.15
    active.network_mask = 0xFFFFFF00;
    active.gateway = 0x0A000202;
  }
  InterfaceConfiguration ActiveConfiguration() const override { return active; }
  bool ConfigurationValid() const override { return valid; }
  bool AddressConflictDetected() const override { return conflict_detected; }
  AcdConflict LastConflict() const override { return last_conflict; }
  void ClearLastConflict() override {
    last_conflict = AcdConflict{};
    ++clears;
  }
  TcpIpSettings StoredSettings() const override { return stored; }
  base::Status StoreSettings(const TcpIpSettings& settings) override {
    ++stores;
    if (store_result.ok()) stored = settings;
    return store_result;
  }

  InterfaceConfiguration active;
  bool valid = true;
  bool conflict_detected = false;
  AcdConflict last_conflict;
  TcpIpSettings stored;
  base::Status store_result;
  int stores = 0;
  int clears = 0;
};

class FakeLinks final : public EthernetLinkProvider {
 public:
  LinkState State(LinkPort port) const override { return state[Index(port)]; }
  InterfaceCounters Counters(LinkPort port) const override { return counters[Index(port)]; }
  MediaCounters Media(LinkPort port) const override { return media[Index(port)]; }
  void ClearCounters(LinkPort port) override { counters[Index(port)] = InterfaceCounters{}; }
  void ClearMedia(LinkPort port) override { media[Index(port)] = MediaCounters{}; }
  LinkSetting StoredSetting() const override { return setting; }
  base::Status StoreSetting(LinkSetting value) override {
    if (store_result.ok()) setting = value;
    return store_result;
  }

  static std::size_t Index(LinkPort port) { return static_cast<std::size_t>(port); }

  std::array<LinkState, 2> state{};
  std::array<InterfaceCounters, 2> counters{};
  std::array<MediaCounters, 2> media{};
  LinkSetting setting = LinkSetting::kAuto;
  base::Status store_result;
};

// The QoS object's store (not part of FakeCard: a test registers a QosObject on it).
class FakeQos final : public QosProvider {
 public:
  QosSettings StoredQos() const override { return stored; }
  base::Status StoreQos(const QosSettings& settings) override {
    if (!store_result.ok()) return store_result;
    stored = settings;
    ++stores;
    return base::OkStatus();
  }

  QosSettings stored;
  base::Status store_result;
  int stores = 0;
};

class FakeReset final : public hal::ResetControl {
 public:
  void RequestReset(hal::ResetKind kind) override { requests.push_back(kind); }
  std::vector<hal::ResetKind> requests;
};

// A CipDevice on fakes, and a way to ask its message router.
struct FakeCard {
  FakeDeviceInfo device;
  FakeTcpIp tcpip;
  FakeLinks links;
  FakeReset reset;
  ScriptedRandom random;
  CipDevice cip{DeviceProviders{device, tcpip, links, reset, random}};

  Bytes Ask(const Bytes& request) {
    std::vector<std::uint8_t> reply(kMaxEncapsulationData);
    RequestContext context;
    reply.resize(cip.router().HandleUnconnected(request, context, reply));
    return reply;
  }
};

}  // namespace cip::test
