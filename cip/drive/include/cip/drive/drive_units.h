// Unit conversions of the drive profile (seed 000 §4.5, §4.7, §5; docs/drive-profile.md "Conversions").
//
// - Speed: the CIP assemblies 20/21/70/71/101/151 and the AC/DC Drive object speak rpm ("min-1"); the
//   inverter speaks 0.01 Hz (FA07, FD00, FE02). f856 is the number of motor pole PAIRS (§3.1: 1 = 2 poles
//   ... 8 = 16 poles; §4.5 PoleCount = f856 x 2), so rpm = Hz x 120 / poles = Hz x 60 / f856, i.e. in
//   0.01 Hz units rpm = f x 3 / (5 x f856) and f = rpm x 5 x f856 / 3. Both directions round to the
//   nearest unit, halves up. With the factory f856 = 2: 1800 rpm <-> 6000 (60.00 Hz), §5's examples.
// - Time: AccelTime/DecelTime (§4.7 attributes 18/19) are ms; acc (0009) / dec (0010) count 0.1 s, or
//   0.01 s when f519 = 1 (§3.1 (*2)).
// - Current: CurrentActual (§4.7 attribute 9) is 0.1 A; FD03 is 0.01 % of the drive's rated current,
//   FE70 the rated current in 0.1 A.
// Everything is constexpr and saturating: no input makes a result wrap.
#pragma once

#include <cstdint>

namespace cip::drive {

// The highest FA07 the card derives from an rpm reference: 500.00 Hz, the drive's maximum frequency
// range. The inverter follows fh/ul anyway (§4.7 note); a larger value would be refused (0001).
inline constexpr std::uint16_t kMaxFrequencyCommand = 50000;
// rpm values travel as INT (§4.7 SpeedActual/SpeedRef); a speed above it reads as this.
inline constexpr std::uint16_t kMaxRpm = 32767;
// f856's range and factory value (§3.1).
inline constexpr std::uint16_t kMinPolePairs = 1;
inline constexpr std::uint16_t kMaxPolePairs = 8;
inline constexpr std::uint16_t kFactoryPolePairs = 2;

// f856 as used: a value outside 1-8 (ParseCardConfig never passes one) counts as the factory 2.
constexpr std::uint16_t UsablePolePairs(std::uint16_t f856) {
  return f856 >= kMinPolePairs && f856 <= kMaxPolePairs ? f856 : kFactoryPolePairs;
}

// 0.01 Hz -> rpm, rounded to the nearest rpm (halves up), at most kMaxRpm.
constexpr std::uint16_t FrequencyToRpm(std::uint16_t centi_hz, std::uint16_t f856) {
  const std::uint32_t divisor = 5u * UsablePolePairs(f856);
  const std::uint32_t rpm = (3u * centi_hz + divisor / 2) / divisor;
  return static_cast<std::uint16_t>(rpm > kMaxRpm ? kMaxRpm : rpm);
}

// rpm -> 0.01 Hz, rounded to the nearest 0.01 Hz (halves up). A negative reference is 0 (FA07 is
// unsigned; the direction is FA06 bit 9, from Run Fwd/Run Rev). At most kMaxFrequencyCommand.
constexpr std::uint16_t RpmToFrequency(std::int32_t rpm, std::uint16_t f856) {
  if (rpm <= 0) return 0;
  const std::uint32_t magnitude = rpm > 0xFFFF ? 0xFFFFu : static_cast<std::uint32_t>(rpm);
  // N / 3 ends in .0, .33 or .67, never in .5: adding 1 before dividing rounds .67 up and .33 down.
  const std::uint32_t f = (magnitude * 5u * UsablePolePairs(f856) + 1u) / 3u;
  return static_cast<std::uint16_t>(f > kMaxFrequencyCommand ? kMaxFrequencyCommand : f);
}

// acc/dec value -> ms (AccelTime/DecelTime are UINT: at most 65535 ms, although acc reaches 6000 s).
constexpr std::uint16_t TimeParameterToMillis(std::uint16_t value, bool f519_hundredths) {
  const std::uint32_t ms = static_cast<std::uint32_t>(value) * (f519_hundredths ? 10u : 100u);
  return static_cast<std::uint16_t>(ms > 0xFFFF ? 0xFFFFu : ms);
}

// ms -> acc/dec value, rounded to the nearest unit (halves up).
constexpr std::uint16_t MillisToTimeParameter(std::uint16_t ms, bool f519_hundredths) {
  const std::uint32_t unit = f519_hundredths ? 10u : 100u;
  return static_cast<std::uint16_t>((ms + unit / 2) / unit);
}

// FD03 (0.01 % of rated) and FE70 (rated, 0.1 A) -> 0.1 A, rounded to the nearest 0.1 A, at most 65535.
constexpr std::uint16_t CurrentTenthsOfAmp(std::uint16_t fd03, std::uint16_t fe70) {
  const std::uint64_t tenths = (static_cast<std::uint64_t>(fd03) * fe70 + 5000u) / 10000u;
  return static_cast<std::uint16_t>(tenths > 0xFFFF ? 0xFFFFu : tenths);
}

}  // namespace cip::drive
