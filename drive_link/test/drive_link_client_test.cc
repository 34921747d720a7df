// drive_link::LinkClient against a fake inverter: a hal::SerialPort that decodes the card's requests with
// the codec and answers with encoded replies, on a fake clock, with fault injection (dropped, delayed,
// corrupted and split replies, error codes, silence, tripped replies, the silence after a fault reset).
// Exact request bytes come from seed 003 (the VF-S11 manual's examples) where the manual has them.
#include "drive_link/link_client.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <deque>
#include <functional>
#include <map>
#include <optional>
#include <vector>

#include "fake_clock.h"

namespace drive_link {
namespace {

using Bytes = std::vector<std::uint8_t>;
using hal::kMicrosPerMilli;
using hal::kMicrosPerSecond;
using hal::Micros;

// A read at 19200 baud, 8E1: reply_timeout 100 ms + 5 request bytes of 11 bits (2865 us) + a longest
// reply of 17 bytes of 12 bits (10625 us).
constexpr Micros kReadBudget = 100 * kMicrosPerMilli + 2865 + 10625;

// The simulated inverter's end of the serial line. Requests are answered `reply_delay` after their last
// byte arrives; reply bytes become readable `byte_interval` apart.
class FakeInverter final : public hal::SerialPort {
 public:
  explicit FakeInverter(const hal::test::FakeClock& clock) : clock_(clock) {}

  // --- hal::SerialPort ---
  base::Status Configure(const hal::SerialConfig& config) override {
    configured = config;
    ++configure_calls;
    return base::OkStatus();
  }

  base::Result<std::size_t> Read(std::span<std::uint8_t> buffer) override {
    if (data_loss_after_bytes && delivered_ >= *data_loss_after_bytes && Ready()) {
      // The damaged byte is discarded and reported once.
      data_loss_after_bytes.reset();
      out_.pop_front();
      return base::DataLoss();
    }
    std::size_t n = 0;
    while (n < buffer.size() && n < read_chunk && Ready()) {
      if (data_loss_after_bytes && delivered_ >= *data_loss_after_bytes) break;
      buffer[n++] = out_.front().byte;
      out_.pop_front();
      ++delivered_;
    }
    if (n == 0) return base::Unavailable();
    return n;
  }

  base::Result<std::size_t> Write(std::span<const std::uint8_t> bytes) override {
    ++write_calls;
    if (stalled_writes > 0) {
      --stalled_writes;
      return std::size_t{0};
    }
    const std::size_t accepted = std::min(bytes.size(), write_limit);
    for (std::size_t i = 0; i < accepted; ++i) Receive(bytes[i]);
    return accepted;
  }

  // --- test side ---
  // When the next reply byte becomes readable (kNever: none pending).
  Micros NextReadyAt() const { return out_.empty() ? hal::kNever : out_.front().ready_at; }
  // Puts raw bytes on the line towards the card, readable from `at`.
  void Inject(const Bytes& bytes, Micros at) {
    for (std::uint8_t byte : bytes) Queue(at, byte);
  }
  std::size_t RequestCount() const { return requests.size(); }

  std::map<std::uint16_t, std::uint16_t> registers = {{0xFD01, 0x4000}, {0xFD00, 0x1770}, {0x0000, 0x0000}};
  std::array<std::uint16_t, wire::kMaxBlockReads> block_reads{};
  std::uint8_t block_write_status = 0;
  std::uint8_t own_number = 0;
  bool tripped = false;
  bool silent = false;             // answers nothing
  int drop_next = 0;               // answers nothing to the next n requests
  int corrupt_next = 0;            // flips the checksum of the next n replies
  std::deque<wire::ErrorCode> error_next;  // answers the next requests with these codes
  Micros reply_delay = 5 * kMicrosPerMilli;
  Micros byte_interval = 0;
  Micros reset_silence = 800 * kMicrosPerMilli;  // deaf this long after a fault reset (FA06/FA00 bit 13)
  std::size_t write_limit = 64;    // bytes taken per Write call
  int stalled_writes = 0;          // the next n Write calls take nothing
  std::size_t read_chunk = 64;     // bytes handed out per Read call
  std::optional<std::size_t> data_loss_after_bytes;  // parity error on the byte after this many

  hal::SerialConfig configured{};
  int configure_calls = 0;
  int write_calls = 0;
  Bytes wire;                      // every byte the card wrote
  std::vector<Bytes> frames;       // every request frame, whole
  std::vector<wire::DecodedRequest> requests;
  std::vector<Micros> request_times;  // when each request's last byte arrived

 private:
  struct OutByte {
    Micros ready_at;
    std::uint8_t byte;
  };

  // Bytes leave in the order of their times; bytes of equal time in the order they were queued.
  void Queue(Micros at, std::uint8_t byte) {
    const auto later = std::upper_bound(out_.begin(), out_.end(), at,
                                        [](Micros t, const OutByte& b) { return t < b.ready_at; });
    out_.insert(later, OutByte{at, byte});
  }

  bool Ready() const { return !out_.empty() && out_.front().ready_at <= clock_.NowMicros(); }

  void Receive(std::uint8_t byte) {
    wire.push_back(byte);
    std::span<const std::uint8_t> rest(&byte, 1);
    while (!rest.empty()) {
      const wire::StreamFramer::FeedResult fed = framer_.Feed(rest);
      rest = rest.subspan(fed.consumed);
      if (!fed.frame_ready) continue;
      frames.emplace_back(framer_.frame().begin(), framer_.frame().end());
      requests.push_back(wire::DecodeRequest(framer_.frame()));
      request_times.push_back(clock_.NowMicros());
      Answer(requests.back());
    }
  }

