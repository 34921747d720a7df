// The MS/NS LED state model (net/led_model.h, docs/network.md "LED model"): every row of the §2.4
// tables for both protocols, the priorities between rows, the flash timing at each edge, the power-up
// test, the phase rules of LedModel and its deadlines.
#include "net/led_model.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace net {
namespace {

using hal::Led;
using hal::LedColor;
using hal::Micros;

constexpr Micros kMs = hal::kMicrosPerMilli;

LedInputs Ready(Protocol protocol) {
  LedInputs in;
  in.protocol = protocol;
  in.configured = true;
  in.has_address = true;
  in.any_link_up = true;
  return in;
}

constexpr LedIndication kOffInd{LedPattern::kOff, LedColor::kOff};
constexpr LedIndication Steady(LedColor c) { return {LedPattern::kSteady, c}; }
constexpr LedIndication Flashing(LedColor c) { return {LedPattern::kFlashing, c}; }
constexpr LedIndication Green(LedPattern p) { return {p, LedColor::kGreen}; }

struct Row {
  const char* name;
  LedInputs inputs;
  LedIndication expected;
};

template <typename Mutate>
LedInputs With(Protocol protocol, Mutate mutate) {
  LedInputs in = Ready(protocol);
  mutate(in);
  return in;
}

void CheckRows(const std::vector<Row>& rows, LedIndication (*indication)(const LedInputs&)) {
  for (const Row& row : rows) {
    SCOPED_TRACE(row.name);
    const LedIndication got = indication(row.inputs);
    EXPECT_EQ(got.pattern, row.expected.pattern);
    EXPECT_EQ(got.color, row.expected.color);
  }
}

TEST(LedModelTest, EtherNetIpModuleStatusTable) {
  constexpr Protocol p = Protocol::kEtherNetIp;
  CheckRows(
      {
          {"operating correctly", Ready(p), Steady(LedColor::kGreen)},
          {"not configured", With(p, [](LedInputs& in) { in.configured = false; }), Flashing(LedColor::kGreen)},
          {"minor fault", With(p, [](LedInputs& in) { in.fault = ModuleFault::kMinor; }), Flashing(LedColor::kRed)},
          {"major fault", With(p, [](LedInputs& in) { in.fault = ModuleFault::kMajor; }), Steady(LedColor::kRed)},
          {"major outranks not configured",
           With(p, [](LedInputs& in) { in.fault = ModuleFault::kMajor; in.configured = false; }),
           Steady(LedColor::kRed)},
          {"minor outranks not configured",
           With(p, [](LedInputs& in) { in.fault = ModuleFault::kMinor; in.configured = false; }),
           Flashing(LedColor::kRed)},
          // MS is about the module: no address or no link does not change it.
          {"no address", With(p, [](LedInputs& in) { in.has_address = false; }), Steady(LedColor::kGreen)},
      },
      ModuleStatusIndication);
}

TEST(LedModelTest, EtherNetIpNetworkStatusTable) {
  constexpr Protocol p = Protocol::kEtherNetIp;
  CheckRows(
      {
          {"no established connection", Ready(p), Flashing(LedColor::kGreen)},
          {"connection established",
           With(p, [](LedInputs& in) { in.connections = ConnectionState::kEstablished; }), Steady(LedColor::kGreen)},
          {"connection timed out", With(p, [](LedInputs& in) { in.connections = ConnectionState::kTimedOut; }),
           Flashing(LedColor::kRed)},
          {"duplicate IP", With(p, [](LedInputs& in) { in.duplicate_address = true; }), Steady(LedColor::kRed)},
          {"no address", With(p, [](LedInputs& in) { in.has_address = false; }), kOffInd},
          {"BOOTP/DHCP running: no address yet",
           With(p, [](LedInputs& in) { in.has_address = false; in.acquiring_address = true; }), kOffInd},
          {"duplicate IP after the address was given up",
           With(p, [](LedInputs& in) { in.has_address = false; in.duplicate_address = true; }),
           Steady(LedColor::kRed)},
          {"duplicate outranks a timeout",
           With(p, [](LedInputs& in) { in.duplicate_address = true; in.connections = ConnectionState::kTimedOut; }),
           Steady(LedColor::kRed)},
          {"all ports unplugged keeps the connection view",
           With(p, [](LedInputs& in) { in.any_link_up = false; }), Flashing(LedColor::kGreen)},
      },
      NetworkStatusIndication);
}

TEST(LedModelTest, ModbusModuleStatusTable) {
  constexpr Protocol p = Protocol::kModbusTcp;
  CheckRows(
      {
          {"ready", Ready(p), Steady(LedColor::kGreen)},
          {"no address", With(p, [](LedInputs& in) { in.has_address = false; }), kOffInd},
          {"waiting for cable", With(p, [](LedInputs& in) { in.any_link_up = false; }), Flashing(LedColor::kGreen)},
          {"not ready", With(p, [](LedInputs& in) { in.configured = false; }), Flashing(LedColor::kGreen)},
          {"communication error err8",
           With(p, [](LedInputs& in) { in.connections = ConnectionState::kTimedOut; }), Flashing(LedColor::kRed)},
          {"option module error e-23", With(p, [](LedInputs& in) { in.fault = ModuleFault::kMajor; }),
           Steady(LedColor::kRed)},
          {"e-23 shows without an address",
           With(p, [](LedInputs& in) { in.fault = ModuleFault::kMajor; in.has_address = false; }),
           Steady(LedColor::kRed)},
          {"a minor fault has no row", With(p, [](LedInputs& in) { in.fault = ModuleFault::kMinor; }),
           Steady(LedColor::kGreen)},
          {"err8 outranks not ready",
           With(p, [](LedInputs& in) { in.connections = ConnectionState::kTimedOut; in.any_link_up = false; }),
           Flashing(LedColor::kRed)},
      },
      ModuleStatusIndication);
}

TEST(LedModelTest, ModbusNetworkStatusTable) {
  constexpr Protocol p = Protocol::kModbusTcp;
  CheckRows(
      {
          {"port connected and address obtained", Ready(p), Steady(LedColor::kGreen)},
          {"no address", With(p, [](LedInputs& in) { in.has_address = false; }), kOffInd},
          {"all ports unplugged, address kept", With(p, [](LedInputs& in) { in.any_link_up = false; }),
           Green(LedPattern::kFlashing3Times)},
          {"duplicate IP", With(p, [](LedInputs& in) { in.duplicate_address = true; }),
           Green(LedPattern::kFlashing4Times)},
          {"BOOTP/DHCP in progress",
           With(p, [](LedInputs& in) { in.has_address = false; in.acquiring_address = true; }),
           Green(LedPattern::kFlashing5Times)},
          {"duplicate without an address",
           With(p, [](LedInputs& in) { in.has_address = false; in.duplicate_address = true; }),
           Green(LedPattern::kFlashing4Times)},
          {"duplicate outranks acquisition",
           With(p, [](LedInputs& in) { in.duplicate_address = true; in.acquiring_address = true; }),
           Green(LedPattern::kFlashing4Times)},
          {"no address and unplugged", With(p, [](LedInputs& in) { in.has_address = false; in.any_link_up = false; }),
           kOffInd},
          {"connections do not show on NS",
           With(p, [](LedInputs& in) { in.connections = ConnectionState::kTimedOut; }), Steady(LedColor::kGreen)},
      },
      NetworkStatusIndication);
}

TEST(LedModelTest, FlashingIsHalfSecondOnHalfSecondOffStartingOn) {
  const LedIndication red = Flashing(LedColor::kRed);
  EXPECT_EQ(PatternColor(red, 0), LedColor::kRed);
  EXPECT_EQ(PatternColor(red, 500 * kMs - 1), LedColor::kRed);
  EXPECT_EQ(PatternColor(red, 500 * kMs), LedColor::kOff);
  EXPECT_EQ(PatternColor(red, 1000 * kMs - 1), LedColor::kOff);
  EXPECT_EQ(PatternColor(red, 1000 * kMs), LedColor::kRed);
  EXPECT_EQ(PatternColor(red, 7500 * kMs), LedColor::kOff);
  EXPECT_EQ(NextPatternChange(red, 0), 500 * kMs);
  EXPECT_EQ(NextPatternChange(red, 500 * kMs - 1), 500 * kMs);
  EXPECT_EQ(NextPatternChange(red, 500 * kMs), 1000 * kMs);
  EXPECT_EQ(NextPatternChange(red, 1000 * kMs), 1500 * kMs);
}

TEST(LedModelTest, SteadyAndOffNeverChange) {
  EXPECT_EQ(PatternColor(Steady(LedColor::kGreen), 123456789), LedColor::kGreen);
  EXPECT_EQ(PatternColor(kOffInd, 0), LedColor::kOff);
  EXPECT_EQ(NextPatternChange(Steady(LedColor::kGreen), 0), hal::kNever);
  EXPECT_EQ(NextPatternChange(kOffInd, 0), hal::kNever);
}

// The lit intervals of one period of "flashing N times", in ms, and the period.
void CheckCounted(LedPattern pattern, unsigned count) {
  SCOPED_TRACE(count);
  const LedIndication ind = Green(pattern);
  const Micros period = (count * 400 + 800) * kMs;
  std::vector<Micros> edges;  // every edge of one period, then the next period's first
  for (unsigned i = 0; i < count; ++i) {
    const Micros on = i * 400 * kMs;
    EXPECT_EQ(PatternColor(ind, on), LedColor::kGreen) << i;
    EXPECT_EQ(PatternColor(ind, on + 200 * kMs - 1), LedColor::kGreen) << i;
    EXPECT_EQ(PatternColor(ind, on + 200 * kMs), LedColor::kOff) << i;
    EXPECT_EQ(PatternColor(ind, on + 400 * kMs - 1), LedColor::kOff) << i;
    edges.push_back(on + 200 * kMs);
    if (i + 1 < count) edges.push_back(on + 400 * kMs);
  }
  // The pause: dark from the last flash's end to the period's end.
  EXPECT_EQ(PatternColor(ind, count * 400 * kMs), LedColor::kOff);
  EXPECT_EQ(PatternColor(ind, period - 1), LedColor::kOff);
  EXPECT_EQ(PatternColor(ind, period), LedColor::kGreen);
  edges.push_back(period);
  Micros t = 0;
  for (const Micros edge : edges) {
    EXPECT_EQ(NextPatternChange(ind, t), edge) << t;
    EXPECT_EQ(NextPatternChange(ind, edge - 1), edge) << edge;
    t = edge;
  }
  EXPECT_EQ(NextPatternChange(ind, period), period + 200 * kMs);
}

TEST(LedModelTest, CountedFlashesAreTwoHundredMsWithOneSecondBetweenGroups) {
  CheckCounted(LedPattern::kFlashing3Times, 3);
  CheckCounted(LedPattern::kFlashing4Times, 4);
  CheckCounted(LedPattern::kFlashing5Times, 5);
}

TEST(LedModelTest, PowerUpTestColoursAtEachStep) {
  struct Expect {
    Micros at;
    LedColor ms, ns, lnk;
  };
  const Expect steps[] = {
      {0, LedColor::kGreen, LedColor::kOff, LedColor::kGreen},
      {250 * kMs - 1, LedColor::kGreen, LedColor::kOff, LedColor::kGreen},
      {250 * kMs, LedColor::kRed, LedColor::kOff, LedColor::kRed},
      {500 * kMs - 1, LedColor::kRed, LedColor::kOff, LedColor::kRed},
      {500 * kMs, LedColor::kGreen, LedColor::kGreen, LedColor::kOff},
      {750 * kMs - 1, LedColor::kGreen, LedColor::kGreen, LedColor::kOff},
      {750 * kMs, LedColor::kGreen, LedColor::kRed, LedColor::kOff},
      {1000 * kMs - 1, LedColor::kGreen, LedColor::kRed, LedColor::kOff},
      {1000 * kMs, LedColor::kOff, LedColor::kOff, LedColor::kOff},
  };
  for (const Expect& e : steps) {
    SCOPED_TRACE(e.at);
    EXPECT_EQ(PowerUpTestColor(Led::kModuleStatus, e.at), e.ms);
    EXPECT_EQ(PowerUpTestColor(Led::kNetworkStatus, e.at), e.ns);
    EXPECT_EQ(PowerUpTestColor(Led::kLinkLeft, e.at), e.lnk);
    EXPECT_EQ(PowerUpTestColor(Led::kLinkRight, e.at), e.lnk);
  }
}

TEST(LedModelTest, ModelRunsTheTestThenFollowsTheInputsFromTheTestEnd) {
  constexpr Micros t0 = 5 * hal::kMicrosPerSecond;
  LedModel model;
  model.StartPowerUpTest(t0);
  model.Update(Ready(Protocol::kEtherNetIp), t0);  // NS: flashing green (no connection)
  EXPECT_TRUE(model.PowerUpTestRunning(t0));
  EXPECT_EQ(model.Indication(Led::kNetworkStatus, t0).pattern, LedPattern::kPowerUpTest);
  EXPECT_EQ(model.ColorAt(Led::kModuleStatus, t0 + 300 * kMs), LedColor::kRed);
  EXPECT_EQ(model.ColorAt(Led::kNetworkStatus, t0 + 800 * kMs), LedColor::kRed);
  EXPECT_EQ(model.LinkTestColor(t0), LedColor::kGreen);
  EXPECT_EQ(model.LinkTestColor(t0 + 600 * kMs), LedColor::kOff);
  // The test is over: LNK goes back to the link colours, NS starts its first flash at the test end.
  const Micros end = t0 + kPowerUpTestDuration;
  EXPECT_FALSE(model.PowerUpTestRunning(end));
  EXPECT_EQ(model.LinkTestColor(end), std::nullopt);
  EXPECT_EQ(model.Indication(Led::kNetworkStatus, end), Flashing(LedColor::kGreen));
  EXPECT_EQ(model.ColorAt(Led::kModuleStatus, end), LedColor::kGreen);
  EXPECT_EQ(model.ColorAt(Led::kNetworkStatus, end), LedColor::kGreen);
  EXPECT_EQ(model.ColorAt(Led::kNetworkStatus, end + 500 * kMs), LedColor::kOff);
  EXPECT_EQ(model.ColorAt(Led::kNetworkStatus, end + 1000 * kMs), LedColor::kGreen);
  // LNK LEDs are not the model's.
  EXPECT_EQ(model.Indication(Led::kLinkLeft, end).pattern, LedPattern::kOff);
  EXPECT_EQ(model.ColorAt(Led::kLinkRight, end), LedColor::kOff);
}

TEST(LedModelTest, ChangedIndicationRestartsItsPatternUnchangedKeepsPhase) {
  LedModel model;
  LedInputs in = Ready(Protocol::kModbusTcp);
  in.any_link_up = false;  // NS: 3 flashes, MS: flashing green
  model.Update(in, 1000 * kMs);
  EXPECT_EQ(model.ColorAt(Led::kNetworkStatus, 1000 * kMs), LedColor::kGreen);
  EXPECT_EQ(model.ColorAt(Led::kNetworkStatus, 1200 * kMs), LedColor::kOff);
  // Same inputs again (an event loop re-evaluates every pass): the phase stays.
  model.Update(in, 1300 * kMs);
  EXPECT_EQ(model.ColorAt(Led::kNetworkStatus, 1300 * kMs), LedColor::kOff);
  EXPECT_EQ(model.ColorAt(Led::kNetworkStatus, 1400 * kMs), LedColor::kGreen);
  // An unrelated input that changes neither indication keeps both phases too.
  in.configured = true;  // MS stays flashing green: no link
  in.fault = ModuleFault::kMinor;  // no Modbus row
  model.Update(in, 1450 * kMs);
  EXPECT_EQ(model.ColorAt(Led::kModuleStatus, 1450 * kMs), LedColor::kGreen);
  EXPECT_EQ(model.ColorAt(Led::kModuleStatus, 1500 * kMs), LedColor::kOff);
  // A duplicate address: NS changes to 4 flashes, starting lit now, mid-way through the old pattern.
  in.duplicate_address = true;
  model.Update(in, 1700 * kMs);
  EXPECT_EQ(model.Indication(Led::kNetworkStatus, 1700 * kMs), Green(LedPattern::kFlashing4Times));
  EXPECT_EQ(model.ColorAt(Led::kNetworkStatus, 1700 * kMs), LedColor::kGreen);
  EXPECT_EQ(model.ColorAt(Led::kNetworkStatus, 1900 * kMs), LedColor::kOff);
  EXPECT_EQ(model.ColorAt(Led::kNetworkStatus, (1700 + 1600) * kMs), LedColor::kOff);  // the pause
  EXPECT_EQ(model.ColorAt(Led::kNetworkStatus, (1700 + 2400) * kMs), LedColor::kGreen);
}

TEST(LedModelTest, NextChangeIsTheEarliestEdgeOfEitherLed) {
  LedModel model;
  EXPECT_EQ(model.NextChange(0), hal::kNever);  // both off
  model.StartPowerUpTest(0);
  EXPECT_EQ(model.NextChange(0), 250 * kMs);
  EXPECT_EQ(model.NextChange(250 * kMs), 500 * kMs);
  EXPECT_EQ(model.NextChange(999 * kMs), 1000 * kMs);
  LedInputs in = Ready(Protocol::kEtherNetIp);
  in.connections = ConnectionState::kEstablished;
  model.Update(in, 100 * kMs);  // MS and NS steady green after the test
  EXPECT_EQ(model.NextChange(1000 * kMs), hal::kNever);
  in.connections = ConnectionState::kTimedOut;  // NS flashing red from 1200 ms
  model.Update(in, 1200 * kMs);
  EXPECT_EQ(model.NextChange(1200 * kMs), 1700 * kMs);
  EXPECT_EQ(model.NextChange(1700 * kMs), 2200 * kMs);
  in.configured = false;  // MS flashing green from 1300 ms
  model.Update(in, 1300 * kMs);
  EXPECT_EQ(model.NextChange(1300 * kMs), 1700 * kMs);
  EXPECT_EQ(model.NextChange(1700 * kMs), 1800 * kMs);
  EXPECT_EQ(model.NextChange(1800 * kMs), 2200 * kMs);
}

class RecordingLeds final : public hal::Leds {
 public:
  void Set(Led led, LedColor color) override { log.push_back({led, color}); }
  struct Call {
    Led led;
    LedColor color;
    bool operator==(const Call&) const = default;
  };
  std::vector<Call> log;
};

TEST(LedModelTest, DriveSetsModuleAndNetworkStatus) {
  LedModel model;
  LedInputs in = Ready(Protocol::kModbusTcp);
  in.has_address = false;
  in.acquiring_address = true;  // MS off, NS 5 flashes
  model.Update(in, 0);
  RecordingLeds leds;
  model.Drive(leds, 0);
  model.Drive(leds, 250 * kMs);
  const std::vector<RecordingLeds::Call> expected = {
      {Led::kModuleStatus, LedColor::kOff},
      {Led::kNetworkStatus, LedColor::kGreen},
      {Led::kModuleStatus, LedColor::kOff},
      {Led::kNetworkStatus, LedColor::kOff},
  };
  EXPECT_EQ(leds.log, expected);
}

// One scenario end to end: a Modbus TCP card on BOOTP powers up, gets its address, loses both cables,
// gets them back, then ACD finds its address taken.
TEST(LedModelTest, ModbusBootpScenarioSequence) {
  LedModel model;
  model.StartPowerUpTest(0);
  LedInputs in;
  in.protocol = Protocol::kModbusTcp;
  in.configured = true;
  in.any_link_up = true;
  in.acquiring_address = true;
  model.Update(in, 0);
  EXPECT_EQ(model.ColorAt(Led::kNetworkStatus, 999 * kMs), LedColor::kRed);  // test
  EXPECT_EQ(model.Indication(Led::kNetworkStatus, 1000 * kMs), Green(LedPattern::kFlashing5Times));
  EXPECT_EQ(model.Indication(Led::kModuleStatus, 1000 * kMs).pattern, LedPattern::kOff);
  EXPECT_EQ(model.ColorAt(Led::kNetworkStatus, (1000 + 1800) * kMs), LedColor::kOff);  // pause after 5
  in.acquiring_address = false;
  in.has_address = true;
  model.Update(in, 4 * hal::kMicrosPerSecond);
  EXPECT_EQ(model.Indication(Led::kNetworkStatus, 4 * hal::kMicrosPerSecond), Steady(LedColor::kGreen));
  EXPECT_EQ(model.Indication(Led::kModuleStatus, 4 * hal::kMicrosPerSecond), Steady(LedColor::kGreen));
  in.any_link_up = false;
  model.Update(in, 5 * hal::kMicrosPerSecond);
  EXPECT_EQ(model.Indication(Led::kNetworkStatus, 5 * hal::kMicrosPerSecond), Green(LedPattern::kFlashing3Times));
  EXPECT_EQ(model.Indication(Led::kModuleStatus, 5 * hal::kMicrosPerSecond), Flashing(LedColor::kGreen));
  in.any_link_up = true;
  in.duplicate_address = true;
  in.has_address = false;
  model.Update(in, 6 * hal::kMicrosPerSecond);
  EXPECT_EQ(model.Indication(Led::kNetworkStatus, 6 * hal::kMicrosPerSecond), Green(LedPattern::kFlashing4Times));
  EXPECT_EQ(model.Indication(Led::kModuleStatus, 6 * hal::kMicrosPerSecond).pattern, LedPattern::kOff);
}

}  // namespace
}  // namespace net
