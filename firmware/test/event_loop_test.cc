#include "event_loop.h"

#include <gtest/gtest.h>

#include <vector>

#include "fake_frame_port.h"
#include "lwip_fixture.h"

namespace {

using hal::Micros;

class RecordingWaiter final : public hal::Waiter {
 public:
  void WaitUntil(Micros deadline) override { deadlines.push_back(deadline); }
  std::vector<Micros> deadlines;
};

class PeriodicService final : public firmware::Service {
 public:
  PeriodicService(Micros first, Micros period) : next_(first), period_(period) {}
  void Poll(Micros now) override {
    // Next deadline from the previous one, not from `now`: no drift however late the poll is.
    while (next_ <= now) {
      ++runs;
      next_ += period_;
    }
  }
  Micros NextDeadline() const override { return next_; }
  int runs = 0;

 private:
  Micros next_;
  Micros period_;
};

class EventLoopTest : public ::testing::Test {
 protected:
  void SetUp() override {
    hal::test::EnsureLwipInitialised();
    netif_.Start({base::Ipv4Address(0x0A00020F), base::Ipv4Address(0xFFFFFF00), base::Ipv4Address(0x0A000202)}, "ipe002z");
  }
  hal::test::FakeClock& clock_ = hal::test::LwipTestClock();
  hal::test::FakeFramePort port_{{0x02, 0, 0, 0, 0, 1}};
  firmware::CardNetif netif_{port_};
  RecordingWaiter waiter_;
};

TEST_F(EventLoopTest, ServiceDeadlineEarlierThanLwip_LoopSleepsUntilIt) {
  firmware::EventLoop loop(clock_, waiter_, netif_);
  const Micros now = clock_.NowMicros();
  PeriodicService service(now + 250, 1000);  // 250 µs: sooner than any lwIP timer (>= 1 ms)
  ASSERT_TRUE(loop.AddService(service).ok());
  loop.RunOnce();
  ASSERT_EQ(waiter_.deadlines.size(), 1u);
  EXPECT_EQ(waiter_.deadlines[0], now + 250);
}

TEST_F(EventLoopTest, PeriodicService_KeepsBaseTimeWhenPolledLate) {
  firmware::EventLoop loop(clock_, waiter_, netif_);
  const Micros start = clock_.NowMicros();
  PeriodicService service(start + 500, 500);
  ASSERT_TRUE(loop.AddService(service).ok());
  clock_.Set(start + 1'730);  // woke 230 µs late after three periods
  loop.RunOnce();
  EXPECT_EQ(service.runs, 3);
  EXPECT_EQ(waiter_.deadlines.back(), start + 2'000);
}

TEST_F(EventLoopTest, NoServices_SleepsUntilLwipTimerNotForever) {
  firmware::EventLoop loop(clock_, waiter_, netif_);
  loop.RunOnce();
  ASSERT_EQ(waiter_.deadlines.size(), 1u);
  // lwIP's cyclic timers are at most a few seconds away; the loop never spins (deadline > now).
  EXPECT_GT(waiter_.deadlines[0], clock_.NowMicros());
  EXPECT_LE(waiter_.deadlines[0], clock_.NowMicros() + 60 * hal::kMicrosPerSecond);
}

TEST_F(EventLoopTest, FloodOfFrames_PassBoundedAndDoesNotSleep) {
  firmware::EventLoop loop(clock_, waiter_, netif_);
  for (std::size_t i = 0; i < firmware::EventLoop::kMaxFramesPerPass + 5; ++i) {
    port_.Inject(std::vector<std::uint8_t>(60, 0xFF));
  }
  loop.RunOnce();
  EXPECT_EQ(port_.pending(), 5u);
  EXPECT_EQ(waiter_.deadlines.back(), clock_.NowMicros());  // more frames waiting: no sleep
  loop.RunOnce();
  EXPECT_EQ(port_.pending(), 0u);
  EXPECT_GT(waiter_.deadlines.back(), clock_.NowMicros());
  EXPECT_EQ(loop.stats().bounded_passes, 1u);
  EXPECT_EQ(loop.stats().frames_in, firmware::EventLoop::kMaxFramesPerPass + 5);
}

// Notes how many frames still waited in the port when its deadline was served.
class DueProbe final : public firmware::Service {
 public:
  DueProbe(Micros due, const hal::test::FakeFramePort& port) : due_(due), port_(port) {}
  void Poll(Micros now) override {
    if (due_ > now) return;
    pending_when_served.push_back(port_.pending());
    due_ = hal::kNever;
  }
  Micros NextDeadline() const override { return due_; }
  std::vector<std::size_t> pending_when_served;

 private:
  Micros due_;
  const hal::test::FakeFramePort& port_;
};

TEST_F(EventLoopTest, FloodOfFrames_DueServiceServedAfterOneBatchNotAfterThePass) {
  firmware::EventLoop loop(clock_, waiter_, netif_);
  DueProbe probe(clock_.NowMicros(), port_);  // e.g. an I/O production slot that is due
  ASSERT_TRUE(loop.AddService(probe).ok());
  for (std::size_t i = 0; i < firmware::EventLoop::kMaxFramesPerPass; ++i) {
    port_.Inject(std::vector<std::uint8_t>(60, 0xFF));
  }
  loop.RunOnce();
  ASSERT_EQ(probe.pending_when_served.size(), 1u);  // served once, between the batches
  EXPECT_EQ(probe.pending_when_served[0],
            firmware::EventLoop::kMaxFramesPerPass - firmware::EventLoop::kFramesPerBatch);
  EXPECT_EQ(port_.pending(), 0u);
  EXPECT_EQ(loop.stats().frames_in, firmware::EventLoop::kMaxFramesPerPass);
}

TEST_F(EventLoopTest, LinkLost_NetifFollowsOnNextPass) {
  firmware::EventLoop loop(clock_, waiter_, netif_);
  port_.SetLink(hal::PortId::kLeft, false);
  loop.RunOnce();
  EXPECT_FALSE(netif_.link_up());
  port_.SetLink(hal::PortId::kLeft, true);
  loop.RunOnce();
  EXPECT_TRUE(netif_.link_up());
  EXPECT_EQ(loop.stats().link_changes, 2u);
}

TEST_F(EventLoopTest, TooManyServices_ResourceExhausted) {
  firmware::EventLoop loop(clock_, waiter_, netif_);
  std::vector<PeriodicService> services(firmware::EventLoop::kMaxServices + 1, PeriodicService(0, 1));
  for (std::size_t i = 0; i < firmware::EventLoop::kMaxServices; ++i) {
    ASSERT_TRUE(loop.AddService(services[i]).ok());
  }
  EXPECT_EQ(loop.AddService(services.back()).code(), base::StatusCode::kResourceExhausted);
}

}  // namespace
