// The control socket's inverter commands (sim/host/sim_control.h): exact answers for get, set,
// terminal, trip, inject and status, and their refusals.
#include "sim_control.h"

#include <gtest/gtest.h>

#include <array>
#include <vector>

#include "host_sim_fixture.h"
#include "sim/register_numbers.h"

namespace host::test {
namespace {

namespace reg = sim::reg;
using sim::HandleSimCommand;

class SimControl : public SimInverterFixture {
 protected:
  void SetUp() override { ASSERT_TRUE(Start()) << error_; }

  // One command line, split at spaces as the control socket does; "(not ours)" when not handled.
  std::string Run(std::string_view line) {
    std::vector<std::string_view> words;
    while (!line.empty()) {
      const std::size_t space = line.find(' ');
      words.push_back(line.substr(0, space));
      line.remove_prefix(space == std::string_view::npos ? line.size() : space + 1);
    }
    std::string reply;
    if (!HandleSimCommand(words, reply, *inverter_)) return "(not ours)";
    return reply;
  }
};

TEST_F(SimControl, GetByTitleOrNumber) {
  EXPECT_EQ(Run("get acc"), "acc = 100 (0x0064)\nok\n");
  EXPECT_EQ(Run("get ACC"), "acc = 100 (0x0064)\nok\n");
  EXPECT_EQ(Run("get 0009"), "acc = 100 (0x0064)\nok\n");
  EXPECT_EQ(Run("get c500"), "c500 = 0 (0x0000)\nok\n");
  EXPECT_EQ(Run("get FA06"), "fa06 = 0 (0x0000)\nok\n");
  EXPECT_EQ(Run("get f800"), "f800 = 1 (0x0001)\nok\n");  // the title, not the number F800
  EXPECT_EQ(Run("get fd01"), "fd01 = 18432 (0x4800)\nok\n");
}

TEST_F(SimControl, GetRefusals) {
  EXPECT_EQ(Run("get 000A"), "error no communication number 000A (numbers ending in A-F do not exist)\n");
  EXPECT_EQ(Run("get 0001"), "error no communication number 0001\n");
  EXPECT_EQ(Run("get nosuch"), "error unknown register 'nosuch'\n");
  EXPECT_EQ(Run("get"), "error usage: get NAME|COMMNO\n");
  EXPECT_EQ(Run("get acc dec"), "error usage: get NAME|COMMNO\n");
}

TEST_F(SimControl, SetIsAPanelWriteToRamAndEeprom) {
  EXPECT_EQ(Run("set acc 50"), "acc = 50 (0x0032)\nok\n");
  EXPECT_EQ(Run("set 0010 0x28"), "dec = 40 (0x0028)\nok\n");
  EXPECT_EQ(inverter_->model().EepromValue(reg::kAcc), 50);
  EXPECT_EQ(inverter_->model().EepromWriteCount(reg::kAcc), 1u);
  EXPECT_EQ(Run("set fa06 0x8000"), "fa06 = 32768 (0x8000)\nok\n");
}

TEST_F(SimControl, SetRefusals) {
  EXPECT_EQ(Run("set 000A 1"), "error no communication number 000A (numbers ending in A-F do not exist)\n");
  EXPECT_EQ(Run("set nosuch 1"), "error unknown register 'nosuch'\n");
  EXPECT_EQ(Run("set acc 0"), "error acc: 0 out of range 1..60000\n");
  EXPECT_EQ(Run("set acc -5"), "error acc: -5 out of range 1..60000\n");
  EXPECT_EQ(Run("set acc 70000"), "error acc: 70000 out of range 1..60000\n");
  EXPECT_EQ(Run("set acc fast"), "error invalid value 'fast' (a decimal or 0x-hex integer)\n");
  EXPECT_EQ(Run("set fd00 1"), "error fd00 is read-only (monitor)\n");
  EXPECT_EQ(Run("set fe10 1"), "error fe10 is read-only (trip-hold)\n");
  EXPECT_EQ(Run("set ul 9000"), "error ul: 9000 refused by a run-time limit (data error)\n");  // ul <= fh
  EXPECT_EQ(Run("set acc"), "error usage: set NAME|COMMNO VALUE\n");
  EXPECT_EQ(inverter_->model().EepromWriteCount(reg::kAcc), 0u);
}

TEST_F(SimControl, SetWhileRunningRefusedForFh) {
  EXPECT_EQ(Run("set fa07 6000"), "fa07 = 6000 (0x1770)\nok\n");
  EXPECT_EQ(Run("set fa06 0xC400"), "fa06 = 50176 (0xC400)\nok\n");
  clock_.Advance(kSecond);
  EXPECT_EQ(Run("set fh 6000"), "error fh: not writable while the drive runs\n");
  EXPECT_EQ(Run("set acc 50"), "acc = 50 (0x0032)\nok\n");  // acc may change during run
}

TEST_F(SimControl, SetFa30Trips) {
  EXPECT_EQ(Run("set fa30 5"), "error fa30: 5 refused by a run-time limit (data error)\n");
  EXPECT_EQ(Run("set fa30 27"), "fa30 = 0 (0x0000)\nok\n");
  EXPECT_EQ(inverter_->model().trip(), 27);
}

TEST_F(SimControl, Terminal) {
  EXPECT_EQ(Run("terminal ST on"), "ok\n");
  EXPECT_TRUE(inverter_->model().terminal(sim::Terminal::kSt));
  EXPECT_EQ(Run("get fd01"), "fd01 = 16384 (0x4000)\nok\n");  // ST closed: 0x4800 -> 0x4000
  EXPECT_EQ(Run("terminal st off"), "ok\n");
  EXPECT_FALSE(inverter_->model().terminal(sim::Terminal::kSt));
  EXPECT_EQ(Run("terminal X on"), "error unknown terminal 'X' (F R RES S1 S2 S3 VIB VIA ST)\n");
  EXPECT_EQ(Run("terminal F maybe"), "error usage: terminal F|R|RES|S1|S2|S3|VIB|VIA|ST on|off\n");
}

TEST_F(SimControl, TripByNameOrCode) {
  const std::array<std::pair<const char*, int>, 6> cases = {
      {{"trip err8", 27}, {"trip ERR8", 27}, {"trip e-23", 55}, {"trip E", 17}, {"trip err5", 24}, {"trip 200", 200}}};
  for (const auto& [command, code] : cases) {
    EXPECT_EQ(Run(command), "ok\n") << command;
    EXPECT_EQ(inverter_->model().trip(), code) << command;
    inverter_->model().PowerCycle();  // the only reset that clears every one of them
  }
}

TEST_F(SimControl, TripRefusals) {
  EXPECT_EQ(Run("trip 0"), "error usage: trip CODE (1-255, or E, err5, err8, e-23)\n");
  EXPECT_EQ(Run("trip 256"), "error usage: trip CODE (1-255, or E, err5, err8, e-23)\n");
  EXPECT_EQ(Run("trip err9"), "error usage: trip CODE (1-255, or E, err5, err8, e-23)\n");
  EXPECT_EQ(Run("trip E"), "ok\n");
  EXPECT_EQ(Run("trip err8"), "error already tripped with code 17 (the first trip holds)\n");
}

TEST_F(SimControl, InjectAndClear) {
  EXPECT_EQ(Run("inject drop"), "ok\n");
  EXPECT_EQ(Run("inject drop 3"), "ok\n");
  EXPECT_EQ(Run("inject corrupt until-cleared"), "ok\n");
  EXPECT_EQ(Run("inject silent 1"), "ok\n");
  EXPECT_EQ(Run("inject delay until-cleared 150"), "ok\n");
  EXPECT_EQ(inverter_->server().active_faults(), 5u);
  EXPECT_EQ(Run("inject clear"), "ok\n");
  EXPECT_EQ(inverter_->server().active_faults(), 0u);
}

TEST_F(SimControl, InjectRefusals) {
  const std::string usage =
      "error usage: inject drop|delay|corrupt|silent [COUNT|until-cleared] [DELAY-MS], inject clear\n";
  EXPECT_EQ(Run("inject"), usage);
  EXPECT_EQ(Run("inject bogus"), usage);
  EXPECT_EQ(Run("inject drop 1 100"), usage);  // a delay only for delay
  EXPECT_EQ(Run("inject drop 0"),
            "error count must be 1 or more, or until-cleared; usage: inject drop|delay|corrupt|silent "
            "[COUNT|until-cleared] [DELAY-MS], inject clear\n");
  EXPECT_EQ(Run("inject delay 1 0"), "error delay must be 1-60000 ms\n");
  EXPECT_EQ(Run("inject delay 1 60001"), "error delay must be 1-60000 ms\n");
  EXPECT_EQ(inverter_->server().active_faults(), 0u);
}

// The delay reaches the serial line: a read of FD01 (seed 003's binary example) is answered 200 ms
// (the default) later than the 2 ms processing time plus 7 bytes at 19200 baud 8E1 (4.011 ms).
TEST_F(SimControl, InjectedDelayDefaultsTo200Milliseconds) {
  const std::array<std::uint8_t, 5> read_fd01 = {0x2F, 0x52, 0xFD, 0x01, 0x7F};
  ASSERT_EQ(Run("inject delay"), "ok\n");
  ASSERT_TRUE(card_->Write(read_fd01).ok());
  inverter_->server().Poll(clock_.NowMicros());
  EXPECT_EQ(inverter_->server().NextDeadline(), clock_.NowMicros() + 200000 + 2000 + 4011);
  ASSERT_EQ(inverter_->server().counters().delayed, 1u);
}

TEST_F(SimControl, StatusStopped) {
  EXPECT_EQ(Run("status"),
            "{\"state\":\"stopped\",\"model\":\"vf-mb1\",\"output_hz\":0.00,\"target_hz\":0.00,"
            "\"command_source\":\"panel\",\"frequency_source\":\"panel\",\"command_priority\":\"none\","
            "\"frequency_priority\":\"none\",\"fa06\":\"0x0000\",\"fa07\":0,\"fd01\":\"0x4800\",\"trip\":0,"
            "\"eeprom_writes\":0}\nok\n");
}

TEST_F(SimControl, StatusRunningWithTheOptionInCommand) {
  Run("set acc 50");  // 0 -> fh (80 Hz) in 5.0 s: 16 Hz/s
  Run("set dec 50");  // fh -> 0 in 5.0 s: 16 Hz/s
  Run("set fa07 6000");
  Run("set fa06 0xC400");
  clock_.Advance(2 * kSecond);
  EXPECT_EQ(Run("status"),
            "{\"state\":\"running\",\"model\":\"vf-mb1\",\"output_hz\":32.00,\"target_hz\":60.00,"
            "\"command_source\":\"option\",\"frequency_source\":\"option\",\"command_priority\":\"fa06\","
            "\"frequency_priority\":\"fa06\",\"fa06\":\"0xC400\",\"fa07\":6000,\"fd01\":\"0x6400\",\"trip\":0,"
            "\"eeprom_writes\":2}\nok\n");
  Run("set fa06 0xC600");  // reverse: 32 Hz down to 0 in 2 s, then 1 s the other way
  clock_.Advance(3 * kSecond);
  const std::string status = Run("status");
  EXPECT_NE(status.find("\"output_hz\":-16.00,\"target_hz\":-60.00,"), std::string::npos) << status;
}

TEST_F(SimControl, StatusTrippedAndResetting) {
  Run("trip E");
  EXPECT_NE(Run("status").find("{\"state\":\"tripped\","), std::string::npos);
  EXPECT_NE(Run("status").find("\"trip\":17,"), std::string::npos);
  Run("set fa06 0x2000");  // fault reset: the trip clears, the drive is silent for a second
  EXPECT_NE(Run("status").find("{\"state\":\"resetting\","), std::string::npos);
  EXPECT_NE(Run("status").find("\"trip\":0,"), std::string::npos);
  clock_.Advance(kSecond);
  EXPECT_NE(Run("status").find("{\"state\":\"stopped\","), std::string::npos);
}

TEST_F(SimControl, OtherCommandsAreNotOurs) {
  EXPECT_EQ(Run("stats"), "(not ours)");
  EXPECT_EQ(Run("help"), "(not ours)");
  EXPECT_EQ(Run("power-cycle"), "(not ours)");
  EXPECT_EQ(Run(""), "(not ours)");
}

}  // namespace
}  // namespace host::test
