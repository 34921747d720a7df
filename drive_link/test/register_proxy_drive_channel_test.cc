// drive_link::RegisterProxy as DriveCommandChannel, against the real simulated inverter
// (register_proxy_fixture.h): FA06/FA07 taken over for the CIP drive profile, the scanner words that
// target them held back meanwhile, masked scanner words, the FD00/FE02 feedback reads, loss actions and
// reloads. Besides the model's registers, every request the proxy puts on the serial line is decoded and
// recorded with its time, so the tests assert exactly which registers are written and read, and when.
#include <gtest/gtest.h>

#include <cstdio>
#include <initializer_list>
#include <memory>
#include <string>
#include <vector>

#include "drive_link/register_proxy.h"
#include "drive_link/wire/toshiba_frame.h"
#include "register_proxy_fixture.h"

namespace drive_link::test {
namespace {

constexpr std::uint16_t kFa06 = 0xFA06;
constexpr std::uint16_t kFa07 = 0xFA07;
constexpr std::uint16_t kFa23 = 0xFA23;
constexpr std::uint16_t kFd00 = 0xFD00;
constexpr std::uint16_t kAcc = 0x0009;
constexpr std::uint16_t kDec = 0x0010;
constexpr std::uint8_t kEmergencyStopTrip = 0x11;
constexpr Micros kRefresh = 500 * kMilli;  // ProxyConfig::command_refresh_interval

// One request the proxy wrote on the line, as the inverter decodes it.
struct SentRequest {
  Micros at = 0;
  std::string text;  // "P FA06 C400", "W 0009 001E", "R FD01", "X 2" (a block read of 2 groups)
  std::uint16_t number = 0;
  bool write = false;
};

// The card's end of the line, recording every complete request frame written through it.
class RecordingPort final : public hal::SerialPort {
 public:
  RecordingPort(hal::SerialPort& line, const hal::Clock& clock) : line_(line), clock_(clock) {}

  base::Status Configure(const hal::SerialConfig& config) override { return line_.Configure(config); }
  base::Result<std::size_t> Read(std::span<std::uint8_t> buffer) override { return line_.Read(buffer); }
  base::Result<std::size_t> Write(std::span<const std::uint8_t> bytes) override {
    const base::Result<std::size_t> written = line_.Write(bytes);
    if (!written.ok()) return written;
    std::span<const std::uint8_t> rest = bytes.first(*written);
    while (!rest.empty()) {
      const wire::StreamFramer::FeedResult fed = framer_.Feed(rest);
      rest = rest.subspan(fed.consumed);
      if (!fed.frame_ready) break;
      Record(wire::DecodeRequest(framer_.frame()));
    }
    return written;
  }

  std::vector<SentRequest> sent;

 private:
  void Record(const wire::DecodedRequest& decoded) {
    SentRequest request;
    request.at = clock_.NowMicros();
    char text[32];
    if (!decoded.ok()) {
      std::snprintf(text, sizeof text, "undecodable");
    } else if (decoded.kind == wire::RequestKind::kBlock) {
      std::snprintf(text, sizeof text, "X %u", static_cast<unsigned>(decoded.block.read_count));
    } else {
      const wire::Request& r = decoded.request;
      request.number = r.comm_number;
      request.write = r.command == wire::Command::kWrite || r.command == wire::Command::kWriteRam;
      if (request.write) {
        std::snprintf(text, sizeof text, "%c %04X %04X", static_cast<char>(r.command),
                      static_cast<unsigned>(r.comm_number), static_cast<unsigned>(r.data));
      } else {
        std::snprintf(text, sizeof text, "%c %04X", static_cast<char>(r.command), static_cast<unsigned>(r.comm_number));
      }
    }
    request.text = text;
    sent.push_back(request);
  }

  hal::SerialPort& line_;
  const hal::Clock& clock_;
  wire::StreamFramer framer_{wire::Direction::kRequests};
};

using Texts = std::vector<std::string>;

class RegisterProxyDriveChannelTest : public RegisterProxyFixture {
 protected:
  ~RegisterProxyDriveChannelTest() override { proxy_.reset(); }  // before the port it writes to