  void Answer(const wire::DecodedRequest& request) {
    const Micros now = clock_.NowMicros();
    if (silent || now < deaf_until_) return;
    if (drop_next > 0) {
      --drop_next;
      return;
    }
    std::array<std::uint8_t, wire::kMaxFrameLength> out{};
    base::Result<std::size_t> length = std::size_t{0};
    const wire::Envelope envelope = wire::ReplyEnvelope(request.request.envelope, own_number);
    std::optional<wire::ErrorCode> error = wire::ErrorReplyFor(request);
    if (!error && !error_next.empty()) {
      error = error_next.front();
      error_next.pop_front();
    }
    if (!request.ok() && !error) return;  // format errors: silence
    if (error) {
      wire::ErrorReply reply;
      reply.envelope = envelope;
      reply.tripped = tripped;
      reply.code = *error;
      length = wire::EncodeErrorReply(reply, out);
    } else if (request.kind == wire::RequestKind::kBlock) {
      wire::BlockReply reply;
      reply.address = wire::ReplyAddress(request.block.address, own_number);
      reply.tripped = tripped;
      reply.read_count = wire::ReadGroupsToReturn(request.block);
      reply.write_status = block_write_status;
      for (std::size_t i = 0; i < reply.read_count; ++i) reply.read_data[i] = block_reads[i];
      length = wire::EncodeBlockReply(reply, out);
    } else {
      const wire::Request& r = request.request;
      wire::Reply reply;
      reply.envelope = envelope;
      reply.command = r.command;
      reply.tripped = tripped;
      reply.comm_number = r.comm_number;
      if (r.command == wire::Command::kRead) {
        const auto it = registers.find(r.comm_number);
        if (it == registers.end()) {
          error_next.push_front(wire::ErrorCode::kCommunicationNumberError);
          Answer(request);
          return;
        }
        reply.data = it->second;
      } else {
        registers[r.comm_number] = r.data;
        reply.data = r.data;
        if ((r.comm_number == 0xFA06 || r.comm_number == 0xFA00) && (r.data & 0x2000) != 0) {
          deaf_until_ = now + reset_silence;  // fault reset: no data is returned
          return;
        }
      }
      length = wire::EncodeReply(reply, out);
    }
    ASSERT_TRUE(length.ok());
    Bytes reply(out.begin(), out.begin() + static_cast<std::ptrdiff_t>(*length));
    if (corrupt_next > 0) {
      --corrupt_next;
      reply.back() = static_cast<std::uint8_t>(reply.back() ^ 0x01);
    }
    replies.push_back(reply);
    Micros at = now + reply_delay;
    for (std::uint8_t byte : reply) {
      Queue(at, byte);
      at += byte_interval;
    }
  }

 public:
  std::vector<Bytes> replies;  // every reply frame sent, whole

 private:
  const hal::test::FakeClock& clock_;
  wire::StreamFramer framer_{wire::Direction::kRequests};
  std::deque<OutByte> out_;
  std::size_t delivered_ = 0;
  Micros deaf_until_ = 0;
};

struct Delivered {
  RequestId id;
  Completion completion;
  Micros at;
  LinkState state_then;
};

class RecordingObserver final : public LinkObserver {
 public:
  explicit RecordingObserver(const hal::test::FakeClock& clock) : clock_(clock) {}

  void OnComplete(RequestId id, const Completion& completion) override {
    completions.push_back({id, completion, clock_.NowMicros(), client ? client->state() : LinkState::kStarting});
    if (on_complete) on_complete(id, completion);
  }
  void OnLinkStateChanged(LinkState previous, LinkState current) override {
    transitions.emplace_back(previous, current);
  }

  const Delivered* Find(RequestId id) const {
    for (const Delivered& d : completions) {
      if (d.id == id) return &d;
    }
    return nullptr;
  }

  const LinkClient* client = nullptr;
  std::function<void(RequestId, const Completion&)> on_complete;
  std::vector<Delivered> completions;
  std::vector<std::pair<LinkState, LinkState>> transitions;

 private:
  const hal::test::FakeClock& clock_;
};

class DriveLinkClientTest : public ::testing::Test {
 protected:
  // The defaults except the startup silence, which has its own test.
  static LinkConfig TestConfig() {
    LinkConfig config;
    config.startup_silence = 0;
    return config;
  }

  void Start(const LinkConfig& config = TestConfig()) {
    client_.emplace(inverter_, config, &observer_);
    observer_.client = &*client_;
    ASSERT_TRUE(client_->Start(clock_.NowMicros()).ok());
  }

  RequestId Submit(const Transaction& transaction) {
    const base::Result<RequestId> id = client_->Submit(transaction);
    EXPECT_TRUE(id.ok()) << base::StatusName(id.status());
    return id.ok() ? *id : kNoRequestId;
  }

  // An event loop on the fake clock: Poll, then jump to the client's deadline or the next reply byte,
  // whichever comes first, until `end` or until `done` says so. Fails if the client asks to run again
  // at the same instant over and over (a busy loop).
  void RunUntil(Micros end, const std::function<bool()>& done = nullptr) {
    int passes_at_same_time = 0;
    for (;;) {
      const Micros now = clock_.NowMicros();
      client_->Poll(now);
      if (now >= end || (done && done())) return;
      const Micros next = std::min({client_->NextDeadline(), inverter_.NextReadyAt(), end});
      if (next <= now) {
        if (++passes_at_same_time > 100) {
          ADD_FAILURE() << "the client keeps asking for a pass at " << now;
          return;
        }
        continue;
      }
      passes_at_same_time = 0;
      clock_.Set(next);
    }
  }
  void RunFor(Micros duration) { RunUntil(clock_.NowMicros() + duration); }

  // Runs until `id` completes (at most 10 s of fake time) and returns its completion; the clock stops at
  // the instant of the completion.
  Completion RunUntilComplete(RequestId id) {
    RunUntil(clock_.NowMicros() + 10 * kMicrosPerSecond, [&] { return observer_.Find(id) != nullptr; });
    const Delivered* delivered = observer_.Find(id);
    EXPECT_NE(delivered, nullptr) << "request " << id << " did not complete";
    return delivered != nullptr ? delivered->completion : Completion{};
  }

