// Communication numbers the simulated inverter's behaviour model acts on. Every one must be a row of
// registers.csv: InverterModel aborts on a missing one the first time it looks it up, and the unit tests
// (sim/test/inverter_*_test.cc) reach every one. This header only names them.
//
// Numbers the card acts on too are defined once, in drive_link/drive_registers.h, and only brought in
// here; the rest are the simulator's own.
#pragma once

#include <cstdint>

#include "drive_link/drive_registers.h"

namespace sim::reg {

// Shared with the card.
using drive_link::reg::kAcc;
using drive_link::reg::kC001;
using drive_link::reg::kC021;
using drive_link::reg::kC100;
using drive_link::reg::kC101;
using drive_link::reg::kC102;
using drive_link::reg::kC103;
using drive_link::reg::kC523;
using drive_link::reg::kCmod;
using drive_link::reg::kDec;
using drive_link::reg::kF207;
using drive_link::reg::kF856;
using drive_link::reg::kF899;
using drive_link::reg::kFa00;
using drive_link::reg::kFa01;
using drive_link::reg::kFa06;
using drive_link::reg::kFa07;
using drive_link::reg::kFa23;
using drive_link::reg::kFa30;
using drive_link::reg::kFa50;
using drive_link::reg::kFa51;
using drive_link::reg::kFc90;
using drive_link::reg::kFc91;
using drive_link::reg::kFd00;
using drive_link::reg::kFd01;
using drive_link::reg::kFe14;
using drive_link::reg::kFmod;
using drive_link::reg::kUl;
using drive_link::reg::kVb;
using drive_link::reg::kVlv;

// The simulator's own.
inline constexpr std::uint16_t kFmsl = 0x0005;
inline constexpr std::uint16_t kTyp = 0x0007;
inline constexpr std::uint16_t kFh = 0x0011;
inline constexpr std::uint16_t kLl = 0x0013;
inline constexpr std::uint16_t kVl = 0x0014;
inline constexpr std::uint16_t kSr1 = 0x0018;  // sr1-sr7 = 0018-0024 (0019, 0020: no A-F numbers)
inline constexpr std::uint16_t kF109 = 0x0109;
inline constexpr std::uint16_t kF111 = 0x0111;  // f111-f118
inline constexpr std::uint16_t kF130 = 0x0130;
inline constexpr std::uint16_t kF131 = 0x0131;
inline constexpr std::uint16_t kF132 = 0x0132;
inline constexpr std::uint16_t kF170 = 0x0170;
inline constexpr std::uint16_t kF171 = 0x0171;
inline constexpr std::uint16_t kF172 = 0x0172;
inline constexpr std::uint16_t kF219 = 0x0219;
inline constexpr std::uint16_t kF268 = 0x0268;
inline constexpr std::uint16_t kF287 = 0x0287;  // f287-f294: preset speeds 8-15
inline constexpr std::uint16_t kF405 = 0x0405;
inline constexpr std::uint16_t kF415 = 0x0415;
inline constexpr std::uint16_t kF417 = 0x0417;
inline constexpr std::uint16_t kF500 = 0x0500;
inline constexpr std::uint16_t kF501 = 0x0501;
inline constexpr std::uint16_t kF510 = 0x0510;
inline constexpr std::uint16_t kF511 = 0x0511;
inline constexpr std::uint16_t kF519 = 0x0519;
inline constexpr std::uint16_t kF749 = 0x0749;
inline constexpr std::uint16_t kF814 = 0x0814;
inline constexpr std::uint16_t kFd03 = 0xFD03;
inline constexpr std::uint16_t kFd04 = 0xFD04;
inline constexpr std::uint16_t kFd05 = 0xFD05;
inline constexpr std::uint16_t kFd06 = 0xFD06;
inline constexpr std::uint16_t kFd07 = 0xFD07;
inline constexpr std::uint16_t kFd16 = 0xFD16;
inline constexpr std::uint16_t kFd18 = 0xFD18;
inline constexpr std::uint16_t kFd20 = 0xFD20;
inline constexpr std::uint16_t kFd22 = 0xFD22;
inline constexpr std::uint16_t kFd23 = 0xFD23;
inline constexpr std::uint16_t kFd24 = 0xFD24;
inline constexpr std::uint16_t kFd25 = 0xFD25;
inline constexpr std::uint16_t kFd26 = 0xFD26;
inline constexpr std::uint16_t kFd27 = 0xFD27;
inline constexpr std::uint16_t kFd29 = 0xFD29;
inline constexpr std::uint16_t kFd30 = 0xFD30;
inline constexpr std::uint16_t kFd83 = 0xFD83;
inline constexpr std::uint16_t kFe00 = 0xFE00;
inline constexpr std::uint16_t kFe01 = 0xFE01;
inline constexpr std::uint16_t kFe02 = 0xFE02;
inline constexpr std::uint16_t kFe03 = 0xFE03;
inline constexpr std::uint16_t kFe04 = 0xFE04;
inline constexpr std::uint16_t kFe05 = 0xFE05;
inline constexpr std::uint16_t kFe06 = 0xFE06;
inline constexpr std::uint16_t kFe07 = 0xFE07;
inline constexpr std::uint16_t kFe10 = 0xFE10;  // FE10-FE13 trip history
inline constexpr std::uint16_t kFe13 = 0xFE13;
inline constexpr std::uint16_t kFe15 = 0xFE15;
inline constexpr std::uint16_t kFe16 = 0xFE16;
inline constexpr std::uint16_t kFe18 = 0xFE18;
inline constexpr std::uint16_t kFe20 = 0xFE20;
inline constexpr std::uint16_t kFe21 = 0xFE21;
inline constexpr std::uint16_t kFe22 = 0xFE22;
inline constexpr std::uint16_t kFe26 = 0xFE26;
inline constexpr std::uint16_t kFe27 = 0xFE27;
inline constexpr std::uint16_t kFe29 = 0xFE29;
inline constexpr std::uint16_t kFe30 = 0xFE30;
inline constexpr std::uint16_t kFe35 = 0xFE35;  // FE35-FE37 analog inputs
inline constexpr std::uint16_t kFe40 = 0xFE40;
inline constexpr std::uint16_t kFe56 = 0xFE56;
inline constexpr std::uint16_t kFe70 = 0xFE70;
inline constexpr std::uint16_t kFe71 = 0xFE71;
inline constexpr std::uint16_t kFe76 = 0xFE76;
inline constexpr std::uint16_t kFe77 = 0xFE77;
inline constexpr std::uint16_t kFe80 = 0xFE80;

// The communication number whose hex digits read as the decimal `n`: titles count in decimal and
// numbers ending in A-F do not exist, so sr1 = 0018 is followed by sr3 = 0020 and f289 by f290.
constexpr std::uint16_t DecimalDigits(int n) {
  return static_cast<std::uint16_t>((n / 1000) << 12 | (n / 100 % 10) << 8 | (n / 10 % 10) << 4 | n % 10);
}

// Preset speed n (1-15): sr1-sr7 = 0018-0024, then f287-f294.
constexpr std::uint16_t PresetSpeed(int n) { return DecimalDigits(n <= 7 ? 17 + n : 279 + n); }
static_assert(PresetSpeed(1) == 0x0018 && PresetSpeed(2) == 0x0019 && PresetSpeed(3) == 0x0020 &&
              PresetSpeed(7) == 0x0024 && PresetSpeed(8) == 0x0287 && PresetSpeed(15) == 0x0294);

}  // namespace sim::reg
