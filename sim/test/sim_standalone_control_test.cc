// ipe002z-inverter's control socket (sim/host/standalone_control.h): the inverter commands routed as in
// ipe002z-host, its own help, stats and power-cycle (the inverter alone), and the command splitter both
// control sockets share (hal/host/control_server.h).
#include "standalone_control.h"

#include <gtest/gtest.h>

#include <array>
#include <string>

#include "control_server.h"
#include "host_sim_fixture.h"
#include "listening_serial_port.h"
#include "sim/register_numbers.h"

namespace host::test {
namespace {

namespace reg = sim::reg;

class StandaloneControl : public SimInverterFixture {
 protected:
  void SetUp() override {
    ASSERT_TRUE(Start()) << error_;
    std::string error;
    auto line = hal::host::ListeningSerialPort::Listen("unix:" + dir_ + "/serial.sock", &error);
    ASSERT_TRUE(line.ok()) << error;
    line_port_ = std::move(line.value());
  }

  std::string Run(std::string_view command) {
    std::string reply;
    sim::HandleStandaloneCommand(command, reply, *inverter_, *line_port_);
    return reply;
  }

  std::unique_ptr<hal::host::ListeningSerialPort> line_port_;
};

TEST_F(StandaloneControl, HelpListsItsOwnAndTheInverterCommands) {
  const std::string help = Run("help");
  EXPECT_EQ(help.rfind("help                   this list\n"
                       "stats                  the serial line's clients and the protocol server's counters\n"
                       "power-cycle            power the inverter off and on (its EEPROM image is stored; the "
                       "line stays)\n"
                       "get NAME|COMMNO ",
                       0),
            0u)
      << help;
  for (const char* line : {"\nset NAME|COMMNO VALUE ", "\nterminal NAME on|off ", "\ntrip CODE ", "\ninject KIND ",
                           "\ninject clear ", "\nstatus "}) {
    EXPECT_NE(help.find(line), std::string::npos) << line;
  }
  EXPECT_EQ(help.find("link L|R"), std::string::npos);  // no card here
  EXPECT_EQ(help.substr(help.size() - 3), "ok\n");
}

TEST_F(StandaloneControl, InverterCommandsAreRouted) {
  EXPECT_EQ(Run("set acc 50"), "acc = 50 (0x0032)\nok\n");
  EXPECT_EQ(Run("  get   0009 "), "acc = 50 (0x0032)\nok\n");
  EXPECT_EQ(Run("set fd00 1"), "error fd00 is read-only (monitor)\n");
  EXPECT_EQ(Run("trip err8"), "ok\n");
  EXPECT_EQ(Run("trip 17"), "error already tripped with code 27 (the first trip holds)\n");
  EXPECT_EQ(Run("inject drop 1"), "ok\n");
  EXPECT_EQ(inverter_->server().active_faults(), 1u);
  EXPECT_EQ(Run("inject delay until-cleared 150 x"), "error unknown command (try 'help')\n");  // 5 words
  EXPECT_EQ(Run("link L down"), "error unknown command (try 'help')\n");
  EXPECT_EQ(Run("stats now"), "error unknown command (try 'help')\n");
}

TEST_F(StandaloneControl, PowerCycle_TheInverterAloneRestartsFromItsStoredImage) {
  Run("set acc 50");
  Run("set fa06 0x8000");
  Run("trip err8");
  EXPECT_EQ(Run("power-cycle"), "ok\n");
  EXPECT_EQ(*inverter_->model().Read(reg::kFa06), 0);  // RAM only: back to its default
  EXPECT_FALSE(inverter_->model().tripped());          // err8 needs exactly this
  EXPECT_TRUE(inverter_->model().in_reset(clock_.NowMicros()));  // the power-on silence
  const std::string image = ReadText(FilePath());
  EXPECT_NE(image.find("\nreg 0009 50 1\n"), std::string::npos);
  EXPECT_NE(image.find("\ntrip-history 27 0 0 0\n"), std::string::npos);
  EXPECT_EQ(Run("get acc"), "acc = 50 (0x0032)\nok\n");
}

TEST_F(StandaloneControl, StatsCountTheLineAndTheServer) {
  EXPECT_EQ(Run("stats"),
            "serial.connected=0\nserial.connections=0\nserial.replaced=0\nserial.refused=0\n"
            "serial.disconnects=0\nserver.requests=0\nserver.ignored=0\nserver.executed=0\nserver.replies=0\n"
            "server.errors=0\nserver.unanswered=0\nserver.in_reset=0\nserver.no_reply=0\nserver.dropped=0\n"
            "server.delayed=0\nserver.corrupted=0\nserver.rx_errors=0\nserver.timeouts=0\nframer.frames=0\n"
            "framer.garbage_bytes=0\nframer.dropped_frames=0\nok\n");
  // The fixture's server is on the socket pair: one read of FD01 from the card's end.
  const std::uint8_t request[] = {0x2F, 0x52, 0xFD, 0x01, 0x7F};
  ASSERT_EQ(card_->Write(request).value(), sizeof request);
  inverter_->server().Poll(clock_.NowMicros());
  const std::string stats = Run("stats");
  EXPECT_NE(stats.find("\nserver.requests=1\nserver.ignored=0\nserver.executed=1\n"), std::string::npos) << stats;
  EXPECT_NE(stats.find("\nframer.frames=1\n"), std::string::npos) << stats;
}

TEST(SplitCommand, WordsAtSpaces) {
  std::array<std::string_view, hal::host::kMaxCommandWords> words;
  EXPECT_EQ(hal::host::SplitCommand("", words), 0u);
  EXPECT_EQ(hal::host::SplitCommand("   ", words), 0u);
  ASSERT_EQ(hal::host::SplitCommand("  get   0009 ", words), 2u);
  EXPECT_EQ(words[0], "get");
  EXPECT_EQ(words[1], "0009");
  ASSERT_EQ(hal::host::SplitCommand("inject delay until-cleared 150", words), 4u);
  EXPECT_EQ(words[3], "150");
  EXPECT_EQ(hal::host::SplitCommand("inject delay until-cleared 150 x", words), 5u);  // more than fit
  EXPECT_EQ(hal::host::SplitCommand("a b c d    ", words), 4u);                      // trailing spaces only
}

}  // namespace
}  // namespace host::test
