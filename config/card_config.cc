// The card's configuration as read from the inverter: menu tables (seed 000 §3.1), the numbers read at
// start-up, their validation (ParseCardConfig) and the drive status code c555.
#include "config/card_config.h"

#include "drive_link/drive_registers.h"

namespace config {

namespace reg = drive_link::reg;

namespace {

// c001-c006 menus 0-17 (seed 000 §3.1); 0 = "-" (not used) and the reserved entries 4, 7, 9-12.
constexpr std::array<std::uint16_t, 18> kCommandTargets = {
    0,          reg::kFa06, reg::kFa23, reg::kFa07, 0,        reg::kFa50,
    reg::kFa51, 0,          reg::kF601, 0,          0,        0,
    0,          reg::kAcc,  reg::kDec,  reg::kUl,   reg::kVb, reg::kVlv,
};

// c021-c026 menus 0-35 (seed 000 §3.1); 0 = "-" and the reserved entries 15-18, 24.
constexpr std::array<std::uint16_t, 36> kMonitorSources = {
    0,      0xFD01, 0xFD00, 0xFD03, 0xFD05, 0xFC91, 0xFD22, 0xFD06, 0xFD07, 0xFE36, 0xFE35, 0xFE37,
    0xFD04, 0xFD16, 0xFD18, 0,      0,      0,      0,      0x0880, 0xFD29, 0xFD30, 0xFE14, 0xFE40,
    0,      0xFD20, 0xFD23, 0xFD24, 0xFD25, 0xFD26, 0xFD27, 0xFE56, 0xFE70, 0xFE76, 0xFE77, 0xFD83,
};

// Device-name characters: printable ASCII; 0 ends the name (seed 000 §3.2.1: one ASCII character each).
constexpr std::uint16_t kFirstNameCharacter = 0x20;
constexpr std::uint16_t kLastNameCharacter = 0x7E;

// Builds kConfigNumbers in the order the header documents.
constexpr std::array<std::uint16_t, kConfigNumberCount> MakeConfigNumbers() {
  std::array<std::uint16_t, kConfigNumberCount> numbers{};
  std::size_t n = 0;
  for (std::uint16_t i = 0; i < 6; ++i) numbers[n++] = static_cast<std::uint16_t>(reg::kC001 + i);
  for (std::uint16_t i = 0; i < 6; ++i) numbers[n++] = static_cast<std::uint16_t>(reg::kC021 + i);
  // c081-c096: the titles count in decimal, so C089 is followed by C090 (numbers ending A-F do not exist).
  for (std::uint16_t i = 1; i <= 9; ++i) numbers[n++] = static_cast<std::uint16_t>(0xC080 + i);
  for (std::uint16_t i = 0; i <= 6; ++i) numbers[n++] = static_cast<std::uint16_t>(0xC090 + i);
  for (std::uint16_t i = 0; i < 4; ++i) numbers[n++] = static_cast<std::uint16_t>(reg::kC100 + i);
  numbers[n++] = reg::kC500;
  numbers[n++] = reg::kC501;
  // c504-c516: c504, then c505-c509 and c510-c516 (decimal titles again).
  for (std::uint16_t i = 4; i <= 9; ++i) numbers[n++] = static_cast<std::uint16_t>(0xC500 + i);
  for (std::uint16_t i = 0; i <= 6; ++i) numbers[n++] = static_cast<std::uint16_t>(0xC510 + i);
  numbers[n++] = reg::kC523;
  numbers[n++] = reg::kC554;
  for (std::uint16_t i = 0; i <= 4; ++i) numbers[n++] = static_cast<std::uint16_t>(reg::kC600 + i);
  numbers[n++] = reg::kCmod;
  numbers[n++] = reg::kFmod;
  numbers[n++] = reg::kF856;
  return numbers;
}

// Positions in kConfigNumbers (and in the reads handed to ParseCardConfig).
constexpr std::size_t kCommandMenusAt = 0;
constexpr std::size_t kMonitorMenusAt = 6;
constexpr std::size_t kDeviceNameAt = 12;
constexpr std::size_t kLossAt = 28;  // c100-c103
constexpr std::size_t kProtocolAt = 32;
constexpr std::size_t kRateAt = 33;
constexpr std::size_t kIpModeAt = 34;
constexpr std::size_t kIpAt = 35;       // c505-c508
constexpr std::size_t kNetmaskAt = 39;  // c509-c512
constexpr std::size_t kGatewayAt = 43;  // c513-c516
constexpr std::size_t kTimeoutAt = 47;
constexpr std::size_t kWebAt = 48;
constexpr std::size_t kMasterAt = 49;  // c600-c603
constexpr std::size_t kIoScanAt = 53;
constexpr std::size_t kCmodAt = 54;
constexpr std::size_t kFmodAt = 55;
constexpr std::size_t kPolePairsAt = 56;

// Collects problems and hands out validated values.
class Parser {
 public:
  Parser(std::span<const AccessResult, kConfigNumberCount> reads, ParsedConfig& out) : reads_(reads), out_(out) {}

  // The value read at `index` if it was read and `valid(value)` holds; otherwise `fallback`, and a
  // problem of `kind` (kUnreadable for a failed read).
  template <typename Valid>
  std::uint16_t Take(std::size_t index, std::uint16_t fallback, ConfigProblem::Kind kind, Valid valid) {
    const AccessResult& read = reads_[index];
    if (!read.ok()) {
      Report(ConfigProblem{kConfigNumbers[index], read.value, ConfigProblem::Kind::kUnreadable, read.error});
      return fallback;
    }
    if (!valid(read.value)) {
      Report(ConfigProblem{kConfigNumbers[index], read.value, kind, AccessError::kNone});
      return fallback;
    }
    return read.value;
  }

