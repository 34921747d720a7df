#include "socket_serial_port.h"

#include <fcntl.h>
#include <poll.h>

#include <gtest/gtest.h>

#include <vector>

namespace hal::host {
namespace {

using Bytes = std::vector<std::uint8_t>;

class SocketSerialPortTest : public ::testing::Test {
 protected:
  void SetUp() override {
    base::Result<SocketSerialPort::Pair> pair = SocketSerialPort::CreatePair();
    ASSERT_TRUE(pair.ok());
    card_ = std::move(pair.value().card);
    inverter_ = std::move(pair.value().inverter);
    ASSERT_NE(card_, nullptr);
    ASSERT_NE(inverter_, nullptr);
  }

  // Everything readable on `port` right now.
  static Bytes ReadAll(SocketSerialPort& port) {
    Bytes all;
    std::uint8_t buffer[256];
    for (;;) {
      const base::Result<std::size_t> n = port.Read(buffer);
      if (!n.ok()) break;
      all.insert(all.end(), buffer, buffer + *n);
    }
    return all;
  }

  std::unique_ptr<SocketSerialPort> card_;
  std::unique_ptr<SocketSerialPort> inverter_;
};

TEST_F(SocketSerialPortTest, BothEndsAreNonBlocking) {
  EXPECT_NE(fcntl(card_->fd(), F_GETFL) & O_NONBLOCK, 0);
  EXPECT_NE(fcntl(inverter_->fd(), F_GETFL) & O_NONBLOCK, 0);
}

TEST_F(SocketSerialPortTest, NothingReceivedIsUnavailable) {
  std::uint8_t buffer[8];
  EXPECT_EQ(card_->Read(buffer).status(), base::Unavailable());
  EXPECT_EQ(inverter_->Read(buffer).status(), base::Unavailable());
}

TEST_F(SocketSerialPortTest, BytesCrossInBothDirections) {
  // A Toshiba inverter protocol read request and its answer, as opaque bytes.
  const Bytes request = {'(', 'R', 'F', 'D', '0', '0', ')'};
  const Bytes answer = {'(', 'R', 'F', 'D', '0', '0', '1', '7', '7', '0', ')'};
  ASSERT_EQ(card_->Write(request).value(), request.size());
  EXPECT_EQ(ReadAll(*inverter_), request);
  ASSERT_EQ(inverter_->Write(answer).value(), answer.size());
  EXPECT_EQ(ReadAll(*card_), answer);
}

TEST_F(SocketSerialPortTest, SmallBufferReadsTheRestNextTime) {
  const Bytes data = {1, 2, 3, 4, 5};
  ASSERT_EQ(inverter_->Write(data).value(), 5u);
  std::uint8_t buffer[3];
  ASSERT_EQ(card_->Read(buffer).value(), 3u);
  EXPECT_EQ(Bytes(buffer, buffer + 3), (Bytes{1, 2, 3}));
  ASSERT_EQ(card_->Read(buffer).value(), 2u);
  EXPECT_EQ(Bytes(buffer, buffer + 2), (Bytes{4, 5}));
  EXPECT_EQ(card_->Read(buffer).status(), base::Unavailable());
}

TEST_F(SocketSerialPortTest, FullTransmitBufferAcceptsFewerBytes) {
  const Bytes chunk(4096, 0x55);
  std::size_t accepted_total = 0;
  std::size_t accepted = chunk.size();
  int rounds = 0;
  while (accepted == chunk.size() && rounds++ < 100000) {
    accepted = card_->Write(chunk).value();
    accepted_total += accepted;
  }
  ASSERT_LT(accepted, chunk.size()) << "the socket buffer never filled";
  EXPECT_EQ(card_->Write(chunk).value(), 0u);
  // Once the far end drains, the card can send again and nothing was lost or duplicated.
  EXPECT_EQ(ReadAll(*inverter_).size(), accepted_total);
  EXPECT_EQ(card_->Write(chunk).value(), chunk.size());
}

TEST_F(SocketSerialPortTest, ConfigureRecordsTheLineSettings) {
  EXPECT_EQ(card_->config().baud, 19200u);  // the contract's defaults until configured
  const SerialConfig config{.baud = 9600, .parity = Parity::kNone, .stop_bits = 2};
  ASSERT_EQ(card_->Configure(config), base::OkStatus());
  EXPECT_EQ(card_->config().baud, 9600u);
  EXPECT_EQ(card_->config().parity, Parity::kNone);
  EXPECT_EQ(card_->config().stop_bits, 2);

  EXPECT_EQ(card_->Configure(SerialConfig{.baud = 0}), base::InvalidArgument());
  EXPECT_EQ(card_->Configure(SerialConfig{.baud = 19200, .stop_bits = 3}), base::InvalidArgument());
  EXPECT_EQ(card_->config().baud, 9600u);  // unchanged by the refused calls
}

TEST_F(SocketSerialPortTest, PollWatchesForInput) {
  PollSet set;
  Micros deadline = 5000;
  card_->PrepareWait(set, deadline);
  EXPECT_EQ(deadline, 5000u);
  ASSERT_EQ(set.size(), 1u);
  EXPECT_EQ(set.data()[0].fd, card_->fd());
  EXPECT_EQ(set.data()[0].events, POLLIN);

  EXPECT_EQ(poll(set.data(), set.size(), 0), 0);
  ASSERT_EQ(inverter_->Write(Bytes{0x42}).value(), 1u);
  EXPECT_EQ(poll(set.data(), set.size(), 1000), 1);
  EXPECT_NE(set.Revents(0) & POLLIN, 0);
  card_->AfterWait(set);
  EXPECT_EQ(ReadAll(*card_), Bytes{0x42});
}

TEST_F(SocketSerialPortTest, ClosedFarEndIsLikeAPulledCable) {
  ASSERT_EQ(inverter_->Write(Bytes{7, 8}).value(), 2u);
  inverter_.reset();

  // Bytes already on the line still arrive, then nothing.
  EXPECT_EQ(ReadAll(*card_), (Bytes{7, 8}));
  EXPECT_TRUE(card_->peer_closed());
  std::uint8_t buffer[4];
  EXPECT_EQ(card_->Read(buffer).status(), base::Unavailable());

  // Writes vanish without an error (and without SIGPIPE killing the test).
  EXPECT_EQ(card_->Write(Bytes{1, 2, 3}).value(), 3u);

  // The end-of-file descriptor is no longer watched, so the event loop does not spin on it.
  PollSet set;
  Micros deadline = kNever;
  card_->PrepareWait(set, deadline);
  EXPECT_EQ(set.size(), 0u);
}

TEST_F(SocketSerialPortTest, WriteToAClosedFarEndBeforeAnyReadIsAccepted) {
  inverter_.reset();
  EXPECT_EQ(card_->Write(Bytes{1, 2, 3}).value(), 3u);
  EXPECT_TRUE(card_->peer_closed());
}

}  // namespace
}  // namespace hal::host
