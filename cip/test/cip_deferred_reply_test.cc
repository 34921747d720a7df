// Deferred explicit replies through the real message router and encapsulation server: a handler that
// must wait for the drive link marks the request pending, nothing is answered, the server keeps the
// message, and the retry executes it again from the start (docs/ethernetip.md "Deferred replies").
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <vector>

#include "cip/encapsulation_server.h"
#include "cip/message_router.h"
#include "cip_test_support.h"

namespace cip {
namespace {

using test::Bytes;
using test::Hex;
using test::Of;

// Class 0x70 instance 1: Get_Attribute_Single of attribute N (1-3) answers N * 0x1111 once the test says
// the "drive access" for N is done; until then it asks to be deferred. It counts executions per attribute.
class SlowObject final : public RequestLifecycle {
 public:
  std::array<bool, 4> done{};
  std::array<int, 4> executions{};
  std::vector<std::uint32_t> started;
  std::vector<std::uint32_t> finished;
  bool ready = false;

  void Answer(RequestContext& context, std::uint16_t id, base::ByteWriter& out) {
    ++executions[id];
    if (!done[id]) {
      context.pending = true;
      return;
    }
    out.U16Le(static_cast<std::uint16_t>(0x1111 * id));
  }

  void OnRequestStarted(std::uint32_t requester) override { started.push_back(requester); }
  void OnRequestFinished(std::uint32_t requester) override { finished.push_back(requester); }
  bool ReadyToRetry(std::uint32_t) const override { return ready; }
};

// A CipObject wrapper that sends Get_Attribute_Single to SlowObject::Answer with the request's context.
class SlowCipObject final : public CipObject {
 public:
  explicit SlowCipObject(SlowObject& slow) : slow_(slow) {}
  std::uint16_t class_id() const override { return 0x70; }
  bool HasInstance(std::uint32_t instance) const override { return instance == 1; }
  bool SupportsService(std::uint32_t, std::uint8_t service) const override {
    return service == kServiceGetAttributeSingle;
  }
  ServiceStatus Execute(const ServiceRequest& request, base::ByteWriter& reply) override {
    if (!request.path.attribute || *request.path.attribute > 3) return Error(GeneralStatus::kAttributeNotSupported);
    slow_.Answer(*request.context, static_cast<std::uint16_t>(*request.path.attribute), reply);
    return Success();
  }

 private:
  SlowObject& slow_;
};

class NoDiscovery final : public DiscoverySource {
 public:
  IdentityItem ListIdentity() const override { return {}; }
};

const Bytes kContext = Hex("01 02 03 04 05 06 07 08");

Bytes Header(std::uint16_t command, std::uint16_t length, std::uint32_t session) {
  Bytes bytes = {static_cast<std::uint8_t>(command), static_cast<std::uint8_t>(command >> 8),
                 static_cast<std::uint8_t>(length), static_cast<std::uint8_t>(length >> 8)};
  for (int i = 0; i < 4; ++i) bytes.push_back(static_cast<std::uint8_t>(session >> (8 * i)));
  bytes.insert(bytes.end(), 4, 0);
  bytes.insert(bytes.end(), kContext.begin(), kContext.end());
  bytes.insert(bytes.end(), 4, 0);
  return bytes;
}

// SendRRData around a message router request.
Bytes SendRRData(std::uint32_t session, const Bytes& request) {
  const auto size = static_cast<std::uint16_t>(request.size());
  Bytes body = Hex("00 00 00 00 | 0A 00 | 02 00 | 00 00 00 00 | B2 00");
  body.push_back(static_cast<std::uint8_t>(size));
  body.push_back(static_cast<std::uint8_t>(size >> 8));
  body = test::Concat(body, request);
  return test::Concat(Header(0x6F, static_cast<std::uint16_t>(body.size()), session), body);
}

// The reply SendRRData wraps around a message router reply.
Bytes SendRRDataReply(std::uint32_t session, const Bytes& reply) {
  const auto size = static_cast<std::uint16_t>(reply.size());
  Bytes body = Hex("00 00 00 00 | 00 00 | 02 00 | 00 00 00 00 | B2 00");
  body.push_back(static_cast<std::uint8_t>(size));
  body.push_back(static_cast<std::uint8_t>(size >> 8));
  body = test::Concat(body, reply);
  return test::Concat(Header(0x6F, static_cast<std::uint16_t>(body.size()), session), body);
}

const Bytes kGet1 = Hex("0E 03 20 70 24 01 30 01");
const Bytes kGet2 = Hex("0E 03 20 70 24 01 30 02");

class CipDeferredReplyTest : public ::testing::Test {
 protected:
  CipDeferredReplyTest() {
    EXPECT_TRUE(registry_.Register(cip_object_).ok());
    server_.set_request_lifecycle(&slow_);
    id_ = server_.OpenTcpConnection(Ipv4Endpoint{base::Ipv4Address(0x0A000202), 50000}, now_).value();
    const TcpStep step = server_.OnTcpData(id_, test::Concat(Header(0x65, 4, 0), Hex("01 00 00 00")), now_);
    const Bytes reply = Of(step.reply);
    session_ = static_cast<std::uint32_t>(reply.at(4) | reply.at(5) << 8 | reply.at(6) << 16 | reply.at(7) << 24);
    slow_.started.clear();
    slow_.finished.clear();
  }