  hal::test::FakeClock clock_{1000 * kMicrosPerSecond};
  FakeInverter inverter_{clock_};
  RecordingObserver observer_{clock_};
  std::optional<LinkClient> client_;
};

// --- Bytes on the wire ---

TEST_F(DriveLinkClientTest, ReadFD01_SendsTheSeedFrameAndDeliversTheValue) {
  Start();
  const RequestId id = Submit(Transaction::Read(0xFD01));
  const Completion done = RunUntilComplete(id);
  EXPECT_EQ(inverter_.wire, (Bytes{0x2F, 0x52, 0xFD, 0x01, 0x7F}));  // seed 003 §3.11
  EXPECT_EQ(inverter_.replies.at(0), (Bytes{0x2F, 0x52, 0xFD, 0x01, 0x40, 0x00, 0xBF}));
  EXPECT_EQ(done.outcome, Outcome::kOk);
  EXPECT_EQ(done.kind, TransactionKind::kRead);
  EXPECT_EQ(done.comm_number, 0xFD01);
  EXPECT_EQ(done.data, 0x4000);
  EXPECT_FALSE(done.tripped);
  EXPECT_EQ(done.attempts, 1);
  EXPECT_EQ(client_->state(), LinkState::kUp);
  EXPECT_EQ(observer_.transitions,
            (std::vector<std::pair<LinkState, LinkState>>{{LinkState::kStarting, LinkState::kUp}}));
  EXPECT_EQ(client_->counters().frames_sent, 1U);
  EXPECT_EQ(client_->counters().replies, 1U);
  EXPECT_EQ(client_->queued(), 0U);
}

TEST_F(DriveLinkClientTest, ReadOf0000_IsTheSeedExample) {
  Start();
  EXPECT_TRUE(RunUntilComplete(Submit(Transaction::Read(0x0000))).ok());
  EXPECT_EQ(inverter_.wire, (Bytes{0x2F, 0x52, 0x00, 0x00, 0x81}));  // seed 003 §3.5
}

TEST_F(DriveLinkClientTest, Writes_SendExactFramesAndDeliverTheEcho) {
  Start();
  const Completion fa07 = RunUntilComplete(Submit(Transaction::Write(0xFA07, 0x1770)));
  EXPECT_EQ(inverter_.frames.at(0), (Bytes{0x2F, 0x57, 0xFA, 0x07, 0x17, 0x70, 0x0E}));
  EXPECT_EQ(fa07.outcome, Outcome::kOk);
  EXPECT_EQ(fa07.kind, TransactionKind::kWrite);
  EXPECT_EQ(fa07.data, 0x1770);

  // Seed 003 §3.11 (P FA01 = 60 Hz) and §3.8 (W 0010 = 10 s).
  EXPECT_TRUE(RunUntilComplete(Submit(Transaction::WriteRam(0xFA01, 0x1770))).ok());
  EXPECT_EQ(inverter_.frames.at(1), (Bytes{0x2F, 0x50, 0xFA, 0x01, 0x17, 0x70, 0x01}));
  EXPECT_TRUE(RunUntilComplete(Submit(Transaction::Write(0x0010, 0x0064))).ok());
  EXPECT_EQ(inverter_.frames.at(2), (Bytes{0x2F, 0x57, 0x00, 0x10, 0x00, 0x64, 0xFA}));
  EXPECT_EQ(inverter_.registers[0xFA07], 0x1770);
}

TEST_F(DriveLinkClientTest, AsciiMode_SendsChecksumAndStopCode) {
  LinkConfig config = TestConfig();
  config.mode = wire::Mode::kAscii;
  Start(config);
  const Completion done = RunUntilComplete(Submit(Transaction::Read(0xFD00)));
  const Bytes expected = {'(', 'R', 'F', 'D', '0', '0', '&', '8', 'A', ')', 0x0D};
  EXPECT_EQ(inverter_.wire, expected);
  const Bytes reply = {'(', 'R', 'F', 'D', '0', '0', '1', '7', '7', '0', '&', '5', '9', ')', 0x0D};
  EXPECT_EQ(inverter_.replies.at(0), reply);
  EXPECT_EQ(done.outcome, Outcome::kOk);
  EXPECT_EQ(done.data, 0x1770);
}

TEST_F(DriveLinkClientTest, BlockExchange_IsTheSeedExample) {
  Start();
  inverter_.block_reads = {0x6400, 0x1770, 0x1A8A, 0x24FD, 0x0000};
  const std::uint16_t writes[] = {0xC400, 0x1770};
  const Completion done = RunUntilComplete(Submit(Transaction::Block(writes, 5)));
  // Seed 003 §4: run forward at 60 Hz, read status, frequency, current, voltage, alarms.
  EXPECT_EQ(inverter_.wire, (Bytes{0x2F, 0x58, 0x02, 0x05, 0xC4, 0x00, 0x17, 0x70, 0xD9}));
  EXPECT_EQ(inverter_.replies.at(0),
            (Bytes{0x2F, 0x59, 0x05, 0x00, 0x64, 0x00, 0x17, 0x70, 0x1A, 0x8A, 0x24, 0xFD, 0x00, 0x00, 0x3D}));
  EXPECT_EQ(done.outcome, Outcome::kOk);
  EXPECT_EQ(done.kind, TransactionKind::kBlock);
  EXPECT_EQ(done.block_read_count, 5);
  EXPECT_EQ(done.block_write_status, 0);
  EXPECT_EQ(done.block_data, (std::array<std::uint16_t, 5>{0x6400, 0x1770, 0x1A8A, 0x24FD, 0x0000}));
}

TEST_F(DriveLinkClientTest, InverterNumber_IsSentAndExpectedBack) {
  LinkConfig config = TestConfig();
  config.address = wire::InverterAddress::Number(5);
  inverter_.own_number = 5;
  Start(config);
  EXPECT_TRUE(RunUntilComplete(Submit(Transaction::Read(0xFD01))).ok());
  EXPECT_EQ(inverter_.wire, (Bytes{0x2F, 0x05, 0x52, 0xFD, 0x01, 0x84}));
}

// --- Transport: partial writes, split replies ---

TEST_F(DriveLinkClientTest, PartialWrites_TheFrameGoesOutWhole) {
  Start();
  inverter_.write_limit = 1;
  inverter_.stalled_writes = 3;
  const Completion done = RunUntilComplete(Submit(Transaction::Write(0xFA07, 0x1770)));
  EXPECT_EQ(inverter_.wire, (Bytes{0x2F, 0x57, 0xFA, 0x07, 0x17, 0x70, 0x0E}));
  EXPECT_EQ(done.outcome, Outcome::kOk);
  EXPECT_EQ(done.attempts, 1);
  EXPECT_GE(client_->counters().partial_writes, 3U);
  EXPECT_EQ(client_->counters().frames_sent, 1U);
}

TEST_F(DriveLinkClientTest, StalledPort_RetriesTheWriteWithoutSpinning) {
  Start();
  inverter_.stalled_writes = 5;
  const Micros start = clock_.NowMicros();
  client_->Poll(start);
  ASSERT_TRUE(client_->Submit(Transaction::Read(0xFD01)).ok());
  client_->Poll(start);
  EXPECT_TRUE(inverter_.wire.empty());
  // Not "at once": the next try is a millisecond later.
  EXPECT_EQ(client_->NextDeadline(), start + kMicrosPerMilli);
  RunFor(50 * kMicrosPerMilli);
  EXPECT_EQ(inverter_.wire, (Bytes{0x2F, 0x52, 0xFD, 0x01, 0x7F}));
}

TEST_F(DriveLinkClientTest, ReplySplitAcrossManyReads_IsReassembled) {
  Start();
  inverter_.read_chunk = 1;
  inverter_.byte_interval = kMicrosPerMilli;  // one byte readable per millisecond: 7 passes
  inverter_.block_reads = {1, 2, 3, 4, 5};
  const Completion read = RunUntilComplete(Submit(Transaction::Read(0xFD00)));
  EXPECT_EQ(read.outcome, Outcome::kOk);
  EXPECT_EQ(read.data, 0x1770);
  const Completion block = RunUntilComplete(Submit(Transaction::Block({}, 5)));
  EXPECT_EQ(block.outcome, Outcome::kOk);
  EXPECT_EQ(block.block_data, (std::array<std::uint16_t, 5>{1, 2, 3, 4, 5}));
  EXPECT_EQ(client_->counters().timeouts, 0U);
  EXPECT_EQ(client_->counters().garbled_frames, 0U);
}

// --- Timeouts and retries ---

TEST_F(DriveLinkClientTest, ReplyDeadline_IsTheDocumentedBudget) {
  Start();
  inverter_.silent = true;
  const Micros sent = clock_.NowMicros();
  Submit(Transaction::Read(0xFD01));
  client_->Poll(sent);
  ASSERT_EQ(inverter_.RequestCount(), 1U);
  EXPECT_EQ(client_->NextDeadline(), sent + kReadBudget);
}

TEST_F(DriveLinkClientTest, OneDroppedReply_IsRetriedOnce) {
  Start();
  inverter_.drop_next = 1;
  const Micros sent = clock_.NowMicros();
  const Completion done = RunUntilComplete(Submit(Transaction::Read(0xFD01)));
  EXPECT_EQ(done.outcome, Outcome::kOk);
  EXPECT_EQ(done.data, 0x4000);
  EXPECT_EQ(done.attempts, 2);
  ASSERT_EQ(inverter_.frames.size(), 2U);
  EXPECT_EQ(inverter_.frames[0], inverter_.frames[1]);
  EXPECT_EQ(inverter_.request_times[1], sent + kReadBudget);
  EXPECT_EQ(client_->counters().timeouts, 1U);
  EXPECT_EQ(client_->counters().retries, 1U);
  EXPECT_EQ(client_->counters().failed_transactions, 0U);
  EXPECT_EQ(client_->state(), LinkState::kUp);
}

TEST_F(DriveLinkClientTest, NoReplyToAnyAttempt_CompletesWithTimeout) {
  Start();
  EXPECT_TRUE(RunUntilComplete(Submit(Transaction::Read(0xFD01))).ok());
  inverter_.silent = true;
  const Micros sent = clock_.NowMicros();
  const RequestId id = Submit(Transaction::Read(0xFD00));
  const Completion done = RunUntilComplete(id);
  EXPECT_EQ(done.outcome, Outcome::kTimeout);
  EXPECT_EQ(done.attempts, 3);
  EXPECT_EQ(done.comm_number, 0xFD00);
  EXPECT_EQ(observer_.Find(id)->at, sent + 3 * kReadBudget);
  EXPECT_EQ(inverter_.RequestCount(), 4U);
  EXPECT_EQ(client_->counters().timeouts, 3U);
  EXPECT_EQ(client_->counters().retries, 2U);
  EXPECT_EQ(client_->counters().failed_transactions, 1U);
  EXPECT_EQ(client_->state(), LinkState::kDegraded);
  EXPECT_FALSE(client_->option_fault());
  EXPECT_EQ(client_->NextDeadline(), hal::kNever);

  // One good exchange brings the link back up.
  inverter_.silent = false;
  EXPECT_TRUE(RunUntilComplete(Submit(Transaction::Read(0xFD01))).ok());
  EXPECT_EQ(client_->state(), LinkState::kUp);
}

TEST_F(DriveLinkClientTest, MaxRetries_IsConfigurable) {
  LinkConfig config = TestConfig();
  config.max_retries = 0;
  Start(config);
  inverter_.silent = true;
  const Completion done = RunUntilComplete(Submit(Transaction::Read(0xFD01)));
  EXPECT_EQ(done.outcome, Outcome::kTimeout);
  EXPECT_EQ(done.attempts, 1);
  EXPECT_EQ(inverter_.RequestCount(), 1U);
}

TEST_F(DriveLinkClientTest, GarbledReply_IsCountedAndRetriedAfterTheTimeout) {
  Start();
  inverter_.corrupt_next = 1;
  const Completion done = RunUntilComplete(Submit(Transaction::Read(0xFD01)));
  EXPECT_EQ(done.outcome, Outcome::kOk);
  EXPECT_EQ(done.attempts, 2);
  EXPECT_EQ(client_->counters().garbled_frames, 1U);
  EXPECT_EQ(client_->counters().timeouts, 1U);
}

TEST_F(DriveLinkClientTest, ParityErrorInAReply_DropsTheFrameAndTheRetryWorks) {
  Start();
  inverter_.data_loss_after_bytes = 3;  // the 4th reply byte is damaged
  const Completion done = RunUntilComplete(Submit(Transaction::Read(0xFD01)));
  EXPECT_EQ(done.outcome, Outcome::kOk);
  EXPECT_EQ(done.data, 0x4000);
  EXPECT_EQ(done.attempts, 2);
  EXPECT_EQ(client_->counters().rx_errors, 1U);
}

TEST_F(DriveLinkClientTest, InverterWaitTime_F805_ExtendsTheTimeout) {
  LinkConfig config = TestConfig();
  config.inverter_wait_time = 300 * kMicrosPerMilli;
  Start(config);
  inverter_.reply_delay = 300 * kMicrosPerMilli;
  const Completion done = RunUntilComplete(Submit(Transaction::Read(0xFD01)));
  EXPECT_EQ(done.outcome, Outcome::kOk);
  EXPECT_EQ(done.attempts, 1);
}

TEST_F(DriveLinkClientTest, LateReply_AnswersTheRetry_WhoseOwnReplyIsStray) {
  Start();
  inverter_.reply_delay = kReadBudget + 10 * kMicrosPerMilli;
  const Completion done = RunUntilComplete(Submit(Transaction::Read(0xFD01)));
  // The first reply arrives while the second attempt waits and answers it (same command and number).
  EXPECT_EQ(done.outcome, Outcome::kOk);
  EXPECT_EQ(done.attempts, 2);
  RunFor(kMicrosPerSecond);
  EXPECT_EQ(client_->counters().stray_frames, 1U);  // the retry's own reply, after completion
}

TEST_F(DriveLinkClientTest, InterFrameGap_SeparatesReplyAndNextRequest) {
  LinkConfig config = TestConfig();
  config.inter_frame_gap = 20 * kMicrosPerMilli;
  Start(config);
  Submit(Transaction::Read(0xFD01));
  Submit(Transaction::Read(0xFD00));
  RunFor(kMicrosPerSecond);
  ASSERT_EQ(inverter_.request_times.size(), 2U);
  // Reply readable 5 ms after the first request, next request 20 ms after that.
  EXPECT_EQ(inverter_.request_times[1], inverter_.request_times[0] + 5 * kMicrosPerMilli + 20 * kMicrosPerMilli);
}

// --- Error replies ---

TEST_F(DriveLinkClientTest, ErrorReplyCodes_ArePassedThroughWithoutRetry) {
  Start();
  const wire::ErrorCode codes[] = {wire::ErrorCode::kImpossibleToExecute, wire::ErrorCode::kDataError,
                                   wire::ErrorCode::kCommunicationNumberError, wire::ErrorCode::kCommandError};
  for (wire::ErrorCode code : codes) {
    inverter_.error_next.push_back(code);
    const Completion done = RunUntilComplete(Submit(Transaction::Write(0x0011, 0x1F40)));
    EXPECT_EQ(done.outcome, Outcome::kErrorReply);
    EXPECT_EQ(done.error, code);
    EXPECT_EQ(done.attempts, 1);
    EXPECT_FALSE(done.tripped);
  }
  EXPECT_EQ(client_->counters().error_replies, 4U);
  EXPECT_EQ(client_->counters().retries, 0U);
  EXPECT_EQ(client_->counters().failed_transactions, 0U);
  EXPECT_EQ(client_->state(), LinkState::kUp);  // the inverter answered: the link is fine
  // An unknown number, as the fake's register file answers it.
  const Completion unknown = RunUntilComplete(Submit(Transaction::Read(0x0123)));
  EXPECT_EQ(unknown.outcome, Outcome::kErrorReply);
  EXPECT_EQ(unknown.error, wire::ErrorCode::kCommunicationNumberError);
  EXPECT_EQ(inverter_.replies.back(), (Bytes{0x2F, 0x4E, 0x00, 0x02, 0x7F}));  // seed 003 §3.7
}

TEST_F(DriveLinkClientTest, ChecksumErrorReply_IsRetried) {
  Start();
  inverter_.error_next.push_back(wire::ErrorCode::kChecksumError);
  const Completion done = RunUntilComplete(Submit(Transaction::Read(0xFD01)));
  EXPECT_EQ(done.outcome, Outcome::kOk);
  EXPECT_EQ(done.attempts, 2);
  EXPECT_EQ(client_->counters().error_replies, 1U);
  EXPECT_EQ(client_->counters().retries, 1U);
  EXPECT_EQ(client_->counters().timeouts, 0U);
}

TEST_F(DriveLinkClientTest, ChecksumErrorOnEveryAttempt_FailsTheTransaction) {
  Start();
  for (int i = 0; i < 3; ++i) inverter_.error_next.push_back(wire::ErrorCode::kChecksumError);
  const Completion done = RunUntilComplete(Submit(Transaction::Read(0xFD01)));
  EXPECT_EQ(done.outcome, Outcome::kErrorReply);
  EXPECT_EQ(done.error, wire::ErrorCode::kChecksumError);
  EXPECT_EQ(done.attempts, 3);
  EXPECT_EQ(client_->counters().failed_transactions, 1U);
  EXPECT_EQ(client_->state(), LinkState::kDegraded);
}

TEST_F(DriveLinkClientTest, TrippedInverter_LowercaseRepliesSetTheFlag) {
  Start();
  inverter_.tripped = true;
  inverter_.registers[0xFD01] = 0x0003;
  const Completion done = RunUntilComplete(Submit(Transaction::Read(0xFD01)));
  EXPECT_EQ(inverter_.replies.at(0), (Bytes{0x2F, 0x72, 0xFD, 0x01, 0x00, 0x03, 0xA2}));  // seed 003 §3.11
  EXPECT_EQ(done.outcome, Outcome::kOk);
  EXPECT_TRUE(done.tripped);
  EXPECT_EQ(done.data, 0x0003);
  EXPECT_TRUE(client_->inverter_tripped());

  inverter_.error_next.push_back(wire::ErrorCode::kDataError);
  const Completion error = RunUntilComplete(Submit(Transaction::Write(0x0010, 0xFFFF)));
  EXPECT_EQ(inverter_.replies.at(1), (Bytes{0x2F, 0x6E, 0x00, 0x01, 0x9E}));  // 'n'
  EXPECT_EQ(error.outcome, Outcome::kErrorReply);
  EXPECT_TRUE(error.tripped);

  inverter_.tripped = false;
  EXPECT_FALSE(RunUntilComplete(Submit(Transaction::Read(0xFD01))).tripped);
  EXPECT_FALSE(client_->inverter_tripped());
}

// --- Link state: e-23 and recovery ---

TEST_F(DriveLinkClientTest, ThreeFailedTransactions_DeclareOptionFault_AndAnAnswerClearsIt) {
  Start();
  EXPECT_TRUE(RunUntilComplete(Submit(Transaction::Read(0xFD01))).ok());
  inverter_.silent = true;
  const RequestId first = Submit(Transaction::Read(0xFD00));
  const RequestId second = Submit(Transaction::WriteRam(0xFA07, 0x1770));
  const RequestId third = Submit(Transaction::Read(0xFD01));
  const RequestId waiting = Submit(Transaction::Read(0xFE03));
  RunUntilComplete(waiting);

  EXPECT_EQ(observer_.Find(first)->completion.outcome, Outcome::kTimeout);
  EXPECT_EQ(observer_.Find(first)->state_then, LinkState::kDegraded);
  EXPECT_EQ(observer_.Find(second)->completion.outcome, Outcome::kTimeout);
  EXPECT_EQ(observer_.Find(third)->completion.outcome, Outcome::kTimeout);
  EXPECT_EQ(observer_.Find(third)->state_then, LinkState::kFault);  // final before the callback
  const Delivered* flushed = observer_.Find(waiting);
  EXPECT_EQ(flushed->completion.outcome, Outcome::kLinkDown);
  EXPECT_EQ(flushed->completion.attempts, 0);
  EXPECT_EQ(flushed->completion.comm_number, 0xFE03);
  EXPECT_EQ(inverter_.RequestCount(), 1U + 9U);  // 0xFE03 was never sent

  EXPECT_EQ(client_->state(), LinkState::kFault);
  EXPECT_TRUE(client_->option_fault());
  EXPECT_EQ(client_->counters().faults, 1U);
  EXPECT_EQ(client_->counters().failed_transactions, 3U);
  EXPECT_EQ(client_->Submit(Transaction::Read(0xFD01)).status(), base::FailedPrecondition());
  using S = LinkState;
  EXPECT_EQ(observer_.transitions, (std::vector<std::pair<S, S>>{{S::kStarting, S::kUp},
                                                                 {S::kUp, S::kDegraded},
                                                                 {S::kDegraded, S::kFault}}));

  // In fault: one probe read of FD01 every 500 ms, a single attempt each.
  const Micros fault_at = observer_.Find(third)->at;
  RunUntil(fault_at + 1600 * kMicrosPerMilli);
  ASSERT_EQ(inverter_.RequestCount(), 10U + 3U);
  for (std::size_t i = 10; i < 13; ++i) {
    EXPECT_EQ(inverter_.frames[i], (Bytes{0x2F, 0x52, 0xFD, 0x01, 0x7F}));
    EXPECT_EQ(inverter_.request_times[i], fault_at + (i - 9) * 500 * kMicrosPerMilli);
  }
  EXPECT_EQ(client_->counters().probes, 3U);
  EXPECT_TRUE(client_->option_fault());

  // The inverter answers again: the next probe brings the link up.
  inverter_.silent = false;
  RunUntil(fault_at + 2100 * kMicrosPerMilli);
  EXPECT_EQ(client_->state(), LinkState::kUp);
  EXPECT_FALSE(client_->option_fault());
  EXPECT_EQ(observer_.transitions.back(), (std::pair<S, S>{S::kFault, S::kUp}));
  EXPECT_EQ(client_->counters().probes, 4U);
  EXPECT_EQ(client_->NextDeadline(), hal::kNever);  // no more probes
  EXPECT_TRUE(RunUntilComplete(Submit(Transaction::Read(0xFD00))).ok());
}

TEST_F(DriveLinkClientTest, FaultThreshold_IsConfigurable) {
  LinkConfig config = TestConfig();
  config.fault_threshold = 1;
  config.max_retries = 0;
  Start(config);
  inverter_.silent = true;
  EXPECT_EQ(RunUntilComplete(Submit(Transaction::Read(0xFD01))).outcome, Outcome::kTimeout);
  EXPECT_TRUE(client_->option_fault());
}

TEST_F(DriveLinkClientTest, ErrorRepliesBetweenFailures_ResetTheCount) {
  Start();
  inverter_.silent = true;
  RunUntilComplete(Submit(Transaction::Read(0xFD01)));
  RunUntilComplete(Submit(Transaction::Read(0xFD01)));
  inverter_.silent = false;
  inverter_.error_next.push_back(wire::ErrorCode::kImpossibleToExecute);
  EXPECT_EQ(RunUntilComplete(Submit(Transaction::Write(0x0011, 1))).outcome, Outcome::kErrorReply);
  inverter_.silent = true;
  RunUntilComplete(Submit(Transaction::Read(0xFD01)));
  RunUntilComplete(Submit(Transaction::Read(0xFD01)));
  EXPECT_EQ(client_->state(), LinkState::kDegraded);
  EXPECT_FALSE(client_->option_fault());
}

// --- Expected silence ---

TEST_F(DriveLinkClientTest, SilenceAfterFaultReset_IsNotAFailure) {
  Start();
  EXPECT_TRUE(RunUntilComplete(Submit(Transaction::Read(0xFD01))).ok());
  const RequestId reset = Submit(Transaction::WriteRam(0xFA06, 0x2000));  // bit 13: fault reset
  const RequestId after = Submit(Transaction::Read(0xFD01));
  const Completion reset_done = RunUntilComplete(reset);
  EXPECT_EQ(reset_done.outcome, Outcome::kNoReply);
  EXPECT_EQ(reset_done.attempts, 1);  // never resent: a second edge would reset again
  const Micros reset_sent = inverter_.request_times.at(1);

  const Completion read = RunUntilComplete(after);
  EXPECT_EQ(read.outcome, Outcome::kOk);
  EXPECT_EQ(read.attempts, 1);
  ASSERT_EQ(inverter_.RequestCount(), 3U);
  // Nothing is sent during the reset silence (1 s by default); the inverter was deaf for 800 ms.
  EXPECT_EQ(inverter_.request_times[2], reset_sent + kMicrosPerSecond);
  EXPECT_EQ(client_->counters().silent_timeouts, 1U);
  EXPECT_EQ(client_->counters().timeouts, 0U);
  EXPECT_EQ(client_->counters().failed_transactions, 0U);
  EXPECT_EQ(client_->state(), LinkState::kUp);
  EXPECT_EQ(observer_.transitions.size(), 1U);  // only kStarting -> kUp
}

TEST_F(DriveLinkClientTest, FaultResetByBlockWrite_NeedsTheFlag) {
  Start();
  inverter_.silent = true;
  const std::uint16_t writes[] = {0x2000};
  Transaction reset = Transaction::Block(writes, 0);
  reset.expect_no_reply = true;
  const Completion done = RunUntilComplete(Submit(reset));
  EXPECT_EQ(done.outcome, Outcome::kNoReply);
  EXPECT_EQ(client_->counters().failed_transactions, 0U);
  EXPECT_EQ(client_->state(), LinkState::kStarting);
}

TEST_F(DriveLinkClientTest, QuietUntil_CoversTheRequestOnTheWireAndHoldsTheQueue) {
  Start();
  inverter_.silent = true;
  const RequestId on_wire = Submit(Transaction::Read(0xFD01));
  const RequestId held = Submit(Transaction::Read(0xFD00));
  client_->Poll(clock_.NowMicros());
  ASSERT_EQ(inverter_.RequestCount(), 1U);
  const Micros quiet_end = clock_.NowMicros() + 700 * kMicrosPerMilli;
  client_->QuietUntil(quiet_end);
  EXPECT_EQ(RunUntilComplete(on_wire).outcome, Outcome::kNoReply);
  inverter_.silent = false;
  EXPECT_TRUE(RunUntilComplete(held).ok());
  EXPECT_EQ(inverter_.request_times.at(1), quiet_end);
  EXPECT_EQ(client_->counters().failed_transactions, 0U);
  EXPECT_EQ(client_->counters().timeouts, 0U);
}

TEST_F(DriveLinkClientTest, StartupSilence_NothingIsSentForOneSecond) {
  const Micros start = clock_.NowMicros();
  client_.emplace(inverter_, LinkConfig{}, &observer_);
  EXPECT_EQ(client_->NextDeadline(), hal::kNever);
  ASSERT_TRUE(client_->Start(start).ok());
  EXPECT_EQ(inverter_.configure_calls, 1);
  EXPECT_EQ(inverter_.configured.baud, 19200U);
  EXPECT_EQ(inverter_.configured.parity, hal::Parity::kEven);
  EXPECT_EQ(inverter_.configured.stop_bits, 1);
  EXPECT_EQ(client_->Start(start), base::FailedPrecondition());
  const RequestId id = Submit(Transaction::Read(0xFD01));
  client_->Poll(start);
  EXPECT_EQ(client_->NextDeadline(), start + kMicrosPerSecond);
  EXPECT_TRUE(RunUntilComplete(id).ok());
  EXPECT_EQ(inverter_.request_times.at(0), start + kMicrosPerSecond);
}

// --- Queue, stray frames, configuration ---

TEST_F(DriveLinkClientTest, FullQueue_RefusesWithResourceExhausted) {
  Start();
  std::vector<RequestId> ids;
  for (std::size_t i = 0; i < kRequestQueueCapacity; ++i) ids.push_back(Submit(Transaction::Read(0xFD01)));
  EXPECT_EQ(client_->queued(), kRequestQueueCapacity);
  EXPECT_EQ(client_->Submit(Transaction::Read(0xFD01)).status(), base::ResourceExhausted());
  RunUntilComplete(ids.front());
  EXPECT_TRUE(client_->Submit(Transaction::Read(0xFD00)).ok());
  RunFor(kMicrosPerSecond);
  EXPECT_EQ(observer_.completions.size(), kRequestQueueCapacity + 1);
  // Completions come in submission order, ids count up.
  for (std::size_t i = 0; i < kRequestQueueCapacity; ++i) EXPECT_EQ(observer_.completions[i].id, ids[i]);
  EXPECT_EQ(client_->counters().submitted, kRequestQueueCapacity + 1);
  EXPECT_EQ(client_->counters().completed, kRequestQueueCapacity + 1);
}

TEST_F(DriveLinkClientTest, StrayAndGarbledFrames_AreCountedAndIgnored) {
  Start();
  // A well-formed reply nobody asked for.
  inverter_.Inject({0x2F, 0x52, 0xFD, 0x00, 0x17, 0x70, 0x05}, clock_.NowMicros());
  RunFor(10 * kMicrosPerMilli);
  EXPECT_EQ(client_->counters().stray_frames, 1U);
  EXPECT_EQ(client_->state(), LinkState::kStarting);

  // While FD01 is asked for: a reply for FD00 (stray), a bad checksum (garbled), then the real reply.
  inverter_.reply_delay = 20 * kMicrosPerMilli;
  const RequestId id = Submit(Transaction::Read(0xFD01));
  client_->Poll(clock_.NowMicros());
  inverter_.Inject({0x2F, 0x52, 0xFD, 0x00, 0x17, 0x70, 0x05}, clock_.NowMicros() + kMicrosPerMilli);
  inverter_.Inject({0x2F, 0x52, 0xFD, 0x01, 0x40, 0x00, 0xBE}, clock_.NowMicros() + 2 * kMicrosPerMilli);
  inverter_.Inject({0x2F, 0x57, 0xFD, 0x01, 0x40, 0x00, 0xC4}, clock_.NowMicros() + 3 * kMicrosPerMilli);
  const Completion done = RunUntilComplete(id);
  EXPECT_EQ(done.outcome, Outcome::kOk);
  EXPECT_EQ(done.data, 0x4000);
  EXPECT_EQ(done.attempts, 1);
  EXPECT_EQ(client_->counters().stray_frames, 3U);  // FD00 reply, and a W echo answering an R
  EXPECT_EQ(client_->counters().garbled_frames, 1U);
}

TEST_F(DriveLinkClientTest, BlockReplyWithAnotherReadCount_IsStray) {
  Start();
  inverter_.block_reads = {0x4000, 0x1770, 0, 0, 0};
  inverter_.reply_delay = 20 * kMicrosPerMilli;
  const RequestId id = Submit(Transaction::Block({}, 2));
  client_->Poll(clock_.NowMicros());
  // A block reply with one read group, then the real one with two.
  inverter_.Inject({0x2F, 0x59, 0x01, 0x00, 0x40, 0x00, 0xC9}, clock_.NowMicros() + kMicrosPerMilli);
  const Completion done = RunUntilComplete(id);
  EXPECT_EQ(done.outcome, Outcome::kOk);
  EXPECT_EQ(done.block_read_count, 2);
  EXPECT_EQ(done.block_data[1], 0x1770);
  EXPECT_EQ(client_->counters().stray_frames, 1U);
  EXPECT_EQ(client_->counters().garbled_frames, 0U);
}

TEST_F(DriveLinkClientTest, PartialFrameWhileIdle_IsDroppedAfterTheFrameTimeout) {
  Start();
  const Micros at = clock_.NowMicros();
  inverter_.Inject({0x2F, 0x52, 0xFD}, at);
  client_->Poll(at);
  EXPECT_EQ(client_->NextDeadline(), at + 500 * kMicrosPerMilli);  // wire::kFrameTimeout
  RunFor(600 * kMicrosPerMilli);
  EXPECT_EQ(client_->framer_counters().dropped_frames, 1U);
  EXPECT_EQ(client_->NextDeadline(), hal::kNever);
  EXPECT_TRUE(RunUntilComplete(Submit(Transaction::Read(0xFD01))).ok());
}

TEST_F(DriveLinkClientTest, BabblingLine_IsReadInBoundedPasses) {
  Start();
  const Micros at = clock_.NowMicros();
  inverter_.Inject(Bytes(300, 0x00), at);
  client_->Poll(at);
  EXPECT_EQ(client_->framer_counters().garbage_bytes, 256U);  // 8 reads of 32 bytes per pass
  EXPECT_EQ(client_->NextDeadline(), at);                     // more is waiting: run again at once
  client_->Poll(at);
  EXPECT_EQ(client_->framer_counters().garbage_bytes, 300U);
  EXPECT_EQ(client_->NextDeadline(), hal::kNever);
}

TEST_F(DriveLinkClientTest, ProbesHeldByAQuietPeriod_ResumeOnTheirInterval) {
  LinkConfig config = TestConfig();
  config.fault_threshold = 1;
  config.max_retries = 0;
  Start(config);
  inverter_.silent = true;
  RunUntilComplete(Submit(Transaction::Read(0xFD01)));
  ASSERT_TRUE(client_->option_fault());
  const Micros fault_at = clock_.NowMicros();
  client_->QuietUntil(fault_at + 1700 * kMicrosPerMilli);
  RunUntil(fault_at + 2300 * kMicrosPerMilli);
  // The probes due at +500, +1000 and +1500 ms wait for the end of the quiet period; the next one comes
  // a whole interval later, not at once.
  ASSERT_EQ(inverter_.RequestCount(), 3U);
  EXPECT_EQ(inverter_.request_times[1], fault_at + 1700 * kMicrosPerMilli);
  EXPECT_EQ(inverter_.request_times[2], fault_at + 2200 * kMicrosPerMilli);
  EXPECT_EQ(client_->counters().silent_timeouts, 0U);
}

TEST_F(DriveLinkClientTest, ReplyFromAnotherInverterNumber_IsStray) {
  LinkConfig config = TestConfig();
  config.address = wire::InverterAddress::Number(1);
  config.max_retries = 0;
  Start(config);
  inverter_.own_number = 1;
  const RequestId id = Submit(Transaction::Read(0xFD01));
  client_->Poll(clock_.NowMicros());
  inverter_.Inject({0x2F, 0x02, 0x52, 0xFD, 0x01, 0x40, 0x00, 0xC1}, clock_.NowMicros());  // inverter 02
  inverter_.Inject({0x2F, 0x02, 0x4E, 0x00, 0x00, 0x7F}, clock_.NowMicros());              // its error reply
  inverter_.Inject({0x2F, 0x4E, 0x00, 0x00, 0x7D}, clock_.NowMicros());                    // no number
  EXPECT_TRUE(RunUntilComplete(id).ok());
  EXPECT_EQ(client_->counters().stray_frames, 3U);
}

TEST_F(DriveLinkClientTest, InvalidRequestsAndConfigurations_AreRefused) {
  client_.emplace(inverter_, TestConfig(), &observer_);
  EXPECT_EQ(client_->Submit(Transaction::Read(0xFD01)).status(), base::FailedPrecondition());
  ASSERT_TRUE(client_->Start(clock_.NowMicros()).ok());
  const std::uint16_t three[] = {1, 2, 3};
  EXPECT_EQ(client_->Submit(Transaction::Block(three, 0)).status(), base::InvalidArgument());
  EXPECT_EQ(client_->Submit(Transaction::Block({}, 6)).status(), base::InvalidArgument());
  EXPECT_EQ(client_->queued(), 0U);

  LinkConfig led = TestConfig();
  led.block_write_limit = wire::BlockWriteLimit::kLedDisplay;
  client_.emplace(inverter_, led, &observer_);
  ASSERT_TRUE(client_->Start(clock_.NowMicros()).ok());
  EXPECT_TRUE(client_->Submit(Transaction::Block(three, 0)).ok());

  LinkConfig ascii = TestConfig();
  ascii.mode = wire::Mode::kAscii;
  client_.emplace(inverter_, ascii, &observer_);
  ASSERT_TRUE(client_->Start(clock_.NowMicros()).ok());
  EXPECT_EQ(client_->Submit(Transaction::Block({}, 1)).status(), base::InvalidArgument());

  LinkConfig bad = TestConfig();
  bad.address = wire::InverterAddress::Broadcast();
  EXPECT_EQ(ValidateLinkConfig(bad), base::InvalidArgument());
  bad = TestConfig();
  bad.address = wire::InverterAddress::Number(64);  // binary carries 0-63
  EXPECT_EQ(ValidateLinkConfig(bad), base::InvalidArgument());
  bad.mode = wire::Mode::kAscii;
  EXPECT_TRUE(ValidateLinkConfig(bad).ok());
  bad = TestConfig();
  bad.serial.baud = 0;
  client_.emplace(inverter_, bad, &observer_);
  EXPECT_EQ(client_->Start(clock_.NowMicros()), base::InvalidArgument());
  bad = TestConfig();
  bad.fault_threshold = 0;
  EXPECT_EQ(ValidateLinkConfig(bad), base::InvalidArgument());
}

TEST_F(DriveLinkClientTest, ObserverMaySubmitFromItsCallback) {
  Start();
  int chained = 0;
  observer_.on_complete = [&](RequestId, const Completion&) {
    if (chained < 3) {
      ++chained;
      EXPECT_TRUE(client_->Submit(Transaction::Read(0xFD00)).ok());
    }
  };
  Submit(Transaction::Read(0xFD01));
  RunFor(kMicrosPerSecond);
  EXPECT_EQ(observer_.completions.size(), 4U);
  EXPECT_EQ(inverter_.RequestCount(), 4U);
  EXPECT_EQ(client_->NextDeadline(), hal::kNever);
}

TEST(DriveLinkNames, OutcomesAndStates) {
  EXPECT_STREQ(OutcomeName(Outcome::kNoReply), "no-reply");
  EXPECT_STREQ(LinkStateName(LinkState::kFault), "fault");
}

}  // namespace
}  // namespace drive_link
