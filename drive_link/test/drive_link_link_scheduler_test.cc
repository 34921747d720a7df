// drive_link::LinkScheduler (drive_link/include/drive_link/link_scheduler.h) against the simulated
// inverter (register_proxy_fixture.h's line: InverterModel + InverterProtocolServer on a SocketSerialPort
// pair, fake clock): the own slot and the access slot share the link, one transaction of each at a time,
// so with both waiting they alternate; nothing of the proxy's own follows an access that resets the
// inverter; the link's state changes reach the parts; exact completion times.
#include "drive_link/link_scheduler.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "drive_link_part_fakes.h"
#include "register_proxy_fixture.h"

namespace drive_link::test {
namespace {

// Own transactions: `reads_left` reads of cmod (0003), each completion recorded with its time.
class FakeOwnTransactions final : public OwnTransactions {
 public:
  bool NextOwnJob(hal::Micros /*now*/, OwnJob& job) override {
    ++asked;
    if (reads_left == 0) return false;
    --reads_left;
    job.kind = OwnJobKind::kMonitorRead;
    job.transaction = Transaction::Read(0x0003);
    return true;
  }
  void OnOwnComplete(const OwnJob& job, const Completion& completion, hal::Micros now) override {
    log.push_back("own " + std::to_string(job.transaction.comm_number) + "=" + std::to_string(completion.data) +
                  " at " + std::to_string(now));
  }
  void OnLinkStateChanged(LinkState previous, LinkState current) override {
    log.push_back(std::string("link ") + LinkStateName(previous) + "->" + LinkStateName(current));
  }

  int reads_left = 0;
  int asked = 0;
  std::vector<std::string> log;
};

class DriveLinkLinkScheduler : public RegisterProxyFixture, public AccessListener {
 protected:
  void StartScheduler() {
    server_ = std::make_unique<sim::InverterProtocolServer>(model_, *pair_.inverter, clock_, sim::ServerConfig{});
    scheduler_ = std::make_unique<LinkScheduler>(*pair_.card, LinkConfig{}, accesses_, own_);
    server_->Poll(Now());
    ASSERT_TRUE(scheduler_->Start(Now()).ok());
    EXPECT_EQ(scheduler_->Start(Now()).code(), base::StatusCode::kFailedPrecondition);
  }

  // Runs the line deadline to deadline until `end`, scheduling after each pass as the proxy does.
  void RunLine(hal::Micros end) {
    for (int i = 0; i < 100000 && Now() < end; ++i) {
      scheduler_->Schedule(Now());  // what was asked for since the last pass
      const hal::Micros at = std::min({scheduler_->NextDeadline(), server_->NextDeadline(), end});
      clock_.Set(std::max(at, Now()));
      server_->Poll(Now());
      scheduler_->Schedule(Now());
      scheduler_->Poll(Now());
      accesses_.Deliver();
      scheduler_->Schedule(Now());
      server_->Poll(Now());
    }
  }

  void OnAccessDone(AccessToken /*token*/, const AccessResult& result) override {
    own_.log.push_back("access " + std::to_string(result.number) + "=" + std::to_string(result.value) + " at " +
                       std::to_string(Now()));
  }

  FakeAccessRules rules_;
  ProxyCounters counters_;
  AccessQueue accesses_{rules_, counters_};
  FakeOwnTransactions own_;
  std::unique_ptr<LinkScheduler> scheduler_;
};

TEST_F(DriveLinkLinkScheduler, OwnTransactionsAndAccessesAlternate) {
  StartScheduler();
  own_.reads_left = 2;
  ASSERT_TRUE(accesses_.Read(0x0004, *this).ok());
  ASSERT_TRUE(accesses_.Read(0x0004, *this).ok());
  RunLine(kStart + 2 * kSecond);
  // The start-up silence (1 s), then one exchange (6.011 ms) after another. An access is delivered on
  // the pass after its completion, at the same instant.
  const hal::Micros first = kStart + kSecond;
  const std::vector<std::string> expected = {
      "own 3=1 at " + std::to_string(first + kExchange),
      "link starting->up",  // the state changes after the completion that caused it
      "access 4=0 at " + std::to_string(first + 2 * kExchange),
      "own 3=1 at " + std::to_string(first + 3 * kExchange),
      "access 4=0 at " + std::to_string(first + 4 * kExchange),
  };
  EXPECT_EQ(own_.log, expected);
  EXPECT_TRUE(scheduler_->own_slot_free());
  EXPECT_FALSE(scheduler_->link_fault());
  EXPECT_EQ(scheduler_->link().counters().completed, 4U);
}

TEST_F(DriveLinkLinkScheduler, NothingOwnFollowsAnAccessThatResetsTheInverter) {
  StartScheduler();
  ASSERT_TRUE(accesses_.Write(0x0899, 1, WriteMode::kRamAndEeprom, *this).ok());
  scheduler_->Schedule(Now());  // nothing own is due; f899 goes to the link
  EXPECT_EQ(own_.asked, 1);
  EXPECT_TRUE(accesses_.reset_on_link());
  own_.reads_left = 1;
  RunLine(kStart + kSecond + 3 * kMilli);  // f899 is on the wire, its answer not yet back
  EXPECT_EQ(own_.asked, 1);
  EXPECT_EQ(own_.reads_left, 1);
  RunLine(kStart + 4 * kSecond);
  EXPECT_FALSE(accesses_.reset_on_link());
  EXPECT_EQ(own_.reads_left, 0);
  std::vector<std::string> completions;
  for (const std::string& line : own_.log) {
    if (line.rfind("link ", 0) != 0) completions.push_back(line.substr(0, line.find(" at ")));
  }
  EXPECT_EQ(completions, (std::vector<std::string>{"access 2201=1", "own 3=1"}));
}

}  // namespace
}  // namespace drive_link::test