  // As the fixture's StartLoaded, with the proxy writing through the recording port.
  void StartRecorded() {
    recorder_ = std::make_unique<RecordingPort>(*pair_.card, clock_);
    server_ = std::make_unique<sim::InverterProtocolServer>(model_, *pair_.inverter, clock_);
    proxy_ = std::make_unique<RegisterProxy>(*recorder_, LinkConfig{}, ProxyConfig{});
    proxy_->SetConfigListener(&config_);
    server_->Poll(Now());
    ASSERT_TRUE(proxy_->Start(Now()).ok());
    ASSERT_TRUE(RunUntilTrue([this] { return proxy_->config_loaded(); }, 3 * kSecond).has_value());
  }

  std::size_t Mark() const { return recorder_->sent.size(); }

  // Writes (W or P) of `numbers` sent since `mark`.
  std::vector<SentRequest> WritesOf(std::initializer_list<std::uint16_t> numbers, std::size_t mark) const {
    std::vector<SentRequest> writes;
    for (std::size_t i = mark; i < recorder_->sent.size(); ++i) {
      const SentRequest& r = recorder_->sent[i];
      if (!r.write) continue;
      for (std::uint16_t number : numbers) {
        if (r.number == number) writes.push_back(r);
      }
    }
    return writes;
  }
  Texts WriteTexts(std::initializer_list<std::uint16_t> numbers, std::size_t mark) const {
    Texts texts;
    for (const SentRequest& r : WritesOf(numbers, mark)) texts.push_back(r.text);
    return texts;
  }
  // Every read (R or X) sent since `mark`.
  Texts ReadTexts(std::size_t mark) const {
    Texts texts;
    for (std::size_t i = mark; i < recorder_->sent.size(); ++i) {
      if (!recorder_->sent[i].write) texts.push_back(recorder_->sent[i].text);
    }
    return texts;
  }

  // The reads since `mark` are whole cycles of `cycle` (from the first cycle start on, the last one may
  // be cut short by the end of the run), at least `min_cycles` of them.
  void ExpectReadCycles(std::size_t mark, const Texts& cycle, std::size_t min_cycles) const {
    const Texts reads = ReadTexts(mark);
    std::size_t start = 0;
    while (start < reads.size() && reads[start] != cycle[0]) ++start;
    ASSERT_GE(reads.size() - start, min_cycles * cycle.size());
    for (std::size_t i = start; i < reads.size(); ++i) {
      ASSERT_EQ(reads[i], cycle[(i - start) % cycle.size()]) << "read " << i - start << " of the cycles";
    }
  }

