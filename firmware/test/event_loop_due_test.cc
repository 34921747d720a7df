// EventLoop: which services a pass polls (event_loop.h "Which services a pass polls").
#include <gtest/gtest.h>

#include <vector>

#include "event_loop.h"
#include "fake_frame_port.h"
#include "lwip/timeouts.h"
#include "lwip_fixture.h"

namespace {

using firmware::PollWhen;
using hal::Micros;

class RecordingWaiter final : public hal::Waiter {
 public:
  void WaitUntil(Micros deadline) override { deadlines.push_back(deadline); }
  std::vector<Micros> deadlines;
};

// Counts its polls; its deadline is whatever the test sets (and stays until it is polled at it).
class CountingService final : public firmware::Service {
 public:
  explicit CountingService(Micros first = hal::kNever) : deadline(first) {}
  void Poll(Micros now) override {
    ++polls;
    if (deadline <= now) deadline = hal::kNever;
  }
  Micros NextDeadline() const override { return deadline; }
  int polls = 0;
  Micros deadline;
};

class ScriptedProbe final : public firmware::EventProbe {
 public:
  bool TakeEvent() override {
    const bool was = pending;
    pending = false;
    return was;
  }
  bool pending = false;
};

class EventLoopDueTest : public ::testing::Test {
 protected:
  void SetUp() override {
    hal::test::EnsureLwipInitialised();
    netif_.Start({base::Ipv4Address(0x0A00020F), base::Ipv4Address(0xFFFFFF00), base::Ipv4Address(0x0A000202)}, "ipe002z");
  }
  // The tests move the clock by at most 100 µs after a first pass has run lwIP's due timers; no lwIP
  // timer may fall in that window, or its pass would be an event.
  static bool LwipQuietFor2Ms() { return sys_timeouts_sleeptime() >= 2; }
  hal::test::FakeClock& clock_ = hal::test::LwipTestClock();
  hal::test::FakeFramePort port_{{0x02, 0, 0, 0, 0, 1}};
  firmware::CardNetif netif_{port_};
  RecordingWaiter waiter_;
};

// A pass with no frame, no lwIP timer, no probe event: the clock stands still between passes, so lwIP
// has nothing due after the first pass ran its due timers.
TEST_F(EventLoopDueTest, NothingHappened_OnlyEveryPassServicesArePolled) {
  firmware::EventLoop loop(clock_, waiter_, netif_);
  CountingService every, on_event, due_only;
  ASSERT_TRUE(loop.AddService(every, PollWhen::kEveryPass).ok());
  ASSERT_TRUE(loop.AddService(on_event, PollWhen::kDueOrEvent).ok());
  ASSERT_TRUE(loop.AddService(due_only, PollWhen::kDueOnly).ok());
  loop.RunOnce();  // first pass: every service once (their deadlines are learnt)
  ASSERT_TRUE(LwipQuietFor2Ms());
  const int on_event_before = on_event.polls;
  const int due_only_before = due_only.polls;
  loop.RunOnce();
  loop.RunOnce();
  EXPECT_EQ(every.polls, 3);
  EXPECT_EQ(on_event.polls, on_event_before);
  EXPECT_EQ(due_only.polls, due_only_before);
}

TEST_F(EventLoopDueTest, DeadlinePassed_OnlyThatServiceAndTheEventFollowersArePolled) {
  firmware::EventLoop loop(clock_, waiter_, netif_);
  CountingService production(hal::kNever), follower, first;
  ASSERT_TRUE(loop.AddService(first, PollWhen::kDueOrEvent).ok());
  ASSERT_TRUE(loop.AddService(production, PollWhen::kDueOnly).ok());
  ASSERT_TRUE(loop.AddService(follower, PollWhen::kDueOrEvent).ok());
  loop.RunOnce();
  const Micros now = clock_.NowMicros();
  production.deadline = now;  // as if its last poll had set it (the test sets it directly)
  loop.RunOnce();             // not seen: the loop keeps the deadline it learnt at the first poll
  EXPECT_EQ(production.polls, 1);
  // After a poll, the deadline it reports is the one the loop serves.
  CountingService production2(now + 100);
  firmware::EventLoop loop2(clock_, waiter_, netif_);
  ASSERT_TRUE(loop2.AddService(first, PollWhen::kDueOrEvent).ok());
  ASSERT_TRUE(loop2.AddService(production2, PollWhen::kDueOnly).ok());
  ASSERT_TRUE(loop2.AddService(follower, PollWhen::kDueOrEvent).ok());
  production2.deadline = now + 100;
  loop2.RunOnce();  // the first pass polls every service; production2 keeps now + 100
  EXPECT_EQ(production2.deadline, now + 100);
  EXPECT_EQ(waiter_.deadlines.back(), now + 100);
  const int first_polls = first.polls;
  const int follower_polls = follower.polls;
  ASSERT_TRUE(LwipQuietFor2Ms());
  clock_.Set(now + 100);
  loop2.RunOnce();
  EXPECT_EQ(production2.polls, 2);
  // A kDueOnly poll is no event: the others were not polled.
  EXPECT_EQ(first.polls, first_polls);
  EXPECT_EQ(follower.polls, follower_polls);
}

TEST_F(EventLoopDueTest, DueOrEventServicePolledAtItsDeadline_LaterServicesFollow) {
  firmware::EventLoop loop(clock_, waiter_, netif_);
  const Micros now = clock_.NowMicros();
  CountingService before, timer(now + 50), after, production;
  ASSERT_TRUE(loop.AddService(before, PollWhen::kDueOrEvent).ok());
  ASSERT_TRUE(loop.AddService(timer, PollWhen::kDueOrEvent).ok());
  ASSERT_TRUE(loop.AddService(after, PollWhen::kDueOrEvent).ok());
  ASSERT_TRUE(loop.AddService(production, PollWhen::kDueOnly).ok());
  loop.RunOnce();
  ASSERT_TRUE(LwipQuietFor2Ms());
  clock_.Set(now + 50);
  loop.RunOnce();
  EXPECT_EQ(timer.polls, 2);
  EXPECT_EQ(before.polls, 1);      // before it in the order: waits for the next event
  EXPECT_EQ(after.polls, 2);       // may follow what the timer changed
  EXPECT_EQ(production.polls, 1);  // kDueOnly: its first pass, then its deadline only (none)
  EXPECT_EQ(loop.stats().event_passes, 2u);
}

TEST_F(EventLoopDueTest, FrameArrived_DueOrEventServicesPolled) {
  firmware::EventLoop loop(clock_, waiter_, netif_);
  CountingService on_event, due_only;
  ASSERT_TRUE(loop.AddService(on_event, PollWhen::kDueOrEvent).ok());
  ASSERT_TRUE(loop.AddService(due_only, PollWhen::kDueOnly).ok());
  loop.RunOnce();
  port_.Inject(std::vector<std::uint8_t>(60, 0xFF));
  loop.RunOnce();
  EXPECT_EQ(on_event.polls, 2);
  EXPECT_EQ(due_only.polls, 1);
}

TEST_F(EventLoopDueTest, ProbeEventAfterEveryPassService_FollowersPolledInTheSamePass) {
  firmware::EventLoop loop(clock_, waiter_, netif_);
  ScriptedProbe probe;
  loop.SetEventProbe(&probe);
  CountingService drive_link, front_end;
  ASSERT_TRUE(loop.AddService(drive_link, PollWhen::kEveryPass).ok());
  ASSERT_TRUE(loop.AddService(front_end, PollWhen::kDueOrEvent).ok());
  loop.RunOnce();
  loop.RunOnce();
  EXPECT_EQ(front_end.polls, 1);
  probe.pending = true;  // e.g. the drive link finished a transaction in its poll
  loop.RunOnce();
  EXPECT_EQ(drive_link.polls, 3);
  EXPECT_EQ(front_end.polls, 2);
}

TEST_F(EventLoopDueTest, DeadlineMovedByAnEvent_SleepFollowsTheNewDeadline) {
  firmware::EventLoop loop(clock_, waiter_, netif_);
  CountingService production;
  ASSERT_TRUE(loop.AddService(production, PollWhen::kDueOnly).ok());
  loop.RunOnce();
  const Micros now = clock_.NowMicros();
  production.deadline = now + 300;  // a frame opened a connection: its first slot
  port_.Inject(std::vector<std::uint8_t>(60, 0xFF));
  loop.RunOnce();
  EXPECT_EQ(waiter_.deadlines.back(), now + 300);
  EXPECT_EQ(production.polls, 1);
}

}  // namespace
