// Encapsulation wire format: the 24-byte header, the discovery reply bodies, the Common Packet Format
// items and the TCP stream reassembler.
#include <gtest/gtest.h>

#include <array>
#include <cstdint>

#include "cip/cpf.h"
#include "cip/encapsulation.h"
#include "cip/tcp_message_assembler.h"
#include "cip_test_support.h"

namespace cip {
namespace {

using test::Bytes;
using test::Hex;
using test::Of;

TEST(CipEncapsulationHeader, DecodesEveryFieldLittleEndian) {
  const Bytes bytes = Hex("6F 00 10 00 | 44 33 22 11 | 01 00 00 00 | 01 02 03 04 05 06 07 08 | 00 00 00 80 | AA");
  const base::Result<EncapsulationHeader> header = DecodeEncapsulationHeader(bytes);
  ASSERT_TRUE(header.ok());
  EXPECT_EQ(header->command, 0x006F);
  EXPECT_EQ(header->length, 0x0010);
  EXPECT_EQ(header->session_handle, 0x11223344U);
  EXPECT_EQ(header->status, 1U);
  EXPECT_EQ(header->sender_context, (std::array<std::uint8_t, 8>{1, 2, 3, 4, 5, 6, 7, 8}));
  EXPECT_EQ(header->options, 0x80000000U);
}

TEST(CipEncapsulationHeader, EveryTruncationIsRefused) {
  const Bytes bytes = Hex("65 00 04 00 00 00 00 00 00 00 00 00 01 02 03 04 05 06 07 08 00 00 00 00");
  for (std::size_t size = 0; size < bytes.size(); ++size) {
    EXPECT_EQ(DecodeEncapsulationHeader(std::span(bytes).first(size)).status(), base::OutOfRange()) << size;
  }
}

TEST(CipEncapsulationHeader, EncodeIsTheInverseOfDecode) {
  EncapsulationHeader header;
  header.command = 0x0065;
  header.length = 4;
  header.session_handle = 0xDEADBEEF;
  header.status = 0x69;
  header.sender_context = {8, 7, 6, 5, 4, 3, 2, 1};
  header.options = 0;
  std::array<std::uint8_t, 24> buffer{};
  base::ByteWriter out(buffer);
  EncodeEncapsulationHeader(header, out);
  ASSERT_TRUE(out.ok());
  EXPECT_EQ(Of(out.written()), Hex("65 00 04 00 EF BE AD DE 69 00 00 00 08 07 06 05 04 03 02 01 00 00 00 00"));
  EXPECT_EQ(DecodeEncapsulationHeader(buffer).value(), header);
}

TEST(CipEncapsulationHeader, ReplyHeaderEchoesCommandSessionAndContext) {
  EncapsulationHeader request;
  request.command = 0x0004;
  request.length = 9;
  request.session_handle = 7;
  request.status = 5;
  request.sender_context = {1, 1, 1, 1, 2, 2, 2, 2};
  request.options = 3;
  const EncapsulationHeader reply = ReplyHeaderFor(request, EncapStatus::kInvalidLength);
  EXPECT_EQ(reply.command, 0x0004);
  EXPECT_EQ(reply.length, 0);
  EXPECT_EQ(reply.session_handle, 7U);
  EXPECT_EQ(reply.status, 0x65U);
  EXPECT_EQ(reply.sender_context, request.sender_context);
  EXPECT_EQ(reply.options, 0U);
}

IdentityItem SampleIdentity() {
  IdentityItem item;
  item.socket_address = SocketAddress{SocketAddress::kAfInet, 44818, 0x0A00020F};
  item.vendor_id = 377;
  item.device_type = 2;
  item.product_code = 32000;
  item.major_revision = 1;
  item.minor_revision = 8;
  item.status = 0x0030;
  item.serial_number = 0xF47D02C0;
  EXPECT_TRUE(item.product_name.Assign("VF-MB1"));
  item.state = 0xFF;
  return item;
}

TEST(CipDiscoveryReply, ListIdentityItemLayout) {
  std::array<std::uint8_t, 64> buffer{};
  base::ByteWriter out(buffer);
  EncodeListIdentityData(SampleIdentity(), out);
  ASSERT_TRUE(out.ok());
  EXPECT_EQ(Of(out.written()), Hex("01 00 | 0C 00 28 00 | 01 00 | 00 02 AF 12 0A 00 02 0F 00 00 00 00 00 00 00 00"
                                   "| 79 01 | 02 00 | 00 7D | 01 08 | 30 00 | C0 02 7D F4"
                                   "| 06 56 46 2D 4D 42 31 | FF"));
}

TEST(CipDiscoveryReply, ListServicesCommunicationsItem) {
  std::array<std::uint8_t, 32> buffer{};
  base::ByteWriter out(buffer);
  EncodeListServicesData(out);
  ASSERT_TRUE(out.ok());
  EXPECT_EQ(Of(out.written()), Hex("01 00 | 00 01 14 00 | 01 00 | 20 01 |"
                                   "43 6F 6D 6D 75 6E 69 63 61 74 69 6F 6E 73 00 00"));
}

TEST(CipDiscoveryReply, ListInterfacesHasNoItems) {
  std::array<std::uint8_t, 4> buffer{};
  base::ByteWriter out(buffer);
  EncodeListInterfacesData(out);
  EXPECT_EQ(Of(out.written()), Hex("00 00"));
}

TEST(CipCpf, DecodesItemsOfAnUnconnectedRequest) {
  const Bytes bytes = Hex("02 00 | 00 00 00 00 | B2 00 06 00 0E 03 20 01 24 01");
  const base::Result<CpfPacket> packet = DecodeCpf(bytes);
  ASSERT_TRUE(packet.ok());
  ASSERT_EQ(packet->count, 2U);
  EXPECT_EQ(packet->items[0].type, 0x0000);
  EXPECT_TRUE(packet->items[0].data.empty());
  EXPECT_EQ(packet->items[1].type, 0x00B2);
  EXPECT_EQ(Of(packet->items[1].data), Hex("0E 03 20 01 24 01"));
  const base::Result<UnconnectedMessage> message = ParseUnconnectedMessage(*packet);
  ASSERT_TRUE(message.ok());
  EXPECT_EQ(Of(message->request), Hex("0E 03 20 01 24 01"));
  EXPECT_FALSE(message->o_to_t.has_value());
  EXPECT_FALSE(message->t_to_o.has_value());
}

TEST(CipCpf, CountAndLengthsMustMatchTheBytes) {
  // Count says 3, two items present.
  EXPECT_EQ(DecodeCpf(Hex("03 00 00 00 00 00 B2 00 00 00")).status(), base::OutOfRange());
  // Item length runs past the end.
  EXPECT_EQ(DecodeCpf(Hex("02 00 00 00 00 00 B2 00 05 00 0E 03 20 01")).status(), base::OutOfRange());
  // A byte after the last item.
  EXPECT_EQ(DecodeCpf(Hex("02 00 00 00 00 00 B2 00 00 00 FF")).status(), base::InvalidArgument());
  // More items than any command carries.
  EXPECT_EQ(DecodeCpf(Hex("05 00")).status(), base::InvalidArgument());
  // No count at all.
  EXPECT_EQ(DecodeCpf(Hex("01")).status(), base::OutOfRange());
  // Zero items is a well-formed packet (the command decides whether it is acceptable).
  EXPECT_EQ(DecodeCpf(Hex("00 00")).value().count, 0U);
}

TEST(CipCpf, UnconnectedLayoutIsChecked) {
  auto parse = [](const Bytes& bytes) { return ParseUnconnectedMessage(DecodeCpf(bytes).value()).status(); };
  EXPECT_EQ(parse(Hex("01 00 00 00 00 00")), base::InvalidArgument());                          // one item
  EXPECT_EQ(parse(Hex("02 00 A1 00 04 00 01 00 00 00 B2 00 00 00")), base::InvalidArgument());  // address
  EXPECT_EQ(parse(Hex("02 00 00 00 01 00 00 B2 00 00 00")), base::InvalidArgument());  // null with data
  EXPECT_EQ(parse(Hex("02 00 00 00 00 00 B1 00 00 00")), base::InvalidArgument());     // connected data
  EXPECT_EQ(parse(Hex("03 00 00 00 00 00 B2 00 00 00 00 01 00 00")), base::InvalidArgument());  // 3rd item
}

TEST(CipCpf, SocketAddressItemsOfAForwardOpen) {
  const Bytes bytes = Hex("04 00 | 00 00 00 00 | B2 00 01 00 54"
                          "| 00 80 10 00 00 02 08 AE EF C0 01 00 00 00 00 00 00 00 00 00"
                          "| 01 80 10 00 00 02 08 AE 00 00 00 00 00 00 00 00 00 00 00 00");
  const base::Result<UnconnectedMessage> message = ParseUnconnectedMessage(DecodeCpf(bytes).value());
  ASSERT_TRUE(message.ok());
  ASSERT_TRUE(message->o_to_t.has_value());
  EXPECT_EQ(*message->o_to_t, (SocketAddress{2, 2222, 0xEFC00100}));
  ASSERT_TRUE(message->t_to_o.has_value());
  EXPECT_EQ(*message->t_to_o, (SocketAddress{2, 2222, 0}));

  // The same direction twice, and a socket address item of the wrong length.
  EXPECT_FALSE(ParseUnconnectedMessage(
                   DecodeCpf(Hex("04 00 00 00 00 00 B2 00 00 00"
                                 "00 80 10 00 00 02 08 AE 00 00 00 00 00 00 00 00 00 00 00 00"
                                 "00 80 10 00 00 02 08 AE 00 00 00 00 00 00 00 00 00 00 00 00"))
                       .value())
                   .ok());
  EXPECT_FALSE(ParseUnconnectedMessage(DecodeCpf(Hex("03 00 00 00 00 00 B2 00 00 00 01 80 02 00 00 02")).value())
                   .ok());
}

TEST(CipCpf, ConnectedLayoutIsChecked) {
  const Bytes packet = Hex("02 00 | A1 00 04 00 78 56 34 12 | B1 00 06 00 05 00 0E 03 20 01");
  const base::Result<ConnectedMessage> message = ParseConnectedMessage(DecodeCpf(packet).value());
  ASSERT_TRUE(message.ok());
  EXPECT_EQ(message->connection_id, 0x12345678U);
  EXPECT_EQ(message->sequence_count, 5);
  EXPECT_EQ(Of(message->request), Hex("0E 03 20 01"));

  auto parse = [](const Bytes& bytes) { return ParseConnectedMessage(DecodeCpf(bytes).value()).status(); };
  EXPECT_EQ(parse(Hex("02 00 A1 00 02 00 78 56 B1 00 02 00 05 00")), base::InvalidArgument());  // short ID
  EXPECT_EQ(parse(Hex("02 00 A1 00 04 00 78 56 34 12 B1 00 01 00 05")), base::InvalidArgument());  // no seq
  EXPECT_EQ(parse(Hex("02 00 00 00 00 00 B1 00 02 00 05 00")), base::InvalidArgument());  // null address
}

TEST(CipCpf, SendDataPrefixIsSkipped) {
  const base::Result<SendDataCommand> command =
      DecodeSendDataCommand(Hex("00 00 00 00 | 0A 00 | 02 00 00 00 00 00 B2 00 00 00"));
  ASSERT_TRUE(command.ok());
  EXPECT_EQ(command->timeout, 10);
  EXPECT_EQ(command->packet.count, 2U);
  EXPECT_EQ(DecodeSendDataCommand(Hex("00 00 00 00 0A")).status(), base::OutOfRange());
}

TEST(CipCpf, ItemEncoding) {
  std::array<std::uint8_t, 32> buffer{};
  base::ByteWriter out(buffer);
  const std::size_t at = BeginCpfItem(out, CpfItemType::kUnconnectedData);
  out.U16Le(0x038E);
  FinishCpfItem(out, at);
  EncodeSockaddrItem(out, CpfItemType::kSockaddrTtoO, SocketAddress{2, 2222, 0xEFC00120});
  ASSERT_TRUE(out.ok());
  EXPECT_EQ(Of(out.written()), Hex("B2 00 02 00 8E 03 | 01 80 10 00 00 02 08 AE EF C0 01 20 00 00 00 00 00 00 00 00"));
}

// --- TCP stream reassembly -------------------------------------------------------------------------

const Bytes kNopWithData = Hex("00 00 02 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 AB CD");
const Bytes kListServices = Hex("04 00 00 00 00 00 00 00 00 00 00 00 11 11 11 11 11 11 11 11 00 00 00 00");

TEST(CipTcpMessageAssembler, OneByteAtATime) {
  TcpMessageAssembler assembler;
  for (std::size_t i = 0; i + 1 < kNopWithData.size(); ++i) {
    const TcpMessageAssembler::PushResult result = assembler.Push(std::span(kNopWithData).subspan(i, 1));
    EXPECT_EQ(result.consumed, 1U);
    EXPECT_FALSE(result.message_ready) << i;
  }
  const TcpMessageAssembler::PushResult last = assembler.Push(std::span(kNopWithData).last(1));
  EXPECT_TRUE(last.message_ready);
  EXPECT_EQ(assembler.header().length, 2);
  EXPECT_EQ(Of(assembler.body()), Hex("AB CD"));
  EXPECT_FALSE(assembler.oversized());
}

TEST(CipTcpMessageAssembler, BackToBackMessagesComeOutOneAtATime) {
  const Bytes stream = test::Concat(kNopWithData, kListServices);
  TcpMessageAssembler assembler;
  TcpMessageAssembler::PushResult result = assembler.Push(stream);
  EXPECT_EQ(result.consumed, kNopWithData.size());
  ASSERT_TRUE(result.message_ready);
  EXPECT_EQ(assembler.header().command, 0x0000);
  // While a message is waiting, nothing more is taken.
  EXPECT_EQ(assembler.Push(std::span(stream).subspan(result.consumed)).consumed, 0U);
  assembler.Next();
  result = assembler.Push(std::span(stream).subspan(kNopWithData.size()));
  EXPECT_EQ(result.consumed, kListServices.size());
  ASSERT_TRUE(result.message_ready);
  EXPECT_EQ(assembler.header().command, 0x0004);
  EXPECT_TRUE(assembler.body().empty());
}

TEST(CipTcpMessageAssembler, OversizedMessageIsCountedOffAndFlagged) {
  // Length 0x0259 = 601 bytes, one more than the buffer takes.
  Bytes stream = Hex("6F 00 59 02 01 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00");
  stream.resize(stream.size() + 601, 0xEE);
  stream.insert(stream.end(), kListServices.begin(), kListServices.end());
  TcpMessageAssembler assembler;
  TcpMessageAssembler::PushResult result = assembler.Push(std::span(stream).first(100));
  EXPECT_EQ(result.consumed, 100U);
  EXPECT_FALSE(result.message_ready);
  result = assembler.Push(std::span(stream).subspan(100));
  EXPECT_EQ(result.consumed, 24U + 601U - 100U);
  ASSERT_TRUE(result.message_ready);
  EXPECT_TRUE(assembler.oversized());
  EXPECT_EQ(assembler.header().command, 0x006F);
  EXPECT_TRUE(assembler.body().empty());
  assembler.Next();
  result = assembler.Push(std::span(stream).subspan(24 + 601));
  ASSERT_TRUE(result.message_ready);
  EXPECT_EQ(assembler.header().command, 0x0004);
  EXPECT_FALSE(assembler.oversized());
}

TEST(CipTcpMessageAssembler, LargestMessageFits) {
  Bytes stream = Hex("6F 00 58 02 01 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00");
  stream.resize(stream.size() + kMaxEncapsulationData, 0x5A);
  TcpMessageAssembler assembler;
  const TcpMessageAssembler::PushResult result = assembler.Push(stream);
  ASSERT_TRUE(result.message_ready);
  EXPECT_FALSE(assembler.oversized());
  EXPECT_EQ(assembler.body().size(), kMaxEncapsulationData);
}

}  // namespace
}  // namespace cip
