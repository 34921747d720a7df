// Drive-link benchmark: the card's RegisterProxy against the simulated inverter (InverterModel +
// InverterProtocolServer on a socket pair), on a fake clock. Prints, per server profile, the cyclic
// exchange period and the latency from SetCommandWords to the value landing in the inverter's register.
//
// Simulated time: the clock moves from deadline to deadline; the line timing is the server's model
// (processing delay + reply bytes at the baud rate), so the figures are exact and repeatable, not
// wall-clock measurements. Bounded: a fixed number of samples and of simulated seconds per profile.
//
// usage: drive_link_bench [--samples N]   (N <= 10000, default 500)
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "drive_link/register_proxy.h"
#include "hal/clock.h"
#include "sim/inverter_model.h"
#include "sim/protocol_server.h"
#include "socket_serial_port.h"

namespace {

using hal::Micros;

constexpr Micros kMilli = hal::kMicrosPerMilli;
constexpr Micros kSecond = hal::kMicrosPerSecond;
constexpr std::uint16_t kFa07 = 0xFA07;

class SimClock final : public hal::Clock {
 public:
  Micros NowMicros() const override { return now_; }
  void Set(Micros now) { now_ = now; }

 private:
  Micros now_ = 1000 * kSecond;
};

struct Profile {
  const char* name;
  sim::ServerConfig server;
  bool block_read;  // F875 = 1 (FD01), F876 = 2 (FD00) in force
};

struct Latency {
  Micros min = 0;
  Micros max = 0;
  double mean = 0.0;
  int samples = 0;
};

// One card and one simulated inverter on a fresh socket pair.
class Bench {
 public:
  explicit Bench(const Profile& profile) : model_(sim::Model::kVfMb1) {
    auto pair = hal::host::SocketSerialPort::CreatePair();
    if (!pair.ok()) {
      std::fprintf(stderr, "drive_link_bench: socketpair failed\n");
      std::exit(1);
    }
    pair_ = std::move(pair.value());
    if (profile.block_read) {
      // As if set before power-on: the selections are in force.
      std::string text = model_.SerializeEeprom();
      Replace(text, "reg 0875 0 ", "reg 0875 1 ");
      Replace(text, "reg 0876 0 ", "reg 0876 2 ");
      if (!model_.LoadEeprom(text)) std::exit(1);
    }
    server_ = std::make_unique<sim::InverterProtocolServer>(model_, *pair_.inverter, clock_, profile.server);
    proxy_ = std::make_unique<drive_link::RegisterProxy>(*pair_.card, drive_link::LinkConfig{},
                                                         drive_link::ProxyConfig{});
    server_->Poll(clock_.NowMicros());
    if (!proxy_->Start(clock_.NowMicros()).ok()) std::exit(1);
  }

  // Runs from deadline to deadline until `end` or until `done` says so; false when `end` came first.
  template <typename Done>
  bool Run(Micros end, Done done) {
    for (int i = 0; i < 10'000'000; ++i) {
      const Micros now = clock_.NowMicros();
      Micros at = std::max(std::min(proxy_->NextDeadline(), server_->NextDeadline()), now);
      if (at > end) {
        if (now >= end) return false;
        at = end;
      }
      clock_.Set(at);
      server_->Poll(at);
      proxy_->Poll(at);
      server_->Poll(at);
      if (done()) return true;
    }
    return false;
  }
  void RunFor(Micros duration) {
    Run(clock_.NowMicros() + duration, [] { return false; });
  }

  bool Loaded() {
    return Run(clock_.NowMicros() + 10 * kSecond, [this] { return proxy_->config_loaded(); });
  }

