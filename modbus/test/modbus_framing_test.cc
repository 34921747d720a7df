// The MBAP framer (seed 000 §8.1): whole ADUs out of a TCP byte stream, partial ADUs across segments,
// several ADUs in one segment, bad headers, pipelined requests served one at a time.
#include <gtest/gtest.h>

#include "modbus/mbap.h"
#include "modbus_fakes.h"

namespace modbus {
namespace {

using test::Bytes;
using test::ServerHarness;

// FC 03 to unit 251 (the option board), register 0 (firmware version 0x0106).
const Bytes kReadVersion = {0x00, 0x01, 0x00, 0x00, 0x00, 0x06, 0xFB, 0x03, 0x00, 0x00, 0x00, 0x01};
const Bytes kVersionAnswer = {0x00, 0x01, 0x00, 0x00, 0x00, 0x05, 0xFB, 0x03, 0x02, 0x01, 0x06};
// The same with transaction id 0x1234, reading registers 1-2 (c500 = 0, c504 = 0).
const Bytes kReadProtocol = {0x12, 0x34, 0x00, 0x00, 0x00, 0x06, 0xFB, 0x03, 0x00, 0x01, 0x00, 0x02};
const Bytes kProtocolAnswer = {0x12, 0x34, 0x00, 0x00, 0x00, 0x07, 0xFB, 0x03, 0x04, 0x00, 0x00, 0x00, 0x00};

Bytes Concat(const Bytes& a, const Bytes& b) {
  Bytes out = a;
  out.insert(out.end(), b.begin(), b.end());
  return out;
}

TEST(ModbusFindFrame, FewerThanSixBytes_NeedMore) {
  const Bytes five(kReadVersion.begin(), kReadVersion.begin() + 5);
  EXPECT_EQ(FindFrame(five).check, FrameCheck::kNeedMore);
}

TEST(ModbusFindFrame, WholeAdu_CompleteWithHeaderFields) {
  const FrameResult frame = FindFrame(kReadProtocol);
  ASSERT_EQ(frame.check, FrameCheck::kComplete);
  EXPECT_EQ(frame.adu_length, 12u);
  EXPECT_EQ(frame.header.transaction_id, 0x1234);
  EXPECT_EQ(frame.header.length, 6);
  EXPECT_EQ(frame.header.unit_id, 0xFB);
}

TEST(ModbusFindFrame, AduFollowedByMore_OnlyTheFirst) {
  const FrameResult frame = FindFrame(Concat(kReadVersion, kReadProtocol));
  ASSERT_EQ(frame.check, FrameCheck::kComplete);
  EXPECT_EQ(frame.adu_length, 12u);
  EXPECT_EQ(frame.header.transaction_id, 0x0001);
}

TEST(ModbusFindFrame, EveryTruncation_NeedMore) {
  for (std::size_t n = 0; n < kReadVersion.size(); ++n) {
    const Bytes prefix(kReadVersion.begin(), kReadVersion.begin() + static_cast<std::ptrdiff_t>(n));
    EXPECT_EQ(FindFrame(prefix).check, FrameCheck::kNeedMore) << n;
  }
}

TEST(ModbusFindFrame, ProtocolIdNotZero_BadHeaderFromSixBytes) {
  const Bytes header = {0x00, 0x01, 0x00, 0x01, 0x00, 0x06};
  const FrameResult frame = FindFrame(header);
  EXPECT_EQ(frame.check, FrameCheck::kBadHeader);
  EXPECT_EQ(frame.fault, HeaderFault::kProtocolId);
}

TEST(ModbusFindFrame, LengthZeroOrOne_BadHeader) {
  EXPECT_EQ(FindFrame(Bytes{0, 1, 0, 0, 0, 0}).fault, HeaderFault::kLengthTooShort);
  EXPECT_EQ(FindFrame(Bytes{0, 1, 0, 0, 0, 1, 0x01}).fault, HeaderFault::kLengthTooShort);
}

TEST(ModbusFindFrame, LengthAbove254_BadHeader) {
  EXPECT_EQ(FindFrame(Bytes{0, 1, 0, 0, 0, 255}).fault, HeaderFault::kLengthTooLong);
  EXPECT_EQ(FindFrame(Bytes{0, 1, 0, 0, 0x01, 0x00}).fault, HeaderFault::kLengthTooLong);
}

TEST(ModbusFindFrame, Length254_LargestAdu260) {
  Bytes adu = {0, 1, 0, 0, 0, 254, 0x01};
  adu.resize(259, 0x00);
  EXPECT_EQ(FindFrame(adu).check, FrameCheck::kNeedMore);
  adu.push_back(0x00);
  const FrameResult frame = FindFrame(adu);
  ASSERT_EQ(frame.check, FrameCheck::kComplete);
  EXPECT_EQ(frame.adu_length, kMaxAduBytes);
}

TEST(ModbusFraming, OneByteAtATime_AnsweredAfterTheLastByte) {
  ServerHarness h;
  const ConnectionId id = h.Connect();
  for (std::size_t i = 0; i + 1 < kReadVersion.size(); ++i) {
    EXPECT_EQ(h.server.Receive(id, Bytes{kReadVersion[i]}, h.now), 1u);
    EXPECT_TRUE(h.server.PendingOutput(id).empty()) << i;
  }
  EXPECT_EQ(h.Exchange(id, Bytes{kReadVersion.back()}), kVersionAnswer);
  EXPECT_EQ(h.server.TakeReleasedInput(id), kReadVersion.size());
}

TEST(ModbusFraming, TwoAdusInOneSegment_TwoAnswersInOrder) {
  ServerHarness h;
  const ConnectionId id = h.Connect();
  EXPECT_EQ(h.Exchange(id, Concat(kReadVersion, kReadProtocol)), Concat(kVersionAnswer, kProtocolAnswer));
  EXPECT_EQ(h.server.counters().requests, 2u);
}

TEST(ModbusFraming, AduAndAHalfThenTheRest_BothAnswered) {
  ServerHarness h;
  const ConnectionId id = h.Connect();
  const Bytes stream = Concat(kReadVersion, kReadProtocol);
  const Bytes first(stream.begin(), stream.begin() + 18);
  const Bytes rest(stream.begin() + 18, stream.end());
  EXPECT_EQ(h.Exchange(id, first), kVersionAnswer);
  EXPECT_EQ(h.Exchange(id, rest), kProtocolAnswer);
}

TEST(ModbusFraming, BadProtocolIdAfterAGoodRequest_GoodOneAnsweredThenClose) {
  ServerHarness h;
  const ConnectionId id = h.Connect();
  const Bytes bad = {0x00, 0x02, 0x00, 0x01, 0x00, 0x06, 0xFB, 0x03, 0x00, 0x00, 0x00, 0x01};
  EXPECT_EQ(h.Exchange(id, Concat(kReadVersion, bad)), kVersionAnswer);
  EXPECT_TRUE(h.server.MustClose(id));
  // Everything was taken out of the window, the bad frame included.
  EXPECT_EQ(h.server.TakeReleasedInput(id), 24u);
  EXPECT_EQ(h.server.counters().framing_errors, 1u);
  // Later bytes are taken and dropped; nothing more is served.
  EXPECT_EQ(h.Exchange(id, kReadVersion), Bytes{});
  EXPECT_EQ(h.server.TakeReleasedInput(id), kReadVersion.size());
}

TEST(ModbusFraming, LengthOne_NoAnswerAndClose) {
  ServerHarness h;
  const ConnectionId id = h.Connect();
  EXPECT_EQ(h.Exchange(id, Bytes{0x00, 0x01, 0x00, 0x00, 0x00, 0x01, 0xFB}), Bytes{});
  EXPECT_TRUE(h.server.MustClose(id));
}

TEST(ModbusFraming, LengthAbove254_NoAnswerAndClose) {
  ServerHarness h;
  const ConnectionId id = h.Connect();
  EXPECT_EQ(h.Exchange(id, Bytes{0x00, 0x01, 0x00, 0x00, 0x01, 0x00}), Bytes{});
  EXPECT_TRUE(h.server.MustClose(id));
}

TEST(ModbusFraming, PipelinedDriveReads_OneAccessAtATimeAnswersInOrder) {
  ServerHarness h;
  h.drive.registers = {{0x0009, 100}, {0x0010, 200}};
  const ConnectionId id = h.Connect();
  const Bytes read_acc = {0x00, 0x0A, 0x00, 0x00, 0x00, 0x06, 0x01, 0x03, 0x00, 0x09, 0x00, 0x01};
  const Bytes read_dec = {0x00, 0x0B, 0x00, 0x00, 0x00, 0x06, 0x01, 0x03, 0x00, 0x10, 0x00, 0x01};
  h.server.Receive(id, Concat(read_acc, read_dec), h.now);
  // Only the first request is at the drive.
  EXPECT_EQ(h.drive.pending(), 1u);
  h.drive.Poll();
  EXPECT_EQ(h.TakeOutput(id), (Bytes{0x00, 0x0A, 0x00, 0x00, 0x00, 0x05, 0x01, 0x03, 0x02, 0x00, 0x64}));
  EXPECT_EQ(h.server.TakeReleasedInput(id), 12u);
  EXPECT_EQ(h.drive.pending(), 1u);
  h.drive.Poll();
  EXPECT_EQ(h.TakeOutput(id), (Bytes{0x00, 0x0B, 0x00, 0x00, 0x00, 0x05, 0x01, 0x03, 0x02, 0x00, 0xC8}));
  EXPECT_EQ(h.server.TakeReleasedInput(id), 12u);
}

TEST(ModbusFraming, AnswersNotTaken_ServingStopsAndResumes) {
  ServerHarness h;
  const ConnectionId id = h.Connect();
  // As many whole 12-byte requests as the receive buffer (536 bytes) holds: 44.
  const std::size_t requests = kReceiveBufferBytes / kReadVersion.size();
  ASSERT_EQ(requests, 44u);
  Bytes stream;
  for (std::size_t i = 0; i < requests; ++i) stream = Concat(stream, kReadVersion);
  EXPECT_EQ(h.server.Receive(id, stream, h.now), stream.size());
  // The answer buffer holds two largest answers (520 bytes); a request starts only while a largest
  // answer (260) still fits: 24 answers of 11 bytes, then the 25th request waits.
  EXPECT_EQ(h.server.PendingOutput(id).size(), 24u * kVersionAnswer.size());
  EXPECT_EQ(h.server.TakeReleasedInput(id), 24u * kReadVersion.size());
  std::size_t answers = 0;
  for (int round = 0; round < 10; ++round) answers += h.TakeOutput(id).size() / kVersionAnswer.size();
  EXPECT_EQ(answers, requests);
  EXPECT_EQ(h.server.TakeReleasedInput(id), (requests - 24) * kReadVersion.size());
}

TEST(ModbusFraming, ReceiveBufferFull_TakesOnlyWhatFits) {
  ServerHarness h;
  const ConnectionId id = h.Connect();
  Bytes stream;
  for (int i = 0; i < 400; ++i) stream = Concat(stream, kReadVersion);
  // The buffer takes kReceiveBufferBytes; 24 requests are answered (then the answer buffer has no
  // room for a largest answer) and their bytes freed, so the next call takes exactly that much more.
  EXPECT_EQ(h.server.Receive(id, stream, h.now), kReceiveBufferBytes);
  const Bytes rest(stream.begin() + kReceiveBufferBytes, stream.end());
  EXPECT_EQ(h.server.Receive(id, rest, h.now), 24u * kReadVersion.size());
}

}  // namespace
}  // namespace modbus
