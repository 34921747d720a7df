// The card's configuration as it lives in the inverter (c-parameters, PAR-1..PAR-5), and the values the
// card writes back. The card reads kConfigNumbers at start-up and after a communication reset (f899 = 1),
// validates them with ParseCardConfig and runs with the result; a value that is reserved or out of range
// is reported as a ConfigProblem and replaced by its factory default, never used as read.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "base/addresses.h"
#include "config/access_result.h"

namespace config {

// Scanner words: c001-c006 (command), c021-c026 (monitor).
inline constexpr std::size_t kScannerWordCount = 6;

// The register a scanner menu number selects (seed 000 §3.1): c001-c006 menus 0-17, c021-c026 menus
// 0-35. 0 for menu 0 ("-", not used) and for reserved or unknown menus; use the Is*Valid functions to
// tell those apart.
std::uint16_t CommandMenuTarget(std::uint16_t menu);
std::uint16_t MonitorMenuSource(std::uint16_t menu);
bool IsCommandMenuValid(std::uint16_t menu);  // 0,1,2,3,5,6,8,13-17
bool IsMonitorMenuValid(std::uint16_t menu);  // 0-14, 19-23, 25-35

enum class Protocol : std::uint8_t { kModbusTcp = 0, kEtherNetIp = 1 };
enum class IpMode : std::uint8_t { kManual = 0, kBootp = 1, kDhcp = 2 };

struct CardConfig {
  std::array<std::uint16_t, kScannerWordCount> command_menus{1, 3, 0, 0, 0, 0};  // c001-c006
  std::array<std::uint16_t, kScannerWordCount> monitor_menus{1, 2, 0, 0, 0, 0};  // c021-c026
  std::array<char, 17> device_name{};  // c081-c096, NUL-terminated; stops at the first 0 character
  std::uint16_t loss_delay_tenths = 0;       // c100, 0.1 s, 0-1000
  std::uint16_t loss_action = 4;             // c101, 0-5
  std::uint16_t loss_preset_speed = 0;       // c102, 0-15
  std::uint16_t loss_condition = 0;          // c103, 0-2
  Protocol protocol = Protocol::kModbusTcp;  // c500
  std::uint16_t rate_setting = 0;            // c501, 0-4
  IpMode ip_mode = IpMode::kManual;          // c504
  base::Ipv4Address ip{};                    // c505-c508
  base::Ipv4Address netmask{};               // c509-c512
  base::Ipv4Address gateway{};               // c513-c516
  std::uint16_t timeout_tenths = 20;         // c523, 0.1 s: 0 disabled, 5-600
  bool web_server = true;                    // c554
  base::Ipv4Address modbus_master{};         // c600-c603, 0.0.0.0 = any
  bool io_scanning = false;                  // c604
  // Read alongside for the loss condition (c103) and the drive's units.
  std::uint16_t cmod = 1;  // 0003
  std::uint16_t fmod = 0;  // 0004
  std::uint16_t pole_pairs = 2;  // f856
};

// The communication numbers read, in this order, to build a CardConfig (c001-c006, c021-c026,
// c081-c096, c100-c103, c500, c501, c504-c516, c523, c554, c600-c604, 0003, 0004, f856).
inline constexpr std::size_t kConfigNumberCount = 6 + 6 + 16 + 4 + 2 + 13 + 1 + 1 + 5 + 3;
extern const std::array<std::uint16_t, kConfigNumberCount> kConfigNumbers;

struct ConfigProblem {
  std::uint16_t number = 0;  // the communication number
  std::uint16_t value = 0;   // what was read
  enum class Kind : std::uint8_t {
    kReservedMenu,  // a scanner menu the manual leaves "-" (c001 4, 7, 9-12; c021 15-18, 24) or > max
    kOutOfRange,    // outside the parameter's range
    kUnreadable,    // the read failed (the access error is in `error`)
  } kind = Kind::kOutOfRange;
  AccessError error = AccessError::kNone;
};

inline constexpr std::size_t kMaxConfigProblems = 16;

struct ParsedConfig {
  CardConfig config;
  std::array<ConfigProblem, kMaxConfigProblems> problems{};
  std::size_t problem_count = 0;    // problems recorded (at most kMaxConfigProblems)
  std::size_t problems_total = 0;   // problems found, including those not recorded
};

// `reads[i]` is the result of reading kConfigNumbers[i]. A failed read or an invalid value leaves the
// factory default in the config and adds a problem.
ParsedConfig ParseCardConfig(std::span<const AccessResult, kConfigNumberCount> reads);

// The values the card writes back into the inverter (seed 000 §3.1, "written by the card").
struct CardStatus {
  std::array<std::uint16_t, 2> port_rates{};  // c502/c503: 0 unconnected, 1 10M full, 2 10M half,
                                              // 3 100M full, 4 100M half
  base::MacAddress mac{};                     // c517-c522
  base::Ipv4Address ip{};                     // c524-c527
  base::Ipv4Address netmask{};                // c528-c531
  base::Ipv4Address gateway{};                // c532-c535
  std::uint16_t ethernet_error = 0;           // c536: 0 none, 1 IO scanning timeout, 2 overload,
                                              // 3 loss of carrier
  bool operator==(const CardStatus&) const = default;
};

// c555 from the status word FD01: 23 when tripped (bit 1), 4 while running (bit 10), otherwise 3
// (gate block).
std::uint16_t DriveStatusCode(std::uint16_t fd01);

}  // namespace config