  // Changes the frequency word at `samples` phases spread over the cycle and measures when FA07 holds it.
  Latency MeasureLatency(int samples) {
    Latency latency;
    latency.min = hal::kNever;
    double total = 0.0;
    drive_link::ScannerWords words = {0xC400, 1000, 0, 0, 0, 0};
    proxy_->SetCommandWords(words);
    RunFor(kSecond);
    for (int i = 0; i < samples; ++i) {
      // A prime step in microseconds walks the start point through every phase of the cycle.
      RunFor(20 * kMilli + static_cast<Micros>((i * 7919) % 50'000));
      words[1] = static_cast<std::uint16_t>(1000 + (i % 2000) + 1);
      proxy_->SetCommandWords(words);
      const Micros set_at = clock_.NowMicros();
      const std::uint16_t wanted = words[1];
      const bool landed = Run(set_at + 5 * kSecond, [this, wanted] {
        const auto value = model_.Read(kFa07);
        return value.ok() && *value == wanted;
      });
      if (!landed) continue;
      const Micros took = clock_.NowMicros() - set_at;
      latency.min = std::min(latency.min, took);
      latency.max = std::max(latency.max, took);
      total += static_cast<double>(took);
      ++latency.samples;
    }
    if (latency.samples > 0) latency.mean = total / latency.samples;
    if (latency.samples == 0) latency.min = 0;
    return latency;
  }

  const drive_link::RegisterProxy& proxy() const { return *proxy_; }

 private:
  static void Replace(std::string& text, const char* from, const char* to) {
    const std::size_t at = text.find(from);
    if (at != std::string::npos) text.replace(at, std::strlen(from), to);
  }

  SimClock clock_;
  sim::InverterModel model_;
  hal::host::SocketSerialPort::Pair pair_;
  std::unique_ptr<sim::InverterProtocolServer> server_;
  std::unique_ptr<drive_link::RegisterProxy> proxy_;
};

double Ms(Micros micros) { return static_cast<double>(micros) / 1000.0; }

}  // namespace

int main(int argc, char** argv) {
  int samples = 500;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--samples") == 0 && i + 1 < argc) {
      samples = std::atoi(argv[++i]);
    } else {
      std::fprintf(stderr, "usage: drive_link_bench [--samples N]   (1 <= N <= 10000)\n");
      return 2;
    }
  }
  if (samples < 1 || samples > 10000) {
    std::fprintf(stderr, "drive_link_bench: --samples must be 1..10000\n");
    return 2;
  }

  const std::vector<Profile> profiles = {
      {"default (19200 baud 8E1, 2 ms processing)", sim::ServerConfig{}, false},
      {"default + block read (F875=1 FD01, F876=2 FD00)", sim::ServerConfig{}, true},
      {"Rs485Profile (19200 baud 8E1, 20 ms processing)", sim::Rs485Profile(), false},
      {"Rs485Profile + block read", sim::Rs485Profile(), true},
  };
  std::printf("drive-link benchmark: RegisterProxy <-> simulated inverter, SIMULATED time (fake clock,\n");
  std::printf("modelled line timing: processing delay + reply bytes at the baud rate), default c001-c026:\n");
  std::printf("command words FA06, FA07; monitor words FD01, FD00. %d latency samples per profile.\n\n", samples);
  for (const Profile& profile : profiles) {
    Bench bench(profile);
    if (!bench.Loaded()) {
      std::printf("%s: configuration never loaded\n", profile.name);
      return 1;
    }
    bench.RunFor(3 * kSecond);  // past the write-back of the owned values
    const drive_link::ProxyCounters idle = bench.proxy().counters();
    const Latency latency = bench.MeasureLatency(samples);
    const drive_link::ProxyCounters& busy = bench.proxy().counters();
    std::printf("%s\n", profile.name);
    std::printf("  cycle period, idle:          %.3f ms (min %.3f, max %.3f since start)\n", Ms(idle.cycle_period_last),
                Ms(idle.cycle_period_min), Ms(idle.cycle_period_max));
    std::printf("  cycle period, words changing: last %.3f ms, max %.3f ms\n", Ms(busy.cycle_period_last),
                Ms(busy.cycle_period_max));
    std::printf("  SetCommandWords -> FA07 in the inverter: min %.3f ms, mean %.3f ms, max %.3f ms (%d/%d)\n",
                Ms(latency.min), latency.mean / 1000.0, Ms(latency.max), latency.samples, samples);
    std::printf("  transactions: %u command writes, %u R reads, %u block reads, %u write-backs\n\n",
                busy.command_writes, busy.monitor_reads, busy.block_reads, busy.owned_writes);
  }
  return 0;
}
