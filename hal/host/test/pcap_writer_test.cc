#include "pcap_writer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <deque>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "capturing_frame_port.h"

namespace hal::host {
namespace {

using Bytes = std::vector<std::uint8_t>;
namespace fs = std::filesystem;

const Bytes kGlobalHeader = {
    0xD4, 0xC3, 0xB2, 0xA1,  // magic 0xa1b2c3d4: microsecond timestamps, little-endian file
    0x02, 0x00, 0x04, 0x00,  // version 2.4
    0x00, 0x00, 0x00, 0x00,  // thiszone
    0x00, 0x00, 0x00, 0x00,  // sigfigs
    0xFF, 0xFF, 0x00, 0x00,  // snaplen 65535
    0x01, 0x00, 0x00, 0x00,  // LINKTYPE_ETHERNET
};

// 2023-11-14T22:13:20.123456Z
constexpr Micros kStamp = 1700000000ULL * kMicrosPerSecond + 123456;

Bytes Frame(std::size_t size, std::uint8_t first) {
  Bytes frame(size);
  for (std::size_t i = 0; i < size; ++i) frame[i] = static_cast<std::uint8_t>(first + i);
  return frame;
}

Bytes RecordHeader(std::uint32_t sec, std::uint32_t usec, std::uint32_t captured, std::uint32_t original) {
  Bytes header;
  for (std::uint32_t value : {sec, usec, captured, original}) {
    for (int i = 0; i < 4; ++i) header.push_back(static_cast<std::uint8_t>(value >> (8 * i)));
  }
  return header;
}

Bytes Concat(std::initializer_list<Bytes> parts) {
  Bytes all;
  for (const Bytes& part : parts) all.insert(all.end(), part.begin(), part.end());
  return all;
}

class PcapWriterTest : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string pattern = (fs::temp_directory_path() / "ipe-pcap-test-XXXXXX").string();
    ASSERT_NE(mkdtemp(pattern.data()), nullptr);
    dir_ = pattern;
    path_ = (dir_ / "capture.pcap").string();
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::unique_ptr<PcapWriter> OpenWriter() {
    std::string error;
    base::Result<std::unique_ptr<PcapWriter>> writer = PcapWriter::Open(path_, &error);
    EXPECT_TRUE(writer.ok()) << error;
    return std::move(writer.value());
  }
  Bytes FileBytes() const {
    std::ifstream in(path_, std::ios::binary);
    return Bytes(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }

  fs::path dir_;
  std::string path_;
};

TEST_F(PcapWriterTest, StartsWithTheGlobalHeader) {
  std::unique_ptr<PcapWriter> writer = OpenWriter();
  EXPECT_EQ(FileBytes(), kGlobalHeader);
  EXPECT_EQ(writer->frames_written(), 0u);
}

TEST_F(PcapWriterTest, EachFrameIsOnDiskAsSoonAsWritten) {
  std::unique_ptr<PcapWriter> writer = OpenWriter();
  const Bytes first = Frame(60, 0x10);
  const Bytes second = Frame(14, 0xF0);
  ASSERT_EQ(writer->Write(first, kStamp), base::OkStatus());
  // Read while the writer is still open: nothing may be held back in a buffer.
  EXPECT_EQ(FileBytes(), Concat({kGlobalHeader, RecordHeader(1700000000, 123456, 60, 60), first}));
  EXPECT_EQ(FileBytes().size(), 24u + 16u + 60u);

  ASSERT_EQ(writer->Write(second, kStamp + kMicrosPerSecond - 123456), base::OkStatus());
  EXPECT_EQ(FileBytes(), Concat({kGlobalHeader, RecordHeader(1700000000, 123456, 60, 60), first,
                                 RecordHeader(1700000001, 0, 14, 14), second}));
  EXPECT_EQ(writer->frames_written(), 2u);
}

TEST_F(PcapWriterTest, RecordHeaderBytesAreLittleEndian) {
  std::unique_ptr<PcapWriter> writer = OpenWriter();
  ASSERT_EQ(writer->Write(Frame(60, 0), kStamp), base::OkStatus());
  const Bytes file = FileBytes();
  const Bytes header(file.begin() + 24, file.begin() + 40);
  EXPECT_EQ(header, (Bytes{0x00, 0xF1, 0x53, 0x65,    // ts_sec 1700000000
                           0x40, 0xE2, 0x01, 0x00,    // ts_usec 123456
                           0x3C, 0x00, 0x00, 0x00,    // captured 60
                           0x3C, 0x00, 0x00, 0x00}));  // original 60
}

TEST_F(PcapWriterTest, FramesLongerThanTheSnapLengthAreCut) {
  std::unique_ptr<PcapWriter> writer = OpenWriter();
  const Bytes huge = Frame(70000, 3);
  ASSERT_EQ(writer->Write(huge, kStamp), base::OkStatus());
  const Bytes file = FileBytes();
  ASSERT_EQ(file.size(), 24u + 16u + 65535u);
  EXPECT_EQ(Bytes(file.begin() + 24, file.begin() + 40), RecordHeader(1700000000, 123456, 65535, 70000));
  EXPECT_EQ(Bytes(file.begin() + 40, file.end()), Bytes(huge.begin(), huge.begin() + 65535));
}

TEST_F(PcapWriterTest, OpenTruncatesAnOldCapture) {
  OpenWriter()->Write(Frame(60, 0), kStamp).IgnoreError();
  std::unique_ptr<PcapWriter> writer = OpenWriter();
  EXPECT_EQ(FileBytes(), kGlobalHeader);
}

TEST_F(PcapWriterTest, OpenSaysWhyItFailed) {
  const std::string bad = (dir_ / "missing" / "capture.pcap").string();
  std::string error;
  EXPECT_EQ(PcapWriter::Open(bad, &error).status(), base::NotFound());
  EXPECT_NE(error.find(bad), std::string::npos) << error;
  EXPECT_NE(error.find("No such file or directory"), std::string::npos) << error;
}

TEST(WallClockTest, IsMicrosecondsSinceTheUnixEpoch) {
  const auto system_now = std::chrono::duration_cast<std::chrono::microseconds>(
                              std::chrono::system_clock::now().time_since_epoch())
                              .count();
  const Micros now = WallClockMicros();
  EXPECT_LT(now > static_cast<Micros>(system_now) ? now - static_cast<Micros>(system_now)
                                                  : static_cast<Micros>(system_now) - now,
            kMicrosPerSecond);
}

// A FramePort that hands out queued frames and accepts or refuses transmits as told.
class ScriptedFramePort final : public FramePort {
 public:
  base::MacAddress Mac() const override { return {0x00, 0x00, 0xA0, 0x12, 0x34, 0x56}; }
  std::size_t PortCount() const override { return 2; }
  LinkState Link(PortId port) const override {
    return port == PortId::kLeft ? LinkState{true, LinkSpeed::k100Mbps, true, true} : LinkState{};
  }
  PortCounters Counters(PortId port) const override {
    PortCounters counters;
    counters.rx_frames = PortIndex(port) + 41;
    return counters;
  }
  base::Result<ReceivedFrame> Receive(std::span<std::uint8_t> buffer) override {
    if (rx.empty()) return base::Unavailable();
    const Bytes frame = rx.front();
    rx.pop_front();
    if (frame.size() > buffer.size()) return base::OutOfRange();
    std::copy(frame.begin(), frame.end(), buffer.begin());
    return ReceivedFrame{frame.size(), PortId::kRight};
  }
  base::Status Transmit(PortId /*port*/, std::span<const std::uint8_t> frame) override {
    transmitted.emplace_back(frame.begin(), frame.end());
    return tx_status;
  }

