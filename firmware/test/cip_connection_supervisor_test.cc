// CipConnectionSupervisor on a real Connection Manager: which connection events count as a loss of the
// master (c100/c101 through LossSupervision) and when the network counts as restored.
#include "cip_connection_supervisor.h"

#include <gtest/gtest.h>

#include <vector>

#include "cip_connection_fakes.h"
#include "fake_clock.h"
#include "modbus_fakes.h"

namespace firmware {
namespace {

using cip::test::ConnectionCard;
using cip::test::ExplicitParams;
using cip::test::ForwardCloseRequestBytes;
using cip::test::IoDatagramBytes;
using cip::test::OpenParams;
using Event = modbus::test::FakeLossSupervision::Event;
using cip::test::Bytes;
using cip::test::Hex;

constexpr drive_link::LossCause kCip = drive_link::LossCause::kCipConnection;

class Listener final : public DriveControlListener {
 public:
  void OnDriveControlLost() override { ++lost; }
  void OnConnectionsChanged() override { ++changes; }
  int lost = 0;
  int changes = 0;
};

class CipConnectionSupervisorTest : public ::testing::Test {
 protected:
  CipConnectionSupervisorTest() {
    card_.cm.set_events(&supervisor_);
    supervisor_.set_listener(&listener_);
  }

  void SetNow(hal::Micros now) {
    card_.now = now;
    clock_.Set(now);
  }
  // An exclusive owner 1/100/150 at 10 ms, multiplier 1 (timeout 80 ms); returns its O->T ID.
  std::uint32_t OpenOwner(const OpenParams& params = {}) {
    const Bytes reply = card_.Open(params);
    EXPECT_EQ(reply.at(2), 0x00);
    return ConnectionCard::OtoTId(reply);
  }
  void Feed(std::uint32_t id, std::uint16_t sequence, bool run) {
    card_.cm.OnIoDatagram(IoDatagramBytes(id, sequence, sequence, run, Hex("00 00 00 00 00 00 00 00")),
                          cip::Ipv4Endpoint{cip::test::kOriginator, 2222}, card_.now);
  }

  hal::test::FakeClock clock_{1000000};
  ConnectionCard card_;
  modbus::test::FakeLossSupervision loss_;
  CipConnectionSupervisor supervisor_{card_.cm, loss_, clock_};
  Listener listener_;
};

TEST_F(CipConnectionSupervisorTest, OwnerTimeoutIsALossAndRunDataRestores) {
  const std::uint32_t id = OpenOwner();
  Feed(id, 1, true);
  EXPECT_TRUE(loss_.events.empty());  // the first run data of a new connection restores nothing: nothing was lost

  SetNow(card_.now + 80000);  // last datagram + RPI x 4 x 2^1
  card_.cm.CheckTimeouts(card_.now);
  EXPECT_EQ(loss_.events, (std::vector<Event>{{true, kCip, 1080000}}));
  EXPECT_TRUE(supervisor_.lost());
  EXPECT_EQ(supervisor_.counters().timeouts, 1U);
  EXPECT_EQ(listener_.lost, 1);

  // A new owner, idle first (Program mode): still lost; in run: restored.
  OpenParams second;
  second.triad.connection_serial = 0x1338;
  const std::uint32_t id2 = OpenOwner(second);
  Feed(id2, 1, false);
  EXPECT_EQ(loss_.events.size(), 1U);
  SetNow(card_.now + 5000);
  Feed(id2, 2, true);
  ASSERT_EQ(loss_.events.size(), 2U);
  EXPECT_EQ(loss_.events[1], (Event{false, drive_link::LossCause::kModbusConnection, 1085000}));
  EXPECT_FALSE(supervisor_.lost());
  EXPECT_EQ(supervisor_.counters().restores, 1U);
}

TEST_F(CipConnectionSupervisorTest, OwnerTurningIdleIsALoss) {
  const std::uint32_t id = OpenOwner();
  Feed(id, 1, true);
  Feed(id, 2, false);
  EXPECT_EQ(loss_.events, (std::vector<Event>{{true, kCip, 1000000}}));
  EXPECT_EQ(supervisor_.counters().idle_transitions, 1U);
  Feed(id, 3, true);
  EXPECT_EQ(loss_.events.size(), 2U);
  EXPECT_FALSE(loss_.events[1].lost);
}

TEST_F(CipConnectionSupervisorTest, ForwardCloseOfTheOwnerIsALoss) {
  const std::uint32_t id = OpenOwner();
  Feed(id, 1, true);
  const Bytes reply = card_.Ask(ForwardCloseRequestBytes(OpenParams{}.triad));
  ASSERT_EQ(reply.at(2), 0x00);
  EXPECT_EQ(loss_.events, (std::vector<Event>{{true, kCip, 1000000}}));
  EXPECT_EQ(supervisor_.counters().owner_closes, 1U);
}

TEST_F(CipConnectionSupervisorTest, InputOnlyAndListenOnlyConnectionsControlNothing) {
  OpenParams input_only;
  input_only.o_to_t.size = 6;  // heartbeat with a run/idle header
  input_only.path = Hex("20 04 24 01 2C C6 2C 96");  // 198 -> 150
  ASSERT_EQ(card_.Open(input_only).at(2), 0x00);
  SetNow(card_.now + 20 * hal::kMicrosPerSecond);  // its first-packet allowance ran out
  card_.cm.CheckTimeouts(card_.now);
  EXPECT_EQ(card_.cm.counters().connection_timeouts, 1U);
  EXPECT_TRUE(loss_.events.empty());
  EXPECT_FALSE(supervisor_.lost());
}

TEST_F(CipConnectionSupervisorTest, ClassThreeTimeoutIsALossItsCloseIsNot) {
  ASSERT_EQ(card_.Open(ExplicitParams()).at(2), 0x00);
  OpenParams closing = ExplicitParams();
  closing.triad.connection_serial = 0x2000;
  ASSERT_EQ(card_.Open(closing).at(2), 0x00);
  ASSERT_EQ(card_.Ask(ForwardCloseRequestBytes(closing.triad, Hex("20 02 24 01"))).at(2), 0x00);
  EXPECT_TRUE(loss_.events.empty());

  SetNow(card_.now + 20 * hal::kMicrosPerSecond);  // 2 s x 4 x 2^1 = 16 s, and the 10 s first allowance
  card_.cm.CheckTimeouts(card_.now);
  EXPECT_EQ(loss_.events, (std::vector<Event>{{true, kCip, 21000000}}));

  // A class 3 connection again, with no exclusive owner open: restored.
  OpenParams again = ExplicitParams();
  again.triad.connection_serial = 0x3000;
  ASSERT_EQ(card_.Open(again).at(2), 0x00);
  ASSERT_EQ(loss_.events.size(), 2U);
  EXPECT_FALSE(loss_.events[1].lost);
}

TEST_F(CipConnectionSupervisorTest, RepeatedLossesReportOnce) {
  const std::uint32_t id = OpenOwner();
  Feed(id, 1, true);
  Feed(id, 2, false);  // idle: lost
  SetNow(card_.now + 80000);
  card_.cm.CheckTimeouts(card_.now);  // then its timeout: still the same loss
  EXPECT_EQ(loss_.events.size(), 1U);
  EXPECT_EQ(supervisor_.counters().losses, 1U);
  EXPECT_EQ(listener_.lost, 2);  // the assemblies hear of each
  EXPECT_GE(listener_.changes, 2);
}

}  // namespace
}  // namespace firmware
