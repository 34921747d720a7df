#include "logging_leds.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <vector>

#include "fake_clock.h"

namespace hal::host {
namespace {

class LoggingLedsTest : public ::testing::Test {
 protected:
  test::FakeClock clock_{1000};
  std::vector<std::string> lines_;
  LoggingLeds leds_{clock_, [this](std::string_view line) { lines_.emplace_back(line); }};
};

TEST_F(LoggingLedsTest, StartsAllOff) {
  EXPECT_EQ(leds_.Current(Led::kLinkLeft), LedColor::kOff);
  EXPECT_EQ(leds_.Current(Led::kNetworkStatus), LedColor::kOff);
  EXPECT_TRUE(leds_.History().empty());
  EXPECT_EQ(leds_.Describe(), "LNK-L=off LNK-R=off MS=off NS=off");
}

TEST_F(LoggingLedsTest, LogsEachChangeWithItsTime) {
  leds_.Set(Led::kModuleStatus, LedColor::kGreen);
  clock_.Set(123456);
  leds_.Set(Led::kNetworkStatus, LedColor::kRed);
  clock_.Advance(500);
  leds_.Set(Led::kModuleStatus, LedColor::kOff);

  EXPECT_EQ(lines_, (std::vector<std::string>{"led MS green t=1000", "led NS red t=123456",
                                              "led MS off t=123956"}));
  EXPECT_EQ(leds_.History(),
            (std::deque<LedChange>{{1000, Led::kModuleStatus, LedColor::kGreen},
                                   {123456, Led::kNetworkStatus, LedColor::kRed},
                                   {123956, Led::kModuleStatus, LedColor::kOff}}));
  EXPECT_EQ(leds_.Current(Led::kModuleStatus), LedColor::kOff);
  EXPECT_EQ(leds_.Current(Led::kNetworkStatus), LedColor::kRed);
}

TEST_F(LoggingLedsTest, SettingTheSameColourAgainIsNotAChange) {
  leds_.Set(Led::kLinkRight, LedColor::kOff);  // already off
  leds_.Set(Led::kLinkRight, LedColor::kYellow);
  clock_.Advance(10);
  leds_.Set(Led::kLinkRight, LedColor::kYellow);
  EXPECT_EQ(lines_, (std::vector<std::string>{"led LNK-R yellow t=1000"}));
  EXPECT_EQ(leds_.History().size(), 1u);
}

TEST_F(LoggingLedsTest, DescribeShowsEveryLed) {
  leds_.Set(Led::kLinkLeft, LedColor::kGreen);
  leds_.Set(Led::kModuleStatus, LedColor::kGreen);
  EXPECT_EQ(leds_.Describe(), "LNK-L=green LNK-R=off MS=green NS=off");
  leds_.Set(Led::kLinkRight, LedColor::kYellow);
  leds_.Set(Led::kNetworkStatus, LedColor::kRed);
  EXPECT_EQ(leds_.Describe(), "LNK-L=green LNK-R=yellow MS=green NS=red");
}

TEST_F(LoggingLedsTest, HistoryKeepsOnlyTheNewestChanges) {
  const std::size_t total = LoggingLeds::kHistoryCapacity + 10;
  for (std::size_t i = 0; i < total; ++i) {
    clock_.Set(i);
    leds_.Set(Led::kModuleStatus, i % 2 == 0 ? LedColor::kGreen : LedColor::kOff);
  }
  ASSERT_EQ(leds_.History().size(), LoggingLeds::kHistoryCapacity);
  EXPECT_EQ(leds_.History().front().at, 10u);
  EXPECT_EQ(leds_.History().back().at, total - 1);
  EXPECT_EQ(lines_.size(), total);  // the log itself is not bounded
}

TEST(LoggingLedsNoSinkTest, WorksWithoutALog) {
  test::FakeClock clock;
  LoggingLeds leds(clock);
  leds.Set(Led::kModuleStatus, LedColor::kRed);
  EXPECT_EQ(leds.Current(Led::kModuleStatus), LedColor::kRed);
  LoggingLeds null_file(clock, nullptr);
  null_file.Set(Led::kModuleStatus, LedColor::kRed);
  EXPECT_EQ(null_file.History().size(), 1u);
}

TEST(LoggingLedsFileSinkTest, WritesOneLinePerChange) {
  test::FakeClock clock(42);
  std::FILE* file = std::tmpfile();
  ASSERT_NE(file, nullptr);
  LoggingLeds leds(clock, file);
  leds.Set(Led::kLinkLeft, LedColor::kGreen);
  leds.Set(Led::kLinkLeft, LedColor::kGreen);
  leds.Set(Led::kNetworkStatus, LedColor::kYellow);

  std::rewind(file);
  char text[128] = {};
  const std::size_t n = std::fread(text, 1, sizeof(text) - 1, file);
  std::fclose(file);
  EXPECT_EQ(std::string(text, n), "led LNK-L green t=42\nled NS yellow t=42\n");
}

}  // namespace
}  // namespace hal::host