  std::deque<Bytes> rx;
  std::vector<Bytes> transmitted;
  base::Status tx_status;
};

TEST_F(PcapWriterTest, CapturingPortRecordsFramesThatCrossTheWire) {
  std::unique_ptr<PcapWriter> writer = OpenWriter();
  ScriptedFramePort inner;
  Micros now = kStamp;
  CapturingFramePort port(inner, *writer, [&now] { return now; });

  const Bytes incoming = Frame(60, 0x20);
  const Bytes oversize = Frame(100, 0x30);
  const Bytes outgoing = Frame(42, 0x40);
  const Bytes refused = Frame(50, 0x50);
  inner.rx = {incoming, oversize};

  Bytes buffer(64, 0);
  const base::Result<ReceivedFrame> got = port.Receive(buffer);
  ASSERT_TRUE(got.ok());
  EXPECT_EQ(got->length, 60u);
  EXPECT_EQ(got->port, PortId::kRight);
  EXPECT_EQ(port.Receive(buffer).status(), base::OutOfRange());   // dropped: not captured
  EXPECT_EQ(port.Receive(buffer).status(), base::Unavailable());  // nothing: not captured

  now += 250;
  EXPECT_EQ(port.Transmit(PortId::kLeft, outgoing), base::OkStatus());
  inner.tx_status = base::FailedPrecondition();
  EXPECT_EQ(port.Transmit(PortId::kLeft, refused), base::FailedPrecondition());  // not captured
  EXPECT_EQ(inner.transmitted, (std::vector<Bytes>{outgoing, refused}));

  EXPECT_EQ(FileBytes(), Concat({kGlobalHeader, RecordHeader(1700000000, 123456, 60, 60), incoming,
                                 RecordHeader(1700000000, 123706, 42, 42), outgoing}));
  EXPECT_EQ(port.capture_errors(), 0u);
}

TEST_F(PcapWriterTest, CapturingPortForwardsTheRest) {
  std::unique_ptr<PcapWriter> writer = OpenWriter();
  ScriptedFramePort inner;
  CapturingFramePort port(inner, *writer);
  EXPECT_EQ(port.Mac(), inner.Mac());
  EXPECT_EQ(port.PortCount(), 2u);
  EXPECT_TRUE(port.Link(PortId::kLeft).up);
  EXPECT_FALSE(port.Link(PortId::kRight).up);
  EXPECT_EQ(port.Counters(PortId::kRight).rx_frames, 42u);
}

TEST_F(PcapWriterTest, CapturingPortStampsWithTheWallClockByDefault) {
  std::unique_ptr<PcapWriter> writer = OpenWriter();
  ScriptedFramePort inner;
  CapturingFramePort port(inner, *writer);
  const Micros before = WallClockMicros();
  ASSERT_EQ(port.Transmit(PortId::kLeft, Frame(60, 0)), base::OkStatus());
  const Micros after = WallClockMicros();

  const Bytes file = FileBytes();
  ASSERT_GE(file.size(), 40u);
  const auto le32 = [&file](std::size_t at) {
    return static_cast<Micros>(file[at]) | static_cast<Micros>(file[at + 1]) << 8 |
           static_cast<Micros>(file[at + 2]) << 16 | static_cast<Micros>(file[at + 3]) << 24;
  };
  const Micros stamp = le32(24) * kMicrosPerSecond + le32(28);
  EXPECT_GE(stamp, before);
  EXPECT_LE(stamp, after);
}

}  // namespace
}  // namespace hal::host
