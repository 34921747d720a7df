// Test harness for drive_link::RegisterProxy against the real simulated inverter: InverterModel +
// InverterProtocolServer on one end of a SocketSerialPort pair, the proxy on the other, both driven on a
// fake clock from deadline to deadline (no sleeping). The server reads a request in the same step the
// proxy writes it, so the modelled line timing (processing delay + reply bytes) is the only delay.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <initializer_list>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "drive_link/register_proxy.h"
#include "fake_clock.h"
#include "sim/inverter_model.h"
#include "sim/protocol_server.h"
#include "socket_serial_port.h"

namespace drive_link::test {

using hal::Micros;

inline constexpr Micros kMilli = hal::kMicrosPerMilli;
inline constexpr Micros kSecond = hal::kMicrosPerSecond;

// One register exchange with the default ServerConfig: 2 ms processing + a 7-byte reply at 19200 baud,
// 11 bits per character (ceil(7 x 11 / 19200 s) = 4011 us).
inline constexpr Micros kExchange = 2 * kMilli + 4011;

class RecordingListener final : public AccessListener {
 public:
  void OnAccessDone(AccessToken token, const AccessResult& result) override { done.emplace_back(token, result); }
  std::vector<std::pair<AccessToken, AccessResult>> done;
};

class ConfigRecorder final : public ConfigListener {
 public:
  void OnConfigLoaded(const config::ParsedConfig& parsed) override {
    loads.push_back(parsed);
    if (on_load) on_load();
  }
  std::vector<config::ParsedConfig> loads;
  std::function<void()> on_load;
};

class RegisterProxyFixture : public ::testing::Test {
 protected:
  static constexpr Micros kStart = 1000 * kSecond;

  RegisterProxyFixture() {
    auto pair = hal::host::SocketSerialPort::CreatePair();
    EXPECT_TRUE(pair.ok());
    if (pair.ok()) pair_ = std::move(pair.value());
  }

  // Puts values into the inverter's EEPROM image as if set before power-on (so the (*3) values and the
  // F870-F879 selections are in force). Values outside the table's static range are refused by the model.
  void SetEeprom(std::initializer_list<std::pair<std::uint16_t, int>> values) {
    std::string text = model_.SerializeEeprom();
    for (const auto& [number, value] : values) {
      char key[16];
      std::snprintf(key, sizeof key, "reg %04X ", static_cast<unsigned>(number));
      const std::size_t at = text.find(key);
      ASSERT_NE(at, std::string::npos) << std::hex << number;
      const std::size_t value_at = at + std::string(key).size();
      const std::size_t value_end = text.find(' ', value_at);
      text.replace(value_at, value_end - value_at, std::to_string(value));
    }
    ASSERT_TRUE(model_.LoadEeprom(text));
  }

  void Start(sim::ServerConfig server_config = {}, ProxyConfig proxy_config = {}, LinkConfig link_config = {}) {
    server_ = std::make_unique<sim::InverterProtocolServer>(model_, *pair_.inverter, clock_, server_config);
    proxy_ = std::make_unique<RegisterProxy>(*pair_.card, link_config, proxy_config);
    proxy_->SetConfigListener(&config_);
    server_->Poll(clock_.NowMicros());  // the model's time base: its power-on silence starts now
    ASSERT_TRUE(proxy_->Start(clock_.NowMicros()).ok());
  }

  // Start() and run until the configuration is loaded (at most 3 s).
  void StartLoaded(sim::ServerConfig server_config = {}, ProxyConfig proxy_config = {}) {
    Start(server_config, proxy_config);
    ASSERT_TRUE(RunUntilTrue([this] { return proxy_->config_loaded(); }, 3 * kSecond).has_value());
  }

  Micros Now() const { return clock_.NowMicros(); }

  void Step() {
    const Micros now = clock_.NowMicros();
    server_->Poll(now);
    proxy_->Poll(now);
    server_->Poll(now);  // takes what the proxy has just written: the request arrives now
  }

  // Runs both sides from deadline to deadline; after each step `stop` is asked (if given). Returns the
  // time at which it first said true, or nullopt when `end` came first. Fails the test when the loop asks
  // for the same instant over and over (a spin).
  std::optional<Micros> Run(Micros end, const std::function<bool()>& stop = nullptr) {
    int same_instant = 0;
    for (int i = 0; i < 2'000'000; ++i) {
      const Micros now = clock_.NowMicros();
      const Micros due = std::min(proxy_->NextDeadline(), server_->NextDeadline());
      Micros at = std::max(due, now);
      if (at > end) {
        if (now >= end) return std::nullopt;
        at = end;
      }
      same_instant = at == now ? same_instant + 1 : 0;
      if (same_instant > 200) {
        ADD_FAILURE() << "the proxy or the server asks for the same instant over and over at " << now;
        return std::nullopt;
      }
      clock_.Set(at);
      Step();
      if (stop && stop()) return clock_.NowMicros();
    }
    ADD_FAILURE() << "never reached " << end;
    return std::nullopt;
  }
  void RunUntil(Micros end) { Run(end); }
  void RunFor(Micros duration) { Run(clock_.NowMicros() + duration); }
  std::optional<Micros> RunUntilTrue(const std::function<bool()>& condition, Micros limit) {
    if (condition()) return clock_.NowMicros();
    return Run(clock_.NowMicros() + limit, condition);
  }

  std::uint16_t Reg(std::uint16_t number) const {
    const base::Result<std::uint16_t> value = model_.Read(number);
    EXPECT_TRUE(value.ok()) << std::hex << number;
    return value.ok() ? *value : 0xDEAD;
  }

  // One on-demand access, run to its completion (at most 5 s).
  AccessResult Access(const std::function<base::Result<AccessToken>(AccessListener&)>& start) {
    RecordingListener listener;
    const base::Result<AccessToken> token = start(listener);
    EXPECT_TRUE(token.ok());
    if (!token.ok()) return AccessResult{AccessError::kNone, 0xDEAD, 0xDEAD};
    EXPECT_TRUE(listener.done.empty()) << "delivered from inside Read/Write";
    RunUntilTrue([&listener] { return !listener.done.empty(); }, 5 * kSecond);
    proxy_->Cancel(listener);  // the listener goes out of scope: the proxy must forget it in any case
    if (listener.done.size() != 1) {
      ADD_FAILURE() << "expected one completion, got " << listener.done.size();
      return AccessResult{AccessError::kNone, 0xDEAD, 0xDEAD};
    }
    EXPECT_EQ(listener.done[0].first, *token);
    return listener.done[0].second;
  }
  AccessResult ReadNow(std::uint16_t number) {
    return Access([&](AccessListener& l) { return proxy_->Read(number, l); });
  }
  AccessResult WriteNow(std::uint16_t number, std::uint16_t value, WriteMode mode = WriteMode::kRamOnly) {
    return Access([&](AccessListener& l) { return proxy_->Write(number, value, mode, l); });
  }

  hal::test::FakeClock clock_{kStart};
  sim::InverterModel model_{sim::Model::kVfMb1};
  hal::host::SocketSerialPort::Pair pair_;
  std::unique_ptr<sim::InverterProtocolServer> server_;
  std::unique_ptr<RegisterProxy> proxy_;
  ConfigRecorder config_;
};

}  // namespace drive_link::test