  hal::Micros now_ = 1'000'000;
  test::ScriptedRandom random_;
  SlowObject slow_;
  SlowCipObject cip_object_{slow_};
  ObjectRegistry registry_;
  MessageRouter router_{registry_};
  NoDiscovery discovery_;
  EncapsulationServer server_{router_, discovery_, random_};
  TcpConnectionId id_;
  std::uint32_t session_ = 0;
};

TEST_F(CipDeferredReplyTest, PendingRequestIsKeptAndAnsweredOnRetry) {
  const Bytes request = SendRRData(session_, kGet1);
  TcpStep step = server_.OnTcpData(id_, request, now_);
  EXPECT_TRUE(step.pending);
  EXPECT_EQ(step.consumed, request.size());
  EXPECT_TRUE(step.reply.empty());
  EXPECT_TRUE(server_.has_pending());
  EXPECT_EQ(slow_.started, (std::vector<std::uint32_t>{1}));  // requester = connection index + 1
  EXPECT_TRUE(slow_.finished.empty());

  // More input is not taken while the message waits.
  step = server_.OnTcpData(id_, request, now_);
  EXPECT_TRUE(step.pending);
  EXPECT_EQ(step.consumed, 0U);
  EXPECT_FALSE(server_.ReadyToRetry(id_));

  // A retry whose access has not completed defers again, without a reply.
  slow_.ready = true;
  ASSERT_TRUE(server_.ReadyToRetry(id_));
  step = server_.RetryTcp(id_, now_);
  EXPECT_TRUE(step.pending);
  EXPECT_TRUE(step.reply.empty());

  slow_.done[1] = true;
  step = server_.RetryTcp(id_, now_);
  EXPECT_FALSE(step.pending);
  EXPECT_EQ(step.consumed, 0U);
  EXPECT_EQ(Of(step.reply), SendRRDataReply(session_, Hex("8E 00 00 00 11 11")));
  EXPECT_EQ(slow_.executions[1], 3);
  EXPECT_EQ(slow_.started, (std::vector<std::uint32_t>{1, 1, 1}));
  EXPECT_EQ(slow_.finished, (std::vector<std::uint32_t>{1}));
  EXPECT_FALSE(server_.has_pending());
  EXPECT_FALSE(server_.ReadyToRetry(id_));

  // The stream carries on with the next message.
  step = server_.OnTcpData(id_, SendRRData(session_, kGet1), now_);
  EXPECT_FALSE(step.pending);
  EXPECT_EQ(Of(step.reply), SendRRDataReply(session_, Hex("8E 00 00 00 11 11")));
}

TEST_F(CipDeferredReplyTest, MultipleServicePacketIsRunAgainFromItsFirstMember) {
  slow_.done[1] = true;
  const Bytes msp = test::Concat(Hex("0A 02 20 02 24 01 | 02 00 06 00 0E 00"), test::Concat(kGet1, kGet2));
  TcpStep step = server_.OnTcpData(id_, SendRRData(session_, msp), now_);
  EXPECT_TRUE(step.pending);
  EXPECT_EQ(slow_.executions[1], 1);
  EXPECT_EQ(slow_.executions[2], 1);

  slow_.ready = true;
  slow_.done[2] = true;
  step = server_.RetryTcp(id_, now_);
  ASSERT_FALSE(step.pending);
  EXPECT_EQ(Of(step.reply),
            SendRRDataReply(session_, Hex("8A 00 00 00 | 02 00 06 00 0C 00 | 8E 00 00 00 11 11 | 8E 00 00 00 22 22")));
  EXPECT_EQ(slow_.executions[1], 2);  // the handler answers the repeat from its own record
  EXPECT_EQ(slow_.executions[2], 2);
}

TEST_F(CipDeferredReplyTest, UnconnectedSendCarriesTheDeferral) {
  // Unconnected_Send to the Connection Manager with an empty route... port 1 link 0 (this device).
  Bytes send = Hex("52 02 20 06 24 01 | 0A F0 | 08 00");
  send = test::Concat(send, kGet2);
  send = test::Concat(send, Hex("01 00 01 00"));
  TcpStep step = server_.OnTcpData(id_, SendRRData(session_, send), now_);
  EXPECT_TRUE(step.pending);
  slow_.ready = true;
  slow_.done[2] = true;
  step = server_.RetryTcp(id_, now_);
  ASSERT_FALSE(step.pending);
  EXPECT_EQ(Of(step.reply), SendRRDataReply(session_, Hex("8E 00 00 00 22 22")));
}

TEST_F(CipDeferredReplyTest, ClosingTheConnectionFinishesItsPendingRequest) {
  EXPECT_TRUE(server_.OnTcpData(id_, SendRRData(session_, kGet1), now_).pending);
  server_.CloseTcpConnection(id_);
  EXPECT_EQ(slow_.finished, (std::vector<std::uint32_t>{1}));
  EXPECT_FALSE(server_.has_pending());
  EXPECT_FALSE(server_.ReadyToRetry(id_));
  EXPECT_TRUE(server_.RetryTcp(id_, now_).close);
}

TEST_F(CipDeferredReplyTest, RequestsThatNeedNoAccessFinishAtOnce) {
  slow_.done[3] = true;
  const TcpStep step = server_.OnTcpData(id_, SendRRData(session_, Hex("0E 03 20 70 24 01 30 03")), now_);
  EXPECT_FALSE(step.pending);
  EXPECT_EQ(Of(step.reply), SendRRDataReply(session_, Hex("8E 00 00 00 33 33")));
  EXPECT_EQ(slow_.started, (std::vector<std::uint32_t>{1}));
  EXPECT_EQ(slow_.finished, (std::vector<std::uint32_t>{1}));
}

}  // namespace
}  // namespace cip
