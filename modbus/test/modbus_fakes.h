// Fakes of drive_link's facades (register_access.h) for the Modbus server's tests and fuzz target,
// and a small harness that runs a modbus::Server against them on a fake clock.
//
// FakeDriveRegisters behaves like the register proxy's contract: Read/Write only start an access; its
// completion arrives in a later Poll() (never inside Read/Write, even for a local refusal), in the
// order started; Cancel(listener) drops that listener's pending completions.
#pragma once

#include <cstdint>
#include <deque>
#include <map>
#include <span>
#include <vector>

#include "drive_link/drive_registers.h"
#include "drive_link/register_access.h"
#include "drive_link_part_fakes.h"
#include "modbus/server.h"

namespace modbus::test {

using Bytes = std::vector<std::uint8_t>;

class FakeDriveRegisters final : public drive_link::DriveRegisters {
 public:
  struct Access {
    bool write = false;
    std::uint16_t number = 0;
    std::uint16_t value = 0;
    drive_link::WriteMode mode = drive_link::WriteMode::kRamAndEeprom;
    bool operator==(const Access&) const = default;
  };

  base::Result<drive_link::AccessToken> Read(std::uint16_t number, drive_link::AccessListener& listener) override {
    return Start(Access{false, number, 0, drive_link::WriteMode::kRamAndEeprom}, listener);
  }
  base::Result<drive_link::AccessToken> Write(std::uint16_t number, std::uint16_t value, drive_link::WriteMode mode,
                                              drive_link::AccessListener& listener) override {
    return Start(Access{true, number, value, mode}, listener);
  }
  // The register proxy's own check (CheckRegisterWrite) on `rules`.
  drive_link::AccessError CheckWrite(std::uint16_t number, std::uint16_t value) const override {
    return drive_link::CheckRegisterWrite(number, value, rules);
  }
  void Cancel(drive_link::AccessListener& listener) override {
    ++cancels;
    std::erase_if(pending_, [&](const Pending& p) { return p.listener == &listener; });
  }

  // Delivers the completions of every access started before this call.
  void Poll() {
    std::deque<Pending> due;
    due.swap(pending_);
    for (const Pending& p : due) {
      drive_link::AccessResult result = Execute(p.access);
      p.listener->OnAccessDone(p.token, result);
    }
  }
  std::size_t pending() const { return pending_.size(); }

  std::map<std::uint16_t, std::uint16_t> registers;
  // What CheckWrite knows: a configuration loaded, the scanner's targets (ServerHarness: its scanner).
  drive_link::test::FakeAccessRules rules;
  // An access to one of these numbers fails with the error (reads and writes).
  std::map<std::uint16_t, drive_link::AccessError> errors;
  int busy_next = 0;       // the next n Read/Write calls return kResourceExhausted
  bool link_down = false;  // Read/Write return kFailedPrecondition
  int cancels = 0;
  std::vector<Access> log;  // every access started

 private:
  struct Pending {
    drive_link::AccessToken token;
    drive_link::AccessListener* listener;
    Access access;
  };

  base::Result<drive_link::AccessToken> Start(const Access& access, drive_link::AccessListener& listener) {
    if (link_down) return base::FailedPrecondition();
    if (busy_next > 0) {
      --busy_next;
      return base::ResourceExhausted();
    }
    log.push_back(access);
    const drive_link::AccessToken token = ++next_token_;
    pending_.push_back(Pending{token, &listener, access});
    return token;
  }

  drive_link::AccessResult Execute(const Access& access) {
    drive_link::AccessResult result;
    result.number = access.number;
    if (!drive_link::reg::HasDecimalLastDigit(access.number)) {
      result.error = drive_link::AccessError::kNoSuchRegister;
      return result;
    }
    if (const auto error = errors.find(access.number); error != errors.end()) {
      result.error = error->second;
      return result;
    }
    const auto value = registers.find(access.number);
    if (value == registers.end()) {
      result.error = drive_link::AccessError::kNoSuchRegister;
      return result;
    }
    if (access.write) value->second = access.value;
    result.value = value->second;
    return result;
  }

  std::deque<Pending> pending_;
  drive_link::AccessToken next_token_ = 0;
};

class FakeScannerImage final : public drive_link::ScannerImage {
 public:
  void SetCommandWords(const drive_link::ScannerWords& words) override {
    command_words = words;
    ++set_calls;
  }
  drive_link::ScannerWords CommandWords() const override { return command_words; }
  drive_link::ScannerWords MonitorWords() const override { return monitor_words; }
  bool IsScannerTarget(std::uint16_t number) const override {
    for (std::uint16_t target : targets) {
      if (target == number) return true;
    }
    return false;
  }

  drive_link::ScannerWords command_words{};
  drive_link::ScannerWords monitor_words{};
  std::vector<std::uint16_t> targets;  // the command words' registers in use
  int set_calls = 0;
};

class FakeLossSupervision final : public drive_link::LossSupervision {
 public:
  struct Event {
    bool lost = false;  // NetworkLost; false: NetworkRestored
    drive_link::LossCause cause = drive_link::LossCause::kModbusConnection;
    hal::Micros at = 0;
    bool operator==(const Event&) const = default;
  };

  void NetworkLost(drive_link::LossCause cause, hal::Micros now) override {
    events.push_back(Event{true, cause, now});
    lost_ = true;
  }
  void NetworkRestored(hal::Micros now) override {
    events.push_back(Event{false, drive_link::LossCause::kModbusConnection, now});
    lost_ = false;
  }
  bool loss_action_active() const override { return lost_; }

  std::vector<Event> events;

 private:
  bool lost_ = false;
};

inline constexpr base::Ipv4Address kClientAddress{192, 168, 1, 30};
inline constexpr base::Ipv4Address kOtherAddress{192, 168, 1, 31};

// A server with fakes behind it and a fake time.
struct ServerHarness {
  explicit ServerHarness(const ServerOptions& options = {}) : server(drive, scanner, loss, options) {
    drive.rules.scanner = &scanner;
  }

  ConnectionId Connect(const base::Ipv4Address& peer = kClientAddress) {
    const base::Result<ConnectionId> id = server.Open(peer, now);
    return id.ok() ? *id : ConnectionId{0xFF};
  }

  // Feeds bytes, then lets the drive complete until the server has nothing in flight (at most
  // `max_rounds` drive polls), and returns (and consumes) everything answered.
  Bytes Exchange(ConnectionId id, const Bytes& request, int max_rounds = 200) {
    server.Receive(id, request, now);
    for (int i = 0; i < max_rounds && drive.pending() > 0; ++i) {
      drive.Poll();
      server.Poll(now);
    }
    return TakeOutput(id);
  }

  Bytes TakeOutput(ConnectionId id) {
    const std::span<const std::uint8_t> out = server.PendingOutput(id);
    Bytes bytes(out.begin(), out.end());
    server.ConsumeOutput(id, bytes.size(), now);
    return bytes;
  }

  void Advance(hal::Micros delta) {
    now += delta;
    server.Poll(now);
  }

  FakeDriveRegisters drive;
  FakeScannerImage scanner;
  FakeLossSupervision loss;
  Server server;
  hal::Micros now = 1'000'000;
};

}  // namespace modbus::test
