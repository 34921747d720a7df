#include "net/led_model.h"

#include <algorithm>

namespace net {
namespace {

using hal::LedColor;
using hal::Micros;

constexpr LedIndication kOff{LedPattern::kOff, LedColor::kOff};
constexpr LedIndication Steady(LedColor color) { return {LedPattern::kSteady, color}; }
constexpr LedIndication Flashing(LedColor color) { return {LedPattern::kFlashing, color}; }

constexpr Micros kFlashPeriod = kFlashOn + kFlashOff;
constexpr Micros kCountedFlash = kCountedFlashOn + kCountedFlashOff;

// Number of flashes of a counted pattern; 0 for the others.
constexpr unsigned FlashCount(LedPattern pattern) {
  switch (pattern) {
    case LedPattern::kFlashing3Times:
      return 3;
    case LedPattern::kFlashing4Times:
      return 4;
    case LedPattern::kFlashing5Times:
      return 5;
    default:
      return 0;
  }
}

constexpr Micros CountedPeriod(unsigned count) { return count * kCountedFlash + kCountedFlashPause; }

// Whether the LED is lit at `phase` within one period of the pattern (not for kOff / kSteady).
bool LitAt(LedPattern pattern, Micros phase) {
  if (pattern == LedPattern::kFlashing) return phase < kFlashOn;
  const unsigned count = FlashCount(pattern);
  if (phase >= count * kCountedFlash) return false;
  return phase % kCountedFlash < kCountedFlashOn;
}

// The offset within the period (> phase, at most the period) of the next on/off edge.
Micros NextEdgeInPeriod(LedPattern pattern, Micros phase) {
  if (pattern == LedPattern::kFlashing) return phase < kFlashOn ? kFlashOn : kFlashPeriod;
  const unsigned count = FlashCount(pattern);
  // The last flash's off time runs into the pause: the next edge is the next period's first flash.
  if (phase >= count * kCountedFlash - kCountedFlashOff) return CountedPeriod(count);
  const Micros within = phase % kCountedFlash;
  return phase - within + (within < kCountedFlashOn ? kCountedFlashOn : kCountedFlash);
}

Micros PeriodOf(LedPattern pattern) {
  return pattern == LedPattern::kFlashing ? kFlashPeriod : CountedPeriod(FlashCount(pattern));
}

bool IsPeriodic(LedPattern pattern) { return pattern == LedPattern::kFlashing || FlashCount(pattern) != 0; }

LedIndication EtherNetIpModuleStatus(const LedInputs& in) {
  if (in.fault == ModuleFault::kMajor) return Steady(LedColor::kRed);
  if (in.fault == ModuleFault::kMinor) return Flashing(LedColor::kRed);
  if (!in.configured) return Flashing(LedColor::kGreen);
  return Steady(LedColor::kGreen);
}

LedIndication ModbusModuleStatus(const LedInputs& in) {
  if (in.fault == ModuleFault::kMajor) return Steady(LedColor::kRed);
  if (!in.has_address) return kOff;
  if (in.connections == ConnectionState::kTimedOut) return Flashing(LedColor::kRed);
  if (!in.any_link_up || !in.configured) return Flashing(LedColor::kGreen);
  return Steady(LedColor::kGreen);
}

LedIndication EtherNetIpNetworkStatus(const LedInputs& in) {
  if (in.duplicate_address) return Steady(LedColor::kRed);
  if (!in.has_address) return kOff;
  if (in.connections == ConnectionState::kTimedOut) return Flashing(LedColor::kRed);
  if (in.connections == ConnectionState::kEstablished) return Steady(LedColor::kGreen);
  return Flashing(LedColor::kGreen);
}

LedIndication ModbusNetworkStatus(const LedInputs& in) {
  if (in.duplicate_address) return {LedPattern::kFlashing4Times, LedColor::kGreen};
  if (in.acquiring_address) return {LedPattern::kFlashing5Times, LedColor::kGreen};
  if (!in.has_address) return kOff;
  if (!in.any_link_up) return {LedPattern::kFlashing3Times, LedColor::kGreen};
  return Steady(LedColor::kGreen);
}

}  // namespace

LedIndication ModuleStatusIndication(const LedInputs& inputs) {
  return inputs.protocol == Protocol::kEtherNetIp ? EtherNetIpModuleStatus(inputs) : ModbusModuleStatus(inputs);
}

LedIndication NetworkStatusIndication(const LedInputs& inputs) {
  return inputs.protocol == Protocol::kEtherNetIp ? EtherNetIpNetworkStatus(inputs) : ModbusNetworkStatus(inputs);
}

LedColor PatternColor(const LedIndication& indication, Micros elapsed) {
  if (indication.pattern == LedPattern::kSteady) return indication.color;
  if (!IsPeriodic(indication.pattern)) return LedColor::kOff;
  return LitAt(indication.pattern, elapsed % PeriodOf(indication.pattern)) ? indication.color : LedColor::kOff;
}

Micros NextPatternChange(const LedIndication& indication, Micros elapsed) {
  if (!IsPeriodic(indication.pattern)) return hal::kNever;
  const Micros phase = elapsed % PeriodOf(indication.pattern);
  return elapsed - phase + NextEdgeInPeriod(indication.pattern, phase);
}

LedColor PowerUpTestColor(hal::Led led, Micros elapsed) {
  if (elapsed >= kPowerUpTestDuration) return LedColor::kOff;
  const Micros step = elapsed / kPowerUpTestStep;  // 0..3
  switch (led) {
    case hal::Led::kModuleStatus:
      return step == 1 ? LedColor::kRed : LedColor::kGreen;
    case hal::Led::kNetworkStatus:
      if (step == 2) return LedColor::kGreen;
      return step == 3 ? LedColor::kRed : LedColor::kOff;
    case hal::Led::kLinkLeft:
    case hal::Led::kLinkRight:
      if (step == 0) return LedColor::kGreen;
      return step == 1 ? LedColor::kRed : LedColor::kOff;
  }
  return LedColor::kOff;
}

void LedModel::StartPowerUpTest(Micros now) {
  test_started_ = true;
  test_start_ = now;
}

bool LedModel::PowerUpTestRunning(Micros now) const {
  return test_started_ && now >= test_start_ && now - test_start_ < kPowerUpTestDuration;
}

void LedModel::Update(const LedInputs& inputs, Micros now) {
  inputs_ = inputs;
  const std::array<LedIndication, 2> next = {ModuleStatusIndication(inputs), NetworkStatusIndication(inputs)};
  for (std::size_t slot = 0; slot < next.size(); ++slot) {
    if (next[slot] == indication_[slot]) continue;
    indication_[slot] = next[slot];
    since_[slot] = now;
  }
}

std::optional<std::size_t> LedModel::Slot(hal::Led led) {
  if (led == hal::Led::kModuleStatus) return kMs;
  if (led == hal::Led::kNetworkStatus) return kNs;
  return std::nullopt;
}

Micros LedModel::Origin(std::size_t slot) const {
  if (!test_started_) return since_[slot];
  return std::max(since_[slot], test_start_ + kPowerUpTestDuration);
}

LedIndication LedModel::Indication(hal::Led led, Micros now) const {
  const std::optional<std::size_t> slot = Slot(led);
  if (!slot) return kOff;
  if (PowerUpTestRunning(now)) return {LedPattern::kPowerUpTest, LedColor::kOff};
  return indication_[*slot];
}

LedColor LedModel::ColorAt(hal::Led led, Micros now) const {
  const std::optional<std::size_t> slot = Slot(led);
  if (!slot) return LedColor::kOff;
  if (PowerUpTestRunning(now)) return PowerUpTestColor(led, now - test_start_);
  const Micros origin = Origin(*slot);
  return PatternColor(indication_[*slot], now > origin ? now - origin : 0);
}

std::optional<LedColor> LedModel::LinkTestColor(Micros now) const {
  if (!PowerUpTestRunning(now)) return std::nullopt;
  return PowerUpTestColor(hal::Led::kLinkLeft, now - test_start_);
}

Micros LedModel::NextChange(Micros now) const {
  if (test_started_ && now < test_start_) return test_start_;
  if (PowerUpTestRunning(now)) {
    // Every step boundary (and the end of the test, where LNK hands over) may change a LED.
    const Micros elapsed = now - test_start_;
    return test_start_ + (elapsed / kPowerUpTestStep + 1) * kPowerUpTestStep;
  }
  Micros next = hal::kNever;
  for (std::size_t slot = 0; slot < indication_.size(); ++slot) {
    const Micros origin = Origin(slot);
    if (now < origin) {
      // An Update stamped later than `now`: the pattern starts at its origin.
      next = std::min(next, origin);
      continue;
    }
    const Micros offset = NextPatternChange(indication_[slot], now - origin);
    if (offset != hal::kNever) next = std::min(next, origin + offset);
  }
  return next;
}

void LedModel::Drive(hal::Leds& leds, Micros now) const {
  leds.Set(hal::Led::kModuleStatus, ColorAt(hal::Led::kModuleStatus, now));
  leds.Set(hal::Led::kNetworkStatus, ColorAt(hal::Led::kNetworkStatus, now));
}

}  // namespace net
