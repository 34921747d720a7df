// The MS and NS indicators (manual §2.4, NET-5): one state model for both protocols. The card's
// condition goes in as LedInputs; out come, per LED, a pattern with its colour (LedIndication) and the
// colour the LED shows at any instant. LNK (one per port) is firmware/card_indicators'; it only takes
// its power-up test colours from here (LinkTestColor), so that all four LEDs run one test.
//
// Tables (§2.4), highest priority first; "test" = the power-up test, which overrides everything:
//
//   EtherNet/IP MS   major fault                 red steady      "non-recoverable major fault"
//                    minor fault                 red flashing    "recoverable minor fault"
//                    not configured              green flashing  "has not been configured"
//                    otherwise                   green steady    "operating correctly"
//   EtherNet/IP NS   duplicate IP address        red steady
//                    no IP address               off
//                    a target connection timed   red flashing    (until re-established or reset)
//                      out (exclusive owner)
//                    a connection established    green steady
//                    otherwise                   green flashing  "no established connection"
//   Modbus TCP MS    major fault (e-23)          red steady      (shown with or without an address)
//                    no IP address               off
//                    communication error (err8)  red flashing    = connections kTimedOut
//                    no port linked / not ready  green flashing  "waiting for cable connection or etc."
//                    otherwise                   green steady    "ready"
//   Modbus TCP NS    duplicate IP address        green, 4 flashes
//                    BOOTP/DHCP in progress      green, 5 flashes
//                    no IP address               off
//                    all ports unplugged         green, 3 flashes (the card keeps its address)
//                    otherwise                   green steady    "a port connected and an address"
//
// A duplicate address and a running BOOTP/DHCP sequence outrank "no IP address" because the card has
// no usable address in both cases, yet the table gives them their own pattern. A Modbus TCP minor fault
// has no row of its own: it does not show.
//
// Timing (docs/network.md "LED model"):
//   flashing        0.5 s on, 0.5 s off, starting with on: the CIP indicator flash rate (1 Hz).
//   flashing N      N x (0.2 s on, 0.2 s off), then 0.8 s more off, so that 1 s of dark separates the
//                   groups and the count can be read; period N x 0.4 s + 0.8 s. The manual names the
//                   patterns but gives no timing: this is our choice.
//   power-up test   0.25 s steps (the CIP indicator test): MS green, MS red, then MS green while NS goes
//                   green, red; NS is off during the MS steps; LNK goes green, red with MS, then off.
//                   1 s in all, then every LED follows its inputs.
// A pattern starts at the instant its indication (pattern or colour) changes, so a new "flashing 4
// times" begins with its first flash; an update that leaves an indication unchanged keeps its phase.
#pragma once

#include <array>
#include <cstdint>
#include <optional>

#include "hal/clock.h"
#include "hal/leds.h"

namespace net {

enum class Protocol : std::uint8_t { kModbusTcp = 0, kEtherNetIp = 1 };  // c500
enum class ModuleFault : std::uint8_t { kNone, kMinor, kMajor };
// EtherNet/IP: the connections this card is the target of (kTimedOut: an exclusive owner connection
// timed out and has not been re-established). Modbus TCP: kTimedOut when the card's loss detection
// (c523 timeout on traffic or IO scanning) fired, i.e. the drive shows err8.
enum class ConnectionState : std::uint8_t { kNone, kEstablished, kTimedOut };

struct LedInputs {
  Protocol protocol = Protocol::kModbusTcp;
  // Parameters valid and the inverter link up (EtherNet/IP "configured", Modbus TCP "ready").
  bool configured = false;
  ModuleFault fault = ModuleFault::kNone;
  bool has_address = false;        // an IP address is in use (manual, BOOTP or DHCP, ACD passed)
  bool acquiring_address = false;  // a BOOTP or DHCP sequence is running
  bool duplicate_address = false;  // ACD found the address in use by another host (and gave it up)
  bool any_link_up = false;        // at least one of ports L and R has link
  ConnectionState connections = ConnectionState::kNone;

