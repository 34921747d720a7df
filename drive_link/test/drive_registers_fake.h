// A drive_link::DriveRegisters fake that records every access and leaves its completion to the test,
// for the CIP drive objects (the access journal, the parameter and motor data objects, the control
// supervisor) and their fuzz target.
//
// As the register proxy's contract says, Read/Write only start an access and never call the listener
// themselves. The test completes accesses one by one (Complete, CompleteWith) or all at once from the
// register map (CompleteAll), in any order; Cancel(listener) drops that listener's completions.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <vector>

#include "drive_link/drive_registers.h"
#include "drive_link/register_access.h"
#include "drive_link_part_fakes.h"

namespace drive_link::test {

class ScriptedDriveRegisters final : public DriveRegisters {
 public:
  struct Access {
    bool write = false;
    std::uint16_t number = 0;
    std::uint16_t value = 0;  // write only
    WriteMode mode = WriteMode::kRamOnly;  // write only
    bool operator==(const Access&) const = default;
  };

  base::Result<AccessToken> Read(std::uint16_t number, AccessListener& listener) override {
    return Start(Access{false, number, 0, WriteMode::kRamOnly}, listener);
  }
  base::Result<AccessToken> Write(std::uint16_t number, std::uint16_t value, WriteMode mode,
                                  AccessListener& listener) override {
    return Start(Access{true, number, value, mode}, listener);
  }
  // The register proxy's own check (CheckRegisterWrite) on `rules`.
  AccessError CheckWrite(std::uint16_t number, std::uint16_t value) const override {
    return CheckRegisterWrite(number, value, rules);
  }
  void Cancel(AccessListener& listener) override {
    ++cancels;
    std::erase_if(pending_, [&](const Pending& p) { return p.listener == &listener; });
  }

  // Completes the oldest pending access with `result` (its number is filled in). False when none.
  bool CompleteWith(const AccessResult& result) {
    if (pending_.empty()) return false;
    const Pending p = pending_.front();
    pending_.erase(pending_.begin());
    AccessResult completed = result;
    completed.number = p.access.number;
    p.listener->OnAccessDone(p.token, completed);
    return true;
  }
  // Completes the oldest pending access as the register map says (CompleteAll's rules).
  bool Complete() {
    if (pending_.empty()) return false;
    return CompleteWith(Execute(pending_.front().access));
  }
  // Completes every access pending now, in the order started.
  void CompleteAll() {
    std::size_t count = pending_.size();
    while (count-- > 0 && Complete()) {
    }
  }
  // Completes the access started with `token`, wherever it is in the queue. False when not pending.
  bool CompleteToken(AccessToken token, const AccessResult& result) {
    for (auto it = pending_.begin(); it != pending_.end(); ++it) {
      if (it->token != token) continue;
      const Pending p = *it;
      pending_.erase(it);
      AccessResult completed = result;
      completed.number = p.access.number;
      p.listener->OnAccessDone(p.token, completed);
      return true;
    }
    return false;
  }

  std::size_t pending() const { return pending_.size(); }
  std::optional<AccessToken> last_token() const {
    if (next_token_ == 0) return std::nullopt;
    return next_token_;
  }

  // The inverter as CompleteAll sees it: a number missing here is kNoSuchRegister; a write stores.
  std::map<std::uint16_t, std::uint16_t> registers;
  FakeAccessRules rules;  // what CheckWrite knows
  std::map<std::uint16_t, AccessError> errors;  // an access to one of these numbers fails so
  int busy_next = 0;       // the next n Read/Write calls return kResourceExhausted (pool full)
  bool link_down = false;  // Read/Write return kFailedPrecondition
  int cancels = 0;
  std::vector<Access> log;  // every access started, in order

 private:
  struct Pending {
    AccessToken token;
    AccessListener* listener;
    Access access;
  };

  base::Result<AccessToken> Start(const Access& access, AccessListener& listener) {
    if (link_down) return base::FailedPrecondition();
    if (busy_next > 0) {
      --busy_next;
      return base::ResourceExhausted();
    }
    log.push_back(access);
    const AccessToken token = ++next_token_;
    pending_.push_back(Pending{token, &listener, access});
    return token;
  }

  AccessResult Execute(const Access& access) {
    AccessResult result;
    result.number = access.number;
    if (const auto error = errors.find(access.number); error != errors.end()) {
      result.error = error->second;
      return result;
    }
    const auto value = registers.find(access.number);
    if (value == registers.end() || !reg::HasDecimalLastDigit(access.number)) {
      result.error = AccessError::kNoSuchRegister;
      return result;
    }
    if (access.write) value->second = access.value;
    result.value = value->second;
    return result;
  }

  std::vector<Pending> pending_;
  AccessToken next_token_ = 0;
};

}  // namespace drive_link::test
