// The card configuration (config/include/config/card_config.h): the scanner menu tables
// (seed 000 §3.1), the numbers read at start-up, ParseCardConfig's validation and problem reports, c555.
#include "config/card_config.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <map>
#include <set>
#include <string>

#include "drive_link/drive_registers.h"

namespace config {
namespace {

namespace reg = drive_link::reg;

// Every menu of c001-c006 with its register (seed 000 §3.1); the others are reserved ("-").
const std::map<std::uint16_t, std::uint16_t> kCommandMenus = {
    {1, 0xFA06}, {2, 0xFA23}, {3, 0xFA07},  {5, 0xFA50},  {6, 0xFA51},  {8, 0x0601},
    {13, 0x0009}, {14, 0x0010}, {15, 0x0012}, {16, 0x0016}, {17, 0x0409},
};

// Every menu of c021-c026 with its register (seed 000 §3.1).
const std::map<std::uint16_t, std::uint16_t> kMonitorMenus = {
    {1, 0xFD01},  {2, 0xFD00},  {3, 0xFD03},  {4, 0xFD05},  {5, 0xFC91},  {6, 0xFD22},  {7, 0xFD06},
    {8, 0xFD07},  {9, 0xFE36},  {10, 0xFE35}, {11, 0xFE37}, {12, 0xFD04}, {13, 0xFD16}, {14, 0xFD18},
    {19, 0x0880}, {20, 0xFD29}, {21, 0xFD30}, {22, 0xFE14}, {23, 0xFE40}, {25, 0xFD20}, {26, 0xFD23},
    {27, 0xFD24}, {28, 0xFD25}, {29, 0xFD26}, {30, 0xFD27}, {31, 0xFE56}, {32, 0xFE70}, {33, 0xFE76},
    {34, 0xFE77}, {35, 0xFD83},
};

// The seed's factory settings of everything ParseCardConfig reads (seed 000 §3.1).
std::map<std::uint16_t, std::uint16_t> FactorySettings() {
  std::map<std::uint16_t, std::uint16_t> values;
  for (std::uint16_t number : kConfigNumbers) values[number] = 0;
  values[0xC001] = 1;
  values[0xC002] = 3;
  values[0xC021] = 1;
  values[0xC022] = 2;
  values[0xC101] = 4;
  values[0xC523] = 20;
  values[0xC554] = 1;
  values[0x0003] = 1;
  values[0x0856] = 2;
  return values;
}

std::array<AccessResult, kConfigNumberCount> Reads(const std::map<std::uint16_t, std::uint16_t>& values) {
  std::array<AccessResult, kConfigNumberCount> reads{};
  for (std::size_t i = 0; i < kConfigNumberCount; ++i) {
    reads[i].number = kConfigNumbers[i];
    reads[i].value = values.at(kConfigNumbers[i]);
  }
  return reads;
}

ParsedConfig ParseWith(std::initializer_list<std::pair<const std::uint16_t, std::uint16_t>> changes) {
  std::map<std::uint16_t, std::uint16_t> values = FactorySettings();
  for (const auto& [number, value] : changes) values[number] = value;
  return ParseCardConfig(Reads(values));
}

std::size_t IndexOf(std::uint16_t number) {
  return static_cast<std::size_t>(std::find(kConfigNumbers.begin(), kConfigNumbers.end(), number) -
                                  kConfigNumbers.begin());
}

TEST(CardConfigTest, CommandMenuTableMatchesTheManual) {
  for (std::uint16_t menu = 0; menu <= 40; ++menu) {
    const auto it = kCommandMenus.find(menu);
    const std::uint16_t expected = it == kCommandMenus.end() ? 0 : it->second;
    EXPECT_EQ(CommandMenuTarget(menu), expected) << "menu " << menu;
    EXPECT_EQ(IsCommandMenuValid(menu), menu == 0 || expected != 0) << "menu " << menu;
  }
  for (const int menu : {4, 7, 9, 10, 11, 12, 18, 0xFFFF}) {
    const auto reserved = static_cast<std::uint16_t>(menu);
    EXPECT_FALSE(IsCommandMenuValid(reserved)) << reserved;
    EXPECT_EQ(CommandMenuTarget(reserved), 0) << reserved;
  }
}

TEST(CardConfigTest, MonitorMenuTableMatchesTheManual) {
  for (std::uint16_t menu = 0; menu <= 60; ++menu) {
    const auto it = kMonitorMenus.find(menu);
    const std::uint16_t expected = it == kMonitorMenus.end() ? 0 : it->second;
    EXPECT_EQ(MonitorMenuSource(menu), expected) << "menu " << menu;
    EXPECT_EQ(IsMonitorMenuValid(menu), menu == 0 || expected != 0) << "menu " << menu;
  }
  for (const int menu : {15, 16, 17, 18, 24, 36, 0xFFFF}) {
    EXPECT_FALSE(IsMonitorMenuValid(static_cast<std::uint16_t>(menu))) << menu;
  }
}

TEST(CardConfigTest, ConfigNumbersAreTheDocumentedListWithoutHexDigitsAboveNine) {
  ASSERT_EQ(kConfigNumbers.size(), 57U);
  const std::array<std::uint16_t, 57> expected = {
      0xC001, 0xC002, 0xC003, 0xC004, 0xC005, 0xC006, 0xC021, 0xC022, 0xC023, 0xC024, 0xC025, 0xC026,
      0xC081, 0xC082, 0xC083, 0xC084, 0xC085, 0xC086, 0xC087, 0xC088, 0xC089, 0xC090, 0xC091, 0xC092,
      0xC093, 0xC094, 0xC095, 0xC096, 0xC100, 0xC101, 0xC102, 0xC103, 0xC500, 0xC501, 0xC504, 0xC505,
      0xC506, 0xC507, 0xC508, 0xC509, 0xC510, 0xC511, 0xC512, 0xC513, 0xC514, 0xC515, 0xC516, 0xC523,
      0xC554, 0xC600, 0xC601, 0xC602, 0xC603, 0xC604, 0x0003, 0x0004, 0x0856,
  };
  EXPECT_EQ(kConfigNumbers, expected);
  for (std::uint16_t number : kConfigNumbers) EXPECT_TRUE(reg::HasDecimalLastDigit(number)) << std::hex << number;
  EXPECT_EQ(std::set<std::uint16_t>(kConfigNumbers.begin(), kConfigNumbers.end()).size(), 57U);
}

TEST(CardConfigTest, FactorySettingsParseToTheDefaultsWithoutProblems) {
  const ParsedConfig parsed = ParseCardConfig(Reads(FactorySettings()));
  EXPECT_EQ(parsed.problem_count, 0U);
  EXPECT_EQ(parsed.problems_total, 0U);
  const CardConfig& c = parsed.config;
  const CardConfig defaults;
  EXPECT_EQ(c.command_menus, (std::array<std::uint16_t, 6>{1, 3, 0, 0, 0, 0}));
  EXPECT_EQ(c.monitor_menus, (std::array<std::uint16_t, 6>{1, 2, 0, 0, 0, 0}));
  EXPECT_EQ(std::string(c.device_name.data()), "");
  EXPECT_EQ(c.loss_delay_tenths, 0);
  EXPECT_EQ(c.loss_action, 4);
  EXPECT_EQ(c.loss_preset_speed, 0);
  EXPECT_EQ(c.loss_condition, 0);
  EXPECT_EQ(c.protocol, Protocol::kModbusTcp);
  EXPECT_EQ(c.rate_setting, 0);
  EXPECT_EQ(c.ip_mode, IpMode::kManual);
  EXPECT_EQ(c.ip, (base::Ipv4Address{0, 0, 0, 0}));
  EXPECT_EQ(c.timeout_tenths, 20);
  EXPECT_TRUE(c.web_server);
  EXPECT_FALSE(c.io_scanning);
  EXPECT_EQ(c.cmod, 1);
  EXPECT_EQ(c.fmod, 0);
  EXPECT_EQ(c.pole_pairs, 2);
  EXPECT_EQ(c.command_menus, defaults.command_menus);
  EXPECT_EQ(c.monitor_menus, defaults.monitor_menus);
}

TEST(CardConfigTest, EveryValidMenuIsTaken) {
  for (const auto& [menu, target] : kCommandMenus) {
    const ParsedConfig parsed = ParseWith({{0xC006, menu}});
    EXPECT_EQ(parsed.config.command_menus[5], menu);
    EXPECT_EQ(parsed.problem_count, 0U) << "menu " << menu;
  }
  for (const auto& [menu, source] : kMonitorMenus) {
    const ParsedConfig parsed = ParseWith({{0xC026, menu}});
    EXPECT_EQ(parsed.config.monitor_menus[5], menu);
    EXPECT_EQ(parsed.problem_count, 0U) << "menu " << menu;
  }
}

TEST(CardConfigTest, ReservedMenusAreReportedAndReplacedByTheFactoryDefault) {
  const ParsedConfig parsed = ParseWith({{0xC001, 4}, {0xC003, 18}, {0xC021, 24}, {0xC022, 15}});
  EXPECT_EQ(parsed.config.command_menus, (std::array<std::uint16_t, 6>{1, 3, 0, 0, 0, 0}));
  EXPECT_EQ(parsed.config.monitor_menus, (std::array<std::uint16_t, 6>{1, 2, 0, 0, 0, 0}));
  ASSERT_EQ(parsed.problem_count, 4U);
  EXPECT_EQ(parsed.problems_total, 4U);
  // In the order of kConfigNumbers: c001, c021 come first (per word), then c022, c003.
  const std::array<std::pair<std::uint16_t, std::uint16_t>, 4> expected = {
      {{0xC001, 4}, {0xC021, 24}, {0xC022, 15}, {0xC003, 18}}};
  for (std::size_t i = 0; i < expected.size(); ++i) {
    EXPECT_EQ(parsed.problems[i].number, expected[i].first) << i;
    EXPECT_EQ(parsed.problems[i].value, expected[i].second) << i;
    EXPECT_EQ(parsed.problems[i].kind, ConfigProblem::Kind::kReservedMenu) << i;
    EXPECT_EQ(parsed.problems[i].error, AccessError::kNone) << i;
  }
}

TEST(CardConfigTest, OutOfRangeValuesAreReportedAndReplacedByTheFactoryDefault) {
  struct Case {
    std::uint16_t number;
    std::uint16_t bad;
    std::uint16_t good;  // the largest valid value, taken as read
  };
  const Case cases[] = {
      {0xC100, 1001, 1000}, {0xC101, 6, 5},   {0xC102, 16, 15},  {0xC103, 3, 2},  {0xC500, 2, 1},
      {0xC501, 5, 4},       {0xC504, 3, 2},   {0xC505, 256, 255}, {0xC512, 256, 255}, {0xC516, 300, 255},
      {0xC523, 601, 600},   {0xC554, 2, 1},   {0xC600, 256, 255}, {0xC604, 2, 1},  {0x0003, 5, 4},
      {0x0004, 15, 14},     {0x0856, 9, 8},
  };
  const ParsedConfig defaults = ParseCardConfig(Reads(FactorySettings()));
  for (const Case& c : cases) {
    const ParsedConfig bad = ParseWith({{c.number, c.bad}});
    ASSERT_EQ(bad.problem_count, 1U) << std::hex << c.number;
    EXPECT_EQ(bad.problems[0].number, c.number);
    EXPECT_EQ(bad.problems[0].value, c.bad);
    EXPECT_EQ(bad.problems[0].kind, ConfigProblem::Kind::kOutOfRange);
    const ParsedConfig good = ParseWith({{c.number, c.good}});
    EXPECT_EQ(good.problem_count, 0U) << std::hex << c.number;
  }
  // The defaults stand in for the bad values.
  const CardConfig& d = defaults.config;
  EXPECT_EQ(ParseWith({{0xC100, 1001}}).config.loss_delay_tenths, d.loss_delay_tenths);
  EXPECT_EQ(ParseWith({{0xC101, 6}}).config.loss_action, 4);
  EXPECT_EQ(ParseWith({{0xC500, 2}}).config.protocol, Protocol::kModbusTcp);
  EXPECT_EQ(ParseWith({{0xC504, 3}}).config.ip_mode, IpMode::kManual);
  EXPECT_EQ(ParseWith({{0xC505, 256}}).config.ip.octets()[0], 0);
  EXPECT_EQ(ParseWith({{0xC523, 601}}).config.timeout_tenths, 20);
  EXPECT_TRUE(ParseWith({{0xC554, 2}}).config.web_server);
  EXPECT_EQ(ParseWith({{0x0856, 0}}).config.pole_pairs, 2);
  EXPECT_EQ(ParseWith({{0x0856, 0}}).problems[0].kind, ConfigProblem::Kind::kOutOfRange);
}

TEST(CardConfigTest, TimeoutIsZeroOrHalfASecondToSixty) {
  EXPECT_EQ(ParseWith({{0xC523, 0}}).config.timeout_tenths, 0);
  EXPECT_EQ(ParseWith({{0xC523, 5}}).config.timeout_tenths, 5);
  for (const int value : {1, 4}) {
    const auto bad = static_cast<std::uint16_t>(value);
    const ParsedConfig parsed = ParseWith({{0xC523, bad}});
    EXPECT_EQ(parsed.config.timeout_tenths, 20) << bad;
    EXPECT_EQ(parsed.problem_count, 1U) << bad;
  }
}

TEST(CardConfigTest, AddressesAndFlagsAreTaken) {
  const ParsedConfig parsed = ParseWith({{0xC500, 1}, {0xC501, 3}, {0xC504, 2}, {0xC505, 192}, {0xC506, 168},
                                         {0xC507, 1},  {0xC508, 12}, {0xC509, 255}, {0xC510, 255},
                                         {0xC511, 255}, {0xC512, 0}, {0xC513, 192}, {0xC516, 254},
                                         {0xC554, 0}, {0xC600, 192}, {0xC603, 30}, {0xC604, 1},
                                         {0x0003, 4}, {0x0004, 7}, {0x0856, 4}, {0xC100, 15},
                                         {0xC101, 5}, {0xC102, 7}, {0xC103, 2}});
  EXPECT_EQ(parsed.problem_count, 0U);
  const CardConfig& c = parsed.config;
  EXPECT_EQ(c.protocol, Protocol::kEtherNetIp);
  EXPECT_EQ(c.rate_setting, 3);
  EXPECT_EQ(c.ip_mode, IpMode::kDhcp);
  EXPECT_EQ(c.ip, (base::Ipv4Address{192, 168, 1, 12}));
  EXPECT_EQ(c.netmask, (base::Ipv4Address{255, 255, 255, 0}));
  EXPECT_EQ(c.gateway, (base::Ipv4Address{192, 0, 0, 254}));
  EXPECT_FALSE(c.web_server);
  EXPECT_EQ(c.modbus_master, (base::Ipv4Address{192, 0, 0, 30}));
  EXPECT_TRUE(c.io_scanning);
  EXPECT_EQ(c.cmod, 4);
  EXPECT_EQ(c.fmod, 7);
  EXPECT_EQ(c.pole_pairs, 4);
  EXPECT_EQ(c.loss_delay_tenths, 15);
  EXPECT_EQ(c.loss_action, 5);
  EXPECT_EQ(c.loss_preset_speed, 7);
  EXPECT_EQ(c.loss_condition, 2);
}

TEST(CardConfigTest, DeviceNameFromTheManualsExample) {
  // seed 000 §3.2.1: 'VFMB1-4007PL' in c081-c092, c093-c096 unset.
  const std::string name = "VFMB1-4007PL";
  std::map<std::uint16_t, std::uint16_t> values = FactorySettings();
  for (std::size_t i = 0; i < name.size(); ++i) values[kConfigNumbers[IndexOf(0xC081) + i]] = static_cast<std::uint8_t>(name[i]);
  EXPECT_EQ(values[0xC090], 0x37);  // the 10th character lives in c090, right after c089
  const ParsedConfig parsed = ParseCardConfig(Reads(values));
  EXPECT_EQ(parsed.problem_count, 0U);
  EXPECT_EQ(std::string(parsed.config.device_name.data()), name);
}

TEST(CardConfigTest, DeviceNameStopsAtTheFirstZeroAndHoldsSixteenCharacters) {
  std::map<std::uint16_t, std::uint16_t> values = FactorySettings();
  for (std::size_t i = 0; i < 16; ++i) values[kConfigNumbers[IndexOf(0xC081) + i]] = static_cast<std::uint16_t>('a' + i);
  EXPECT_EQ(std::string(ParseCardConfig(Reads(values)).config.device_name.data()), "abcdefghijklmnop");
  values[0xC084] = 0;
  EXPECT_EQ(std::string(ParseCardConfig(Reads(values)).config.device_name.data()), "abc");
}

TEST(CardConfigTest, ANonPrintableNameCharacterIsReportedAndEndsTheName) {
  const ParsedConfig parsed = ParseWith({{0xC081, 'A'}, {0xC082, 'B'}, {0xC083, 0x07}, {0xC084, 'C'}});
  EXPECT_EQ(std::string(parsed.config.device_name.data()), "AB");
  ASSERT_EQ(parsed.problem_count, 1U);
  EXPECT_EQ(parsed.problems[0].number, 0xC083);
  EXPECT_EQ(parsed.problems[0].value, 0x07);
  EXPECT_EQ(parsed.problems[0].kind, ConfigProblem::Kind::kOutOfRange);
  EXPECT_EQ(ParseWith({{0xC081, 0x7F}}).problem_count, 1U);
  EXPECT_EQ(ParseWith({{0xC081, ' '}, {0xC082, '~'}}).problem_count, 0U);
}

TEST(CardConfigTest, UnreadableValuesKeepTheDefaultAndTheError) {
  std::array<AccessResult, kConfigNumberCount> reads = Reads(FactorySettings());
  reads[IndexOf(0xC001)].error = AccessError::kTimeout;
  reads[IndexOf(0xC001)].value = 9;  // ignored
  reads[IndexOf(0xC101)].error = AccessError::kNoSuchRegister;
  const ParsedConfig parsed = ParseCardConfig(reads);
  EXPECT_EQ(parsed.config.command_menus[0], 1);
  EXPECT_EQ(parsed.config.loss_action, 4);
  ASSERT_EQ(parsed.problem_count, 2U);
  EXPECT_EQ(parsed.problems[0].number, 0xC001);
  EXPECT_EQ(parsed.problems[0].kind, ConfigProblem::Kind::kUnreadable);
  EXPECT_EQ(parsed.problems[0].error, AccessError::kTimeout);
  EXPECT_EQ(parsed.problems[1].number, 0xC101);
  EXPECT_EQ(parsed.problems[1].error, AccessError::kNoSuchRegister);
}

TEST(CardConfigTest, ProblemsBeyondTheRecordAreCounted) {
  std::array<AccessResult, kConfigNumberCount> reads = Reads(FactorySettings());
  for (AccessResult& read : reads) read.error = AccessError::kLinkDown;
  const ParsedConfig parsed = ParseCardConfig(reads);
  EXPECT_EQ(parsed.problem_count, kMaxConfigProblems);
  EXPECT_EQ(parsed.problems_total, kConfigNumberCount);
  EXPECT_EQ(parsed.problems[kMaxConfigProblems - 1].number, kConfigNumbers[kMaxConfigProblems - 1]);
  // Everything fell back to the factory settings.
  EXPECT_EQ(parsed.config.command_menus, CardConfig{}.command_menus);
  EXPECT_EQ(parsed.config.timeout_tenths, 20);
}

TEST(CardConfigTest, DriveStatusCodeFromStatusWord) {
  EXPECT_EQ(DriveStatusCode(0x4800), 3);  // stopped, ST off: gate block
  EXPECT_EQ(DriveStatusCode(0x4000), 3);  // stopped and ready
  EXPECT_EQ(DriveStatusCode(0x6400), 4);  // running at speed
  EXPECT_EQ(DriveStatusCode(0x6600), 4);  // running in reverse
  EXPECT_EQ(DriveStatusCode(0x0003), 23);  // tripped
  EXPECT_EQ(DriveStatusCode(0x0403), 23);  // tripped wins over the run bit
}

TEST(CardConfigTest, AccessErrorNamesAreDistinct) {
  std::set<std::string> names;
  for (int e = 0; e <= static_cast<int>(AccessError::kNetworkLost); ++e) {
    names.insert(AccessErrorName(static_cast<AccessError>(e)));
  }
  EXPECT_EQ(names.size(), 10U);
  EXPECT_EQ(std::string(AccessErrorName(AccessError::kNetworkLost)), "network-lost");
  EXPECT_EQ(std::string(AccessErrorName(AccessError::kReservedForScanner)), "reserved-for-scanner");
}

}  // namespace
}  // namespace config