  bool operator==(const LedInputs&) const = default;
};

enum class LedPattern : std::uint8_t {
  kOff,
  kSteady,
  kFlashing,
  kFlashing3Times,
  kFlashing4Times,
  kFlashing5Times,
  kPowerUpTest,
};

struct LedIndication {
  LedPattern pattern = LedPattern::kOff;
  hal::LedColor color = hal::LedColor::kOff;  // the lit colour; kOff for kOff and kPowerUpTest

  bool operator==(const LedIndication&) const = default;
};

// Flash timing (see the header comment).
inline constexpr hal::Micros kFlashOn = 500 * hal::kMicrosPerMilli;
inline constexpr hal::Micros kFlashOff = 500 * hal::kMicrosPerMilli;
inline constexpr hal::Micros kCountedFlashOn = 200 * hal::kMicrosPerMilli;
inline constexpr hal::Micros kCountedFlashOff = 200 * hal::kMicrosPerMilli;
inline constexpr hal::Micros kCountedFlashPause = 800 * hal::kMicrosPerMilli;  // after the last flash's off
inline constexpr hal::Micros kPowerUpTestStep = 250 * hal::kMicrosPerMilli;
inline constexpr hal::Micros kPowerUpTestDuration = 4 * kPowerUpTestStep;

// The tables above (never kPowerUpTest: the test is the model's, not the inputs').
LedIndication ModuleStatusIndication(const LedInputs& inputs);
LedIndication NetworkStatusIndication(const LedInputs& inputs);

// The colour `indication` shows `elapsed` µs after it began (kPowerUpTest: off; use PowerUpTestColor).
hal::LedColor PatternColor(const LedIndication& indication, hal::Micros elapsed);
// The smallest offset > `elapsed` at which PatternColor may differ; hal::kNever for off and steady.
hal::Micros NextPatternChange(const LedIndication& indication, hal::Micros elapsed);
// The colour of `led` `elapsed` µs into the power-up test (off from kPowerUpTestDuration on).
hal::LedColor PowerUpTestColor(hal::Led led, hal::Micros elapsed);

class LedModel {
 public:
  // All inputs default (no address, nothing configured): both LEDs are off until Update.
  LedModel() = default;

  // Runs the power-up test from `now` for kPowerUpTestDuration; MS and NS patterns start afresh after it.
  void StartPowerUpTest(hal::Micros now);
  bool PowerUpTestRunning(hal::Micros now) const;

  // New inputs at `now`. Each LED whose indication changes restarts its pattern at `now`.
  void Update(const LedInputs& inputs, hal::Micros now);
  const LedInputs& Inputs() const { return inputs_; }

  // MS and NS only (kOff / off for the LNK LEDs): kPowerUpTest while the test runs.
  LedIndication Indication(hal::Led led, hal::Micros now) const;
  hal::LedColor ColorAt(hal::Led led, hal::Micros now) const;
  // The colour a LNK LED shows while the test runs; nullopt once it is over (CardIndicators then shows the link).
  std::optional<hal::LedColor> LinkTestColor(hal::Micros now) const;

  // The earliest instant after `now` at which any LED this model drives (MS, NS, LNK during the test)
  // may change colour; hal::kNever when all are steady. The event loop's deadline.
  hal::Micros NextChange(hal::Micros now) const;

  // Sets MS and NS to their colours at `now` (hal::Leds ignores a colour that does not change).
  void Drive(hal::Leds& leds, hal::Micros now) const;

 private:
  static constexpr std::size_t kMs = 0;
  static constexpr std::size_t kNs = 1;
  static std::optional<std::size_t> Slot(hal::Led led);
  // When the pattern of `slot` began, as far as its phase goes: never before the end of the test.
  hal::Micros Origin(std::size_t slot) const;

  LedInputs inputs_{};
  std::array<LedIndication, 2> indication_{};
  std::array<hal::Micros, 2> since_{};
  bool test_started_ = false;
  hal::Micros test_start_ = 0;
};

}  // namespace net
