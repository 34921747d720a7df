// Helpers for the register proxy's part tests (drive_link_*_test.cc): completions as the link gives
// them, a ConfigLoader run through a whole load with chosen values, and AccessRules with settable answers
// (also what the DriveRegisters fakes answer CheckWrite with, through the real CheckRegisterWrite).
#pragma once

#include <cstdint>
#include <map>
#include <utility>
#include <vector>

#include "drive_link/access_queue.h"
#include "drive_link/config_loader.h"
#include "drive_link/link_client.h"
#include "drive_link/own_job.h"

namespace drive_link::test {

// A completion with `outcome` (kTimeout, kNoReply, kLinkDown: no reply data).
inline Completion OutcomeCompletion(Outcome outcome) {
  Completion completion;
  completion.outcome = outcome;
  completion.attempts = outcome == Outcome::kLinkDown ? 0 : 1;
  return completion;
}

inline Completion OkCompletion(std::uint16_t data) {
  Completion completion = OutcomeCompletion(Outcome::kOk);
  completion.data = data;
  return completion;
}

inline Completion ErrorCompletion(wire::ErrorCode error) {
  Completion completion = OutcomeCompletion(Outcome::kErrorReply);
  completion.error = error;
  return completion;
}

// The seed's factory settings (seed 000 §3.1) of what a load reads, changed by `values`; F875-F879 = 0,
// FD01 = `fd01`.
inline std::map<std::uint16_t, std::uint16_t> FactoryReads(std::map<std::uint16_t, std::uint16_t> values = {}) {
  std::map<std::uint16_t, std::uint16_t> reads = {
      {0xC001, 1}, {0xC002, 3}, {0xC021, 1}, {0xC022, 2}, {0xC101, 4},
      {0xC523, 20}, {0xC554, 1}, {0x0003, 1}, {0x0856, 2},
  };
  for (const auto& [number, value] : values) reads[number] = value;
  return reads;
}

// Runs a whole load on `loader`, answering each read from `values` (0 where absent). Returns the
// numbers read, in order.
inline std::vector<std::uint16_t> RunLoad(ConfigLoader& loader, const std::map<std::uint16_t, std::uint16_t>& values) {
  std::vector<std::uint16_t> numbers;
  loader.Begin();
  OwnJob job;
  while (loader.NextRead(job)) {
    numbers.push_back(job.transaction.comm_number);
    const auto found = values.find(job.transaction.comm_number);
    if (loader.OnRead(job.index, OkCompletion(found == values.end() ? 0 : found->second))) break;
  }
  return numbers;
}

class FakeAccessRules final : public AccessRules {
 public:
  bool ConfigLoaded() const override { return loaded; }
  bool IsScannerTarget(std::uint16_t number) const override {
    return number == scanner_target || (scanner != nullptr && scanner->IsScannerTarget(number));
  }
  bool CommandsHeldByLoss() const override { return held_by_loss; }
  bool DriveRunning() const override { return running; }
  void OnWriteAccepted(std::uint16_t number, std::uint16_t value) override { accepted.emplace_back(number, value); }
  void OnInverterReset(bool card_reset) override { resets.push_back(card_reset); }

  bool loaded = true;
  std::uint16_t scanner_target = 0;
  const ScannerImage* scanner = nullptr;  // asked too when set
  bool held_by_loss = false;
  bool running = false;
  std::vector<std::pair<std::uint16_t, std::uint16_t>> accepted;
  std::vector<bool> resets;
};

}  // namespace drive_link::test
