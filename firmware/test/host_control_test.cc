// HandleControlCommand (firmware/host/card_report.h): the control socket's dispatch, with the
// simulated inverter's commands and power-cycle.
#include <gtest/gtest.h>

#include <optional>

#include "card_control.h"
#include "fake_frame_port.h"
#include "host_sim_fixture.h"
#include "sim/register_numbers.h"
#include "lwip_fixture.h"

namespace host::test {
namespace {

namespace reg = sim::reg;

class RecordingReset final : public hal::ResetControl {
 public:
  void RequestReset(hal::ResetKind kind) override { kind_ = kind; }
  std::optional<hal::ResetKind> kind_;
};

class HostControl : public SimInverterFixture {
 protected:
  void SetUp() override {
    hal::test::EnsureLwipInitialised();
    ASSERT_TRUE(Start()) << error_;
  }

  std::string Run(std::string_view command) {
    std::string reply;
    HandleControlCommand(command, reply, report_, set_plugged_, reset_, inverter_.get());
    return reply;
  }

  hal::test::FakeFramePort port_{{0x02, 0x11, 0x22, 0x33, 0x44, 0x55}};
  firmware::CardNetif netif_{port_};
  hal::host::PollWaiter waiter_{clock_};
  firmware::EventLoop loop_{clock_, waiter_, netif_};
  hal::host::LoggingLeds leds_{clock_};
  CardReport report_{netif_, loop_, leds_, waiter_};
  SetPlugged set_plugged_ = [](hal::PortId, bool) { return base::OkStatus(); };
  RecordingReset reset_;
};

TEST_F(HostControl, HelpListsTheCardAndTheInverterCommands) {
  const std::string help = Run("help");
  EXPECT_EQ(help.rfind("help                   this list\n", 0), 0u) << help;
  EXPECT_NE(help.find("power-cycle            power-cycle the inverter and restart the card (state dir kept)\n"),
            std::string::npos);
  for (const char* line : {"\nget NAME|COMMNO ", "\nset NAME|COMMNO VALUE ", "\nterminal NAME on|off ",
                           "\ntrip CODE ", "\ninject KIND ", "\ninject clear ", "\nstatus "}) {
    EXPECT_NE(help.find(line), std::string::npos) << line;
  }
  EXPECT_EQ(help.substr(help.size() - 3), "ok\n");
}

TEST_F(HostControl, InverterCommandsAreRouted) {
  EXPECT_EQ(Run("set acc 50"), "acc = 50 (0x0032)\nok\n");
  EXPECT_EQ(Run("  get   0009 "), "acc = 50 (0x0032)\nok\n");
  EXPECT_EQ(Run("inject delay until-cleared 150 x"), "error unknown command (try 'help')\n");  // 5 words
  EXPECT_EQ(Run("frobnicate"), "error unknown command (try 'help')\n");
}

TEST_F(HostControl, PowerCycle_PowerCyclesTheInverterStoresItAndRestartsTheCard) {
  Run("set acc 50");
  Run("set fa06 0x8000");
  Run("trip err8");
  EXPECT_EQ(Run("power-cycle"), "ok\n");
  EXPECT_EQ(reset_.kind_, hal::ResetKind::kRestart);
  EXPECT_EQ(*inverter_->model().Read(reg::kFa06), 0);  // RAM only: back to its default
  EXPECT_FALSE(inverter_->model().tripped());          // err8 needs exactly this
  const std::string image = ReadText(FilePath());      // what the restarted card will load
  EXPECT_NE(image.find("\nreg 0009 50 1\n"), std::string::npos);
  EXPECT_NE(image.find("\ntrip-history 27 0 0 0\n"), std::string::npos);
}

}  // namespace
}  // namespace host::test