  std::unique_ptr<RecordingPort> recorder_;
};

// ---- Take-over, changes, refresh -----------------------------------------------------------------------

TEST_F(RegisterProxyDriveChannelTest, TakeOverWritesFa06ThenFa07AtOnceInRamOnly) {
  SetEeprom({{kAcc, 10}});
  StartRecorded();
  RunFor(kSecond);
  EXPECT_FALSE(proxy_->drive_command_taken());
  EXPECT_EQ(WriteTexts({kFa06, kFa07}, 0), Texts{});  // nothing before the first SetDriveCommand

  const std::size_t mark = Mark();
  proxy_->SetDriveCommand({0xC400, 0x1770});
  const Micros set_at = Now();
  EXPECT_TRUE(proxy_->drive_command_taken());
  RunFor(100 * kMilli);
  const std::vector<SentRequest> writes = WritesOf({kFa06, kFa07}, mark);
  ASSERT_EQ(WriteTexts({kFa06, kFa07}, mark), (Texts{"P FA06 C400", "P FA07 1770"}));
  EXPECT_LE(writes[0].at - set_at, kExchange);  // after the transaction on the wire, at once
  EXPECT_EQ(writes[1].at - writes[0].at, kExchange);
  EXPECT_EQ(proxy_->counters().drive_command_writes, 2U);
  EXPECT_EQ(proxy_->counters().command_writes, 2U);
  RunFor(kSecond);
  EXPECT_EQ(Reg(kFd00), 0x1770);  // the drive runs at 60 Hz from the drive command
  EXPECT_EQ(proxy_->CommandWords(), ScannerWords{});  // the scanner words are not involved
}

TEST_F(RegisterProxyDriveChannelTest, AChangedWordIsWrittenAtOnceAndAloneBeforeItsRefresh) {
  StartRecorded();
  proxy_->SetDriveCommand({0xC400, 0x1770});
  RunFor(100 * kMilli);
  const std::size_t mark = Mark();
  proxy_->SetDriveCommand({0xC400, 0x0BB8});
  const Micros set_at = Now();
  RunFor(100 * kMilli);
  const std::vector<SentRequest> writes = WritesOf({kFa06, kFa07}, mark);
  ASSERT_EQ(WriteTexts({kFa06, kFa07}, mark), Texts{"P FA07 0BB8"});
  EXPECT_LE(writes[0].at - set_at, kExchange);
  EXPECT_EQ(Reg(kFa07), 0x0BB8);
}

TEST_F(RegisterProxyDriveChannelTest, UnchangedWordsAreRefreshedAfterTheInterval) {
  StartRecorded();
  RunFor(kSecond);
  const std::size_t mark = Mark();
  proxy_->SetDriveCommand({0xC400, 0x1770});
  RunFor(2 * kSecond + 100 * kMilli);
  for (const std::uint16_t number : {kFa06, kFa07}) {
    const std::vector<SentRequest> writes = WritesOf({number}, mark);
    ASSERT_EQ(writes.size(), 5U) << std::hex << number;  // the take-over, then every 500 ms
    for (std::size_t i = 1; i < writes.size(); ++i) {
      EXPECT_EQ(writes[i].text, writes[0].text);
      // Due 500 ms after the last write, written in the command phase of the next cycle (2 reads long).
      EXPECT_GE(writes[i].at - writes[i - 1].at, kRefresh) << i;
      EXPECT_LE(writes[i].at - writes[i - 1].at, kRefresh + 3 * kExchange) << i;
    }
  }
  ASSERT_EQ(model_.Write(kFa07, 0, sim::WriteTarget::kRamOnly).outcome, sim::WriteOutcome::kOk);
  ASSERT_TRUE(RunUntilTrue([this] { return Reg(kFa07) == 0x1770; }, kRefresh + 3 * kExchange).has_value());
}

TEST_F(RegisterProxyDriveChannelTest, FaultResetBitIsSentOncePerRisingEdge) {
  SetEeprom({{kAcc, 10}});
  StartRecorded();
  proxy_->SetDriveCommand({0xC400, 0x1770});
  RunFor(1500 * kMilli);
  model_.Trip(kEmergencyStopTrip);
  RunFor(200 * kMilli);
  EXPECT_EQ(proxy_->drive_status() & 0x0003, 0x0003);
  std::size_t mark = Mark();
  proxy_->SetDriveCommand({0xE400, 0x1770});  // raised and held
  RunFor(3 * kSecond);
  Texts fa06 = WriteTexts({kFa06}, mark);
  ASSERT_GE(fa06.size(), 3U);
  EXPECT_EQ(fa06[0], "P FA06 E400");
  for (std::size_t i = 1; i < fa06.size(); ++i) EXPECT_EQ(fa06[i], "P FA06 C400") << i;
  EXPECT_EQ(server_->counters().no_reply, 1U);  // one reset, not one per refresh
  EXPECT_FALSE(model_.tripped());
  EXPECT_EQ(Reg(kFa06), 0xC400);  // written again after the reset, bit 13 cleared
  EXPECT_EQ(Reg(kFa07), 0x1770);
  EXPECT_EQ(Reg(kFd00), 0x1770);

  // Holding the bit is no new edge; dropping and raising it again is.
  model_.Trip(kEmergencyStopTrip);
  proxy_->SetDriveCommand({0xE400, 0x1770});
  RunFor(kSecond);
  EXPECT_TRUE(model_.tripped());
  proxy_->SetDriveCommand({0xC400, 0x1770});
  RunFor(100 * kMilli);
  mark = Mark();
  proxy_->SetDriveCommand({0xE400, 0x1770});
  RunFor(3 * kSecond);
  fa06 = WriteTexts({kFa06}, mark);
  ASSERT_GE(fa06.size(), 2U);
  EXPECT_EQ(fa06[0], "P FA06 E400");
  EXPECT_EQ(server_->counters().no_reply, 2U);
  EXPECT_FALSE(model_.tripped());
}

// ---- Scanner words and the drive command ---------------------------------------------------------------

TEST_F(RegisterProxyDriveChannelTest, ScannerWordsOnFa06AndFa07WaitWhileTakenAndComeBackOnRelease) {
  SetEeprom({{0xC003, 13}});  // c001 = 1 (FA06), c002 = 3 (FA07), c003 = 13 (acc)
  StartRecorded();
  proxy_->SetCommandWords({0xC400, 0x1770, 30, 0, 0, 0});
  RunFor(100 * kMilli);
  ASSERT_EQ(Reg(kFa06), 0xC400);

  std::size_t mark = Mark();
  proxy_->SetDriveCommand({0xC000, 0x0BB8});
  proxy_->SetCommandWords({0xC400, 0x0FA0, 30, 0, 0, 0});  // changed scanner words: still not written
  RunFor(2 * kSecond);
  const Texts drive = WriteTexts({kFa06, kFa07}, mark);
  ASSERT_GE(drive.size(), 8U);  // the take-over and three refreshes of each
  EXPECT_EQ(drive[0], "P FA06 C000");
  EXPECT_EQ(drive[1], "P FA07 0BB8");
  for (const std::string& text : drive) EXPECT_TRUE(text == "P FA06 C000" || text == "P FA07 0BB8") << text;
  const Texts acc = WriteTexts({kAcc}, mark);  // the other scanner word goes on
  ASSERT_GE(acc.size(), 3U);
  for (const std::string& text : acc) EXPECT_EQ(text, "P 0009 001E");
  EXPECT_EQ(proxy_->CommandWords(), (ScannerWords{0xC400, 0x0FA0, 30, 0, 0, 0}));

  mark = Mark();
  proxy_->ReleaseDriveCommand();
  const Micros release_at = Now();
  EXPECT_FALSE(proxy_->drive_command_taken());
  RunFor(100 * kMilli);
  const std::vector<SentRequest> back = WritesOf({kFa06, kFa07}, mark);
  ASSERT_EQ(WriteTexts({kFa06, kFa07}, mark), (Texts{"P FA06 C400", "P FA07 0FA0"}));
  EXPECT_LE(back[0].at - release_at, kExchange);
  EXPECT_EQ(back[1].at - back[0].at, kExchange);
  EXPECT_TRUE(proxy_->IsScannerTarget(kFa06));  // the scanner words' again
}

TEST_F(RegisterProxyDriveChannelTest, TakenRegistersAreScannerTargetsAndTheReleaseWritesNothing) {
  StartRecorded();
  EXPECT_FALSE(proxy_->IsScannerTarget(kFa06));  // c604 = 0, no scanner words: FC06 to FA06/FA07 works
  EXPECT_FALSE(proxy_->IsScannerTarget(kFa07));
  EXPECT_EQ(WriteNow(kFa07, 1000).error, AccessError::kNone);
  proxy_->SetDriveCommand({0x0000, 0x1770});
  EXPECT_TRUE(proxy_->IsScannerTarget(kFa06));
  EXPECT_TRUE(proxy_->IsScannerTarget(kFa07));
  EXPECT_FALSE(proxy_->IsScannerTarget(kFa23));
  EXPECT_FALSE(proxy_->IsScannerTarget(0));
  EXPECT_EQ(WriteNow(kFa06, 0xC400).error, AccessError::kReservedForScanner);
  EXPECT_EQ(WriteNow(kFa07, 1000).error, AccessError::kReservedForScanner);
  RunFor(100 * kMilli);
  EXPECT_EQ(Reg(kFa07), 0x1770);

  const std::size_t mark = Mark();
  proxy_->ReleaseDriveCommand();
  EXPECT_FALSE(proxy_->IsScannerTarget(kFa06));
  EXPECT_FALSE(proxy_->IsScannerTarget(kFa07));
  RunFor(kSecond);
  EXPECT_EQ(WriteNow(kFa07, 1000).error, AccessError::kNone);
  EXPECT_EQ(WriteTexts({kFa06, kFa07}, mark), Texts{"P FA07 03E8"});  // only the on-demand write
  EXPECT_EQ(Reg(kFa07), 1000);
}

TEST_F(RegisterProxyDriveChannelTest, TheDriveCommandDoesNotArmTheScannerWords) {
  SetEeprom({{0xC003, 13}});  // word 3 -> acc: its held 0 must not reach the inverter
  StartRecorded();
  proxy_->SetDriveCommand({0xC000, 0x0BB8});
  RunFor(2 * kSecond);
  EXPECT_EQ(WriteTexts({kAcc}, 0), Texts{});
  EXPECT_EQ(Reg(kAcc), 100);
  EXPECT_FALSE(proxy_->IsScannerTarget(kAcc));
  EXPECT_EQ(proxy_->counters().command_writes, proxy_->counters().drive_command_writes);
}

TEST_F(RegisterProxyDriveChannelTest, MaskedScannerWordsAreTheOnlyOnesExchanged) {
  SetEeprom({{0xC003, 13}, {0xC004, 14}});  // words 3, 4 -> acc, dec
  StartRecorded();
  std::size_t mark = Mark();
  proxy_->SetCommandWordsMasked({0xC400, 0x1770, 30, 40, 0, 0}, 0x03);
  RunFor(kSecond);
  const Texts first = WriteTexts({kFa06, kFa07, kAcc, kDec}, mark);
  ASSERT_GE(first.size(), 2U);
  EXPECT_EQ(first[0], "P FA06 C400");
  EXPECT_EQ(first[1], "P FA07 1770");
  EXPECT_EQ(WriteTexts({kAcc, kDec}, mark), Texts{});
  EXPECT_TRUE(proxy_->IsScannerTarget(kFa06));
  EXPECT_FALSE(proxy_->IsScannerTarget(kAcc));  // not in use while the mask leaves it out
  EXPECT_EQ(proxy_->CommandWords(), (ScannerWords{0xC400, 0x1770, 0, 0, 0, 0}));

  mark = Mark();
  proxy_->SetCommandWordsMasked({0xC400, 0x1770, 30, 40, 0, 0}, 0x07);  // word 3 joins: written at once
  const Micros joined_at = Now();
  RunFor(100 * kMilli);
  const std::vector<SentRequest> joined = WritesOf({kAcc, kDec}, mark);
  ASSERT_EQ(WriteTexts({kAcc, kDec}, mark), Texts{"P 0009 001E"});
  EXPECT_LE(joined[0].at - joined_at, kExchange);
  EXPECT_TRUE(proxy_->IsScannerTarget(kAcc));

  mark = Mark();
  proxy_->SetCommandWordsMasked({0xC400, 0x1770, 31, 40, 0, 0}, 0x03);  // left out again: its 31 is ignored
  RunFor(kSecond);
  EXPECT_EQ(WriteTexts({kAcc, kDec}, mark), Texts{});
  EXPECT_EQ(Reg(kAcc), 30);
  EXPECT_EQ(proxy_->CommandWords(), (ScannerWords{0xC400, 0x1770, 30, 0, 0, 0}));

  mark = Mark();
  proxy_->SetCommandWords({0xC400, 0x1770, 31, 40, 0, 0});  // every word
  RunFor(100 * kMilli);
  EXPECT_EQ(WriteTexts({kAcc, kDec}, mark), (Texts{"P 0009 001F", "P 0010 0028"}));
  EXPECT_TRUE(proxy_->IsScannerTarget(kDec));
}

// ---- Feedback ------------------------------------------------------------------------------------------

TEST_F(RegisterProxyDriveChannelTest, FeedbackIsReadInEachCycleOnlyWhileWanted) {
  SetEeprom({{0xC022, 0}, {kAcc, 10}});  // no monitor word reads FD00
  StartRecorded();
  RunFor(kSecond);
  proxy_->SetDriveCommand({0xC000, 0x0BB8});  // stopped, 30 Hz commanded
  RunFor(100 * kMilli);
  std::size_t mark = Mark();
  RunFor(100 * kMilli);
  ExpectReadCycles(mark, {"R FD01"}, 10);
  EXPECT_FALSE(proxy_->DriveFeedback().known);

  proxy_->SetFeedbackWanted(true);
  EXPECT_FALSE(proxy_->DriveFeedback().known);
  mark = Mark();
  RunFor(200 * kMilli);
  ExpectReadCycles(mark, {"R FD01", "R FD00", "R FE02"}, 8);
  DriveFeedbackWords feedback = proxy_->DriveFeedback();
  EXPECT_TRUE(feedback.known);
  EXPECT_EQ(feedback.fd01, proxy_->drive_status());
  EXPECT_EQ(feedback.fd00, 0);
  EXPECT_EQ(feedback.fe02, 0x0BB8);

  proxy_->SetDriveCommand({0xC400, 0x0BB8});
  RunFor(kSecond);
  feedback = proxy_->DriveFeedback();
  EXPECT_EQ(feedback.fd01, 0x6400);  // running
  EXPECT_EQ(feedback.fd00, 0x0BB8);
  EXPECT_EQ(feedback.fe02, 0x0BB8);

  proxy_->SetFeedbackWanted(false);
  EXPECT_FALSE(proxy_->DriveFeedback().known);
  mark = Mark();
  RunFor(100 * kMilli);
  ExpectReadCycles(mark, {"R FD01"}, 10);
}

TEST_F(RegisterProxyDriveChannelTest, FeedbackSharesTheMonitorWordsReadOfFd00) {
  SetEeprom({{kAcc, 10}});
  StartRecorded();  // c021 = 1 (FD01), c022 = 2 (FD00)
  proxy_->SetCommandWords({0xC400, 0x1770, 0, 0, 0, 0});
  RunFor(2 * kSecond);
  const ScannerWords monitors = proxy_->MonitorWords();
  EXPECT_EQ(monitors, (ScannerWords{0x6400, 0x1770, 0, 0, 0, 0}));
  proxy_->SetFeedbackWanted(true);
  EXPECT_EQ(proxy_->MonitorWords(), monitors);  // the new plan keeps the values read
  const std::size_t mark = Mark();
  RunFor(200 * kMilli);
  ExpectReadCycles(mark, {"R FD01", "R FD00", "R FE02"}, 8);
  const DriveFeedbackWords feedback = proxy_->DriveFeedback();
  EXPECT_TRUE(feedback.known);
  EXPECT_EQ(feedback.fd00, 0x1770);
  EXPECT_EQ(feedback.fe02, 0x1770);
  EXPECT_EQ(proxy_->MonitorWords(), monitors);
}

TEST_F(RegisterProxyDriveChannelTest, FeedbackUsesTheBlockReadWhereTheSelectionsCoverFd00) {
  SetEeprom({{0x0875, 1}, {0x0876, 2}, {0xC022, 0}});  // block data 1 = FD01, 2 = FD00
  StartRecorded();
  RunFor(kSecond);
  std::size_t mark = Mark();
  RunFor(100 * kMilli);
  ExpectReadCycles(mark, {"X 1"}, 10);  // FD00 is not needed: nR stops at FD01
  proxy_->SetFeedbackWanted(true);
  mark = Mark();
  RunFor(200 * kMilli);
  ExpectReadCycles(mark, {"X 2", "R FE02"}, 10);
  EXPECT_TRUE(proxy_->DriveFeedback().known);
  EXPECT_EQ(proxy_->counters().monitor_errors, 0U);
}

// ---- Loss actions --------------------------------------------------------------------------------------

class RegisterProxyDriveChannelLossTest : public RegisterProxyDriveChannelTest {
 protected:
  // The drive command runs the drive at 60 Hz, then the network is lost: c100 = 0.5 s (the deadline
  // falls between two refreshes of the drive command).
  void RunThenLose(int c101) {
    SetEeprom({{0xC100, 5}, {0xC101, c101}, {kAcc, 10}, {kDec, 10}});
    StartRecorded();
    proxy_->SetDriveCommand({0xC400, 0x1770});
    RunFor(1300 * kMilli);
    deadline_ = Now() + 500 * kMilli;
    proxy_->NetworkLost(LossCause::kCipConnection, Now());
  }
  Micros deadline_ = 0;
};

TEST_F(RegisterProxyDriveChannelLossTest, NoDriveCommandWhileTheActionIsInForceThenAfterTheNextCommand) {
  RunThenLose(3);  // coast
  RunUntil(deadline_ - 1);
  EXPECT_EQ(Reg(kFa06), 0xC400);
  const std::size_t mark = Mark();
  RunFor(2 * kSecond);
  EXPECT_TRUE(proxy_->loss_action_active());
  const std::vector<SentRequest> during = WritesOf({kFa06, kFa07}, mark);
  ASSERT_EQ(during.size(), 4U);  // the action, then its refresh every 500 ms: nothing of the drive command
  EXPECT_LE(during[0].at - deadline_, kExchange);
  for (const SentRequest& write : during) EXPECT_EQ(write.text, "P FA06 8800");
  EXPECT_EQ(Reg(kFd00), 0);

  std::size_t restored = Mark();
  proxy_->NetworkRestored(Now());
  RunFor(kSecond);
  EXPECT_EQ(WriteTexts({kFa06, kFa07}, restored), Texts{});  // not before the drive profile sends again
  EXPECT_TRUE(proxy_->drive_command_taken());
  EXPECT_TRUE(proxy_->IsScannerTarget(kFa06));
  restored = Mark();
  proxy_->SetDriveCommand({0xC400, 0x1770});
  RunFor(100 * kMilli);
  EXPECT_EQ(WriteTexts({kFa06, kFa07}, restored), (Texts{"P FA06 C400", "P FA07 1770"}));
}

TEST_F(RegisterProxyDriveChannelLossTest, ACommandSentDuringTheActionIsWrittenWhenRestored) {
  RunThenLose(3);
  ASSERT_TRUE(RunUntilTrue([this] { return Reg(kFa06) == 0x8800; }, kSecond).has_value());
  std::size_t mark = Mark();
  proxy_->SetDriveCommand({0xC400, 0x0BB8});
  RunFor(200 * kMilli);
  EXPECT_EQ(WriteTexts({kFa07}, mark), Texts{});
  EXPECT_EQ(Reg(kFa07), 0x1770);
  mark = Mark();
  proxy_->NetworkRestored(Now());
  const Micros restored_at = Now();
  RunFor(100 * kMilli);
  const std::vector<SentRequest> writes = WritesOf({kFa06, kFa07}, mark);
  ASSERT_EQ(WriteTexts({kFa06, kFa07}, mark), (Texts{"P FA06 C400", "P FA07 0BB8"}));
  EXPECT_LE(writes[1].at - restored_at, 2 * kExchange);
}

TEST_F(RegisterProxyDriveChannelLossTest, Action2DeceleratesFromTheDriveCommandsFa06) {
  RunThenLose(2);  // c001 = 1 holds nothing: the held FA06 is the drive command's C400
  const auto at = RunUntilTrue([this] { return Reg(kFa06) != 0xC400; }, kSecond);
  ASSERT_TRUE(at.has_value());
  EXPECT_GE(*at, deadline_);
  EXPECT_EQ(Reg(kFa06), 0xC000);  // run cleared, command priority kept
  RunFor(200 * kMilli);
  EXPECT_GT(Reg(kFd00), 0);  // decelerating, not coasting
}

// The connection that held the drive command closed first, then c100 ran out (integration.eip_io found
// the action working from an empty FA06): decelerate keeps the released command's priority bits and
// preset speed its frequency priority.
TEST_F(RegisterProxyDriveChannelLossTest, Action2AfterTheReleaseDeceleratesFromTheReleasedFa06) {
  RunThenLose(2);
  proxy_->ReleaseDriveCommand();
  const auto at = RunUntilTrue([this] { return Reg(kFa06) != 0xC400; }, kSecond);
  ASSERT_TRUE(at.has_value());
  EXPECT_GE(*at, deadline_);
  EXPECT_EQ(Reg(kFa06), 0xC000);
}

TEST_F(RegisterProxyDriveChannelLossTest, ATakeOverForgetsTheReleasedFa06) {
  RunThenLose(2);
  proxy_->ReleaseDriveCommand();
  proxy_->SetDriveCommand({0x8400, 0x1770});  // another holder, without frequency priority
  proxy_->ReleaseDriveCommand();
  ASSERT_TRUE(RunUntilTrue([this] { return Reg(kFa06) == 0x8000; }, kSecond).has_value());
}

// ---- Reloads -------------------------------------------------------------------------------------------

TEST_F(RegisterProxyDriveChannelTest, F899ReloadForgetsTheDriveCommand) {
  StartRecorded();
  proxy_->SetFeedbackWanted(true);
  proxy_->SetDriveCommand({0xC000, 0x0BB8});  // stopped: f899 is refused while running
  RunFor(kSecond);
  ASSERT_TRUE(proxy_->DriveFeedback().known);
  EXPECT_EQ(WriteNow(0x0899, 1).error, AccessError::kNone);
  ASSERT_TRUE(RunUntilTrue([this] { return config_.loads.size() == 2; }, 3 * kSecond).has_value());
  EXPECT_FALSE(proxy_->drive_command_taken());
  EXPECT_FALSE(proxy_->IsScannerTarget(kFa06));
  EXPECT_FALSE(proxy_->DriveFeedback().known);  // not read since the load yet

  std::size_t mark = Mark();
  RunFor(kSecond);
  EXPECT_EQ(WriteTexts({kFa06, kFa07}, mark), Texts{});
  EXPECT_EQ(Reg(kFa07), 0);  // the reset cleared it
  EXPECT_TRUE(proxy_->DriveFeedback().known);  // still wanted: FD00/FE02 are read again

  mark = Mark();
  proxy_->SetDriveCommand({0xC000, 0x0BB8});
  RunFor(100 * kMilli);
  EXPECT_EQ(WriteTexts({kFa06, kFa07}, mark), (Texts{"P FA06 C000", "P FA07 0BB8"}));
}

TEST_F(RegisterProxyDriveChannelTest, E23RecoveryWritesTheDriveCommandAgain) {
  StartRecorded();
  proxy_->SetDriveCommand({0xC400, 0x1770});
  RunFor(kSecond);
  server_->Inject({sim::Fault::Kind::kSilent, sim::Fault::kUntilCleared, 0});
  ASSERT_TRUE(RunUntilTrue([this] { return proxy_->link().option_fault(); }, 2 * kSecond).has_value());
  model_.PowerCycle();  // the inverter lost its RAM meanwhile
  const std::size_t mark = Mark();
  Micros loaded_at = 0;
  config_.on_load = [&] { loaded_at = Now(); };
  server_->ClearFaults();
  ASSERT_TRUE(RunUntilTrue([this] { return config_.loads.size() == 2; }, 4 * kSecond).has_value());
  // Not a card reset: still taken, written again at once after the load (first in the same pass).
  EXPECT_TRUE(proxy_->drive_command_taken());
  RunFor(100 * kMilli);
  const std::vector<SentRequest> writes = WritesOf({kFa06, kFa07}, mark);
  ASSERT_EQ(WriteTexts({kFa06, kFa07}, mark), (Texts{"P FA06 C400", "P FA07 1770"}));
  EXPECT_EQ(writes[0].at, loaded_at);
  EXPECT_EQ(Reg(kFa06), 0xC400);
}

}  // namespace
}  // namespace drive_link::test