  std::uint16_t Range(std::size_t index, std::uint16_t fallback, std::uint16_t min, std::uint16_t max) {
    return Take(index, fallback, ConfigProblem::Kind::kOutOfRange,
                [min, max](std::uint16_t v) { return v >= min && v <= max; });
  }

  std::uint8_t Octet(std::size_t index, std::uint8_t fallback) {
    return static_cast<std::uint8_t>(Range(index, fallback, 0, 255));
  }

  void Octets(std::size_t first, base::Ipv4Address& address) {
    base::Ipv4Address::Octets octets = address.octets();
    for (std::size_t i = 0; i < octets.size(); ++i) octets[i] = Octet(first + i, octets[i]);
    address = base::Ipv4Address(octets);
  }

 private:
  void Report(const ConfigProblem& problem) {
    if (out_.problem_count < out_.problems.size()) out_.problems[out_.problem_count++] = problem;
    ++out_.problems_total;
  }

  std::span<const AccessResult, kConfigNumberCount> reads_;
  ParsedConfig& out_;
};

}  // namespace

const std::array<std::uint16_t, kConfigNumberCount> kConfigNumbers = MakeConfigNumbers();

std::uint16_t CommandMenuTarget(std::uint16_t menu) {
  return menu < kCommandTargets.size() ? kCommandTargets[menu] : 0;
}

std::uint16_t MonitorMenuSource(std::uint16_t menu) {
  return menu < kMonitorSources.size() ? kMonitorSources[menu] : 0;
}

bool IsCommandMenuValid(std::uint16_t menu) { return menu == 0 || CommandMenuTarget(menu) != 0; }

bool IsMonitorMenuValid(std::uint16_t menu) { return menu == 0 || MonitorMenuSource(menu) != 0; }

ParsedConfig ParseCardConfig(std::span<const AccessResult, kConfigNumberCount> reads) {
  ParsedConfig parsed;
  CardConfig& c = parsed.config;
  Parser p(reads, parsed);

  for (std::size_t i = 0; i < kScannerWordCount; ++i) {
    c.command_menus[i] = p.Take(kCommandMenusAt + i, c.command_menus[i], ConfigProblem::Kind::kReservedMenu,
                                IsCommandMenuValid);
    c.monitor_menus[i] = p.Take(kMonitorMenusAt + i, c.monitor_menus[i], ConfigProblem::Kind::kReservedMenu,
                                IsMonitorMenuValid);
  }

  // The name ends at the first 0; a character that is not printable ASCII is reported and ends it too.
  bool ended = false;
  std::size_t length = 0;
  for (std::size_t i = 0; i < 16; ++i) {
    const std::uint16_t ch = p.Take(kDeviceNameAt + i, 0, ConfigProblem::Kind::kOutOfRange, [](std::uint16_t v) {
      return v == 0 || (v >= kFirstNameCharacter && v <= kLastNameCharacter);
    });
    if (ch == 0) ended = true;
    if (!ended) c.device_name[length++] = static_cast<char>(ch);
  }
  c.device_name[length] = '\0';

  c.loss_delay_tenths = p.Range(kLossAt + 0, c.loss_delay_tenths, 0, 1000);
  c.loss_action = p.Range(kLossAt + 1, c.loss_action, 0, 5);
  c.loss_preset_speed = p.Range(kLossAt + 2, c.loss_preset_speed, 0, 15);
  c.loss_condition = p.Range(kLossAt + 3, c.loss_condition, 0, 2);
  c.protocol = static_cast<Protocol>(p.Range(kProtocolAt, static_cast<std::uint16_t>(c.protocol), 0, 1));
  c.rate_setting = p.Range(kRateAt, c.rate_setting, 0, 4);
  c.ip_mode = static_cast<IpMode>(p.Range(kIpModeAt, static_cast<std::uint16_t>(c.ip_mode), 0, 2));
  p.Octets(kIpAt, c.ip);
  p.Octets(kNetmaskAt, c.netmask);
  p.Octets(kGatewayAt, c.gateway);
  // c523: 0.0 (disabled) or 0.5-60.0 s (seed 000 §3.2.3).
  c.timeout_tenths = p.Take(kTimeoutAt, c.timeout_tenths, ConfigProblem::Kind::kOutOfRange,
                            [](std::uint16_t v) { return v == 0 || (v >= 5 && v <= 600); });
  c.web_server = p.Range(kWebAt, static_cast<std::uint16_t>(c.web_server ? 1 : 0), 0, 1) == 1;
  p.Octets(kMasterAt, c.modbus_master);
  c.io_scanning = p.Range(kIoScanAt, static_cast<std::uint16_t>(c.io_scanning ? 1 : 0), 0, 1) == 1;
  // fmod 12-14 exist on VF-S15 only; the card accepts the union of both models.
  c.cmod = p.Range(kCmodAt, c.cmod, 0, 4);
  c.fmod = p.Range(kFmodAt, c.fmod, 0, 14);
  c.pole_pairs = p.Range(kPolePairsAt, c.pole_pairs, 1, 8);
  return parsed;
}

std::uint16_t DriveStatusCode(std::uint16_t fd01) {
  if ((fd01 & reg::status_bit::kTripped) != 0) return 23;
  if ((fd01 & reg::status_bit::kRunning) != 0) return 4;
  return 3;
}

}  // namespace config
