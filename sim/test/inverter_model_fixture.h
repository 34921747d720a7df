// Shared fixture for the simulated inverter's behaviour-model tests (inverter_model_test.cc,
// inverter_drive_test.cc): a VF-MB1 past its power-on silence, and short helpers for reads and writes.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>

#include "hal/clock.h"
#include "sim/inverter_model.h"
#include "sim/register_numbers.h"

namespace sim::test {

inline constexpr hal::Micros kSecond = hal::kMicrosPerSecond;
inline constexpr hal::Micros kMilli = hal::kMicrosPerMilli;

class InverterModelFixture : public ::testing::Test {
 protected:
  explicit InverterModelFixture(Model model = Model::kVfMb1) : m_(model) {
    m_.Advance(t_);  // time base; the power-on silence runs to t_ + 1 s
    Wait(2 * kSecond);
  }

  std::uint16_t R(std::uint16_t number) {
    const auto r = m_.Read(number);
    EXPECT_TRUE(r.ok()) << std::hex << number;
    return r.ok() ? *r : 0xDEAD;
  }
  // P-write (RAM only) that must succeed.
  void P(std::uint16_t number, std::uint16_t word) {
    const WriteResult w = m_.Write(number, word, WriteTarget::kRamOnly);
    EXPECT_EQ(w.outcome, WriteOutcome::kOk) << std::hex << number << " = " << word;
  }
  // W-write (RAM and EEPROM) that must succeed.
  void W(std::uint16_t number, std::uint16_t word) {
    const WriteResult w = m_.Write(number, word, WriteTarget::kRamAndEeprom);
    EXPECT_EQ(w.outcome, WriteOutcome::kOk) << std::hex << number << " = " << word;
  }
  WriteOutcome Try(std::uint16_t number, std::uint16_t word) {
    return m_.Write(number, word, WriteTarget::kRamOnly).outcome;
  }
  // Advances in 10 ms steps, as a serial poll would.
  void Wait(hal::Micros duration, hal::Micros step = 10 * kMilli) {
    const hal::Micros end = t_ + duration;
    while (t_ < end) {
      t_ = std::min(end, t_ + step);
      m_.Advance(t_);
    }
  }

  hal::Micros t_ = 1000 * kSecond;  // an arbitrary clock origin
  InverterModel m_;
};

}  // namespace sim::test
