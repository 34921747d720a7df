// tools/ipe: the EtherNet/IP, Modbus, File object and class 1 bytes, exact, and cross-checked with the
// card's own decoders/encoders where the card has the other direction.
#include <gtest/gtest.h>

#include "cip/drive/assembly_codec.h"
#include "cip/encapsulation.h"
#include "eip_codec.h"
#include "file_transfer.h"
#include "io_assembly.h"
#include "modbus_codec.h"

namespace ipe {
namespace {

using B = std::vector<std::uint8_t>;

TEST(IpeEipCodec, ParameterAddresses) {
  EXPECT_EQ(ParameterAddressOf(0x0009).class_id, 0x64);  // acc -> 0x64 / 0x4009
  EXPECT_EQ(ParameterAddressOf(0x0009).instance, 0x4009u);
  EXPECT_EQ(ParameterAddressOf(0xFD00).instance, 0x7D00u);  // fd00 -> 0x64 / 0x7D00
  EXPECT_EQ(ParameterAddressOf(0xC101).class_id, 0x65);     // c101 -> 0x65 / 0xC101
  EXPECT_EQ(ParameterAddressOf(0xC101).instance, 0xC101u);
}

TEST(IpeEipCodec, GetAttributeSingleOfAccInsideSendRRData) {
  const B request = EncodeCipRequest(0x0E, {0x64, 0x4009, 3}, {});
  EXPECT_EQ(request, (B{0x0E, 0x04, 0x20, 0x64, 0x25, 0x00, 0x09, 0x40, 0x30, 0x03}));
  const B message = EncodeSendRRData(0x11223344, request);
  const B expected{0x6F, 0x00, 0x1A, 0x00, 0x44, 0x33, 0x22, 0x11, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0,
                   0, 0, 0, 0, 0, 0, 0x02, 0x00, 0x00, 0x00, 0x00, 0x00, 0xB2, 0x00, 0x0A, 0x00,
                   0x0E, 0x04, 0x20, 0x64, 0x25, 0x00, 0x09, 0x40, 0x30, 0x03};
  EXPECT_EQ(message, expected);
  EXPECT_EQ(EncodeRegisterSession(), (B{0x65, 0, 4, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0,
                                        1, 0, 0, 0}));
}

TEST(IpeEipCodec, ListIdentityAsksForAnAnswerWithin500Ms) {
  EXPECT_EQ(EncodeListIdentityRequest(),
            (B{0x63, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0xF4, 0x01, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0}));
}

TEST(IpeEipCodec, DecodesRepliesWithTheirStatus) {
  // SendRRData data: handle, timeout, 2 items: null address, unconnected data = reply 0x8E, status 0.
  const B ok{0, 0, 0, 0, 0, 0, 2, 0, 0, 0, 0, 0, 0xB2, 0, 6, 0, 0x8E, 0, 0, 0, 0x32, 0x00};
  const std::optional<CipReply> reply = DecodeSendRRDataReply(ok);
  ASSERT_TRUE(reply);
  EXPECT_TRUE(reply->ok());
  EXPECT_EQ(reply->data, (B{0x32, 0x00}));
  const B refused{0, 0, 0, 0, 0, 0, 2, 0, 0, 0, 0, 0, 0xB2, 0, 6, 0, 0xD4, 0, 0x01, 1, 0x06, 0x01};
  const std::optional<CipReply> open = DecodeSendRRDataReply(refused);
  ASSERT_TRUE(open);
  EXPECT_EQ(FormatCipStatus(*open), "general status 0x01 extended 0x0106 (connection failure)");
  const B not_settable{0, 0, 0, 0, 0, 0, 2, 0, 0, 0, 0, 0, 0xB2, 0, 4, 0, 0x90, 0, 0x0E, 0};
  EXPECT_EQ(FormatCipStatus(*DecodeSendRRDataReply(not_settable)), "general status 0x0E (attribute not settable)");
  const B truncated{0, 0, 0, 0, 0, 0, 2, 0, 0, 0, 0, 0, 0xB2, 0, 6, 0, 0x8E, 0};
  EXPECT_FALSE(DecodeSendRRDataReply(truncated));
}

TEST(IpeEipCodec, ListIdentityAsTheCardEncodesIt) {
  cip::IdentityItem item;
  item.socket_address = {2, 44818, 0x0A00020F};
  item.vendor_id = 377;
  item.device_type = 2;
  item.product_code = 32001;
  item.major_revision = 1;
  item.minor_revision = 8;
  item.status = 0x0030;
  item.serial_number = 0xF47D02C0;
  ASSERT_TRUE(item.product_name.Assign(std::string_view("VF-S15")));
  item.state = 0xFF;
  B buffer(128);
  base::ByteWriter out(buffer);
  cip::EncodeListIdentityData(item, out);
  const std::optional<cip::IdentityItem> decoded = DecodeListIdentityReply(out.written());
  ASSERT_TRUE(decoded);
  EXPECT_EQ(decoded->socket_address, item.socket_address);
  EXPECT_EQ(decoded->product_code, 32001);
  EXPECT_EQ(decoded->serial_number, 0xF47D02C0u);
  EXPECT_EQ(ProductNameOf(*decoded), "VF-S15");
  EXPECT_EQ(decoded->state, 0xFF);
  // Cut anywhere, it does not decode.
  for (std::size_t n = 0; n < out.size(); ++n) EXPECT_FALSE(DecodeListIdentityReply(out.written().first(n))) << n;
}

TEST(IpeModbusCodec, RequestsAndAnswers) {
  EXPECT_EQ(EncodeReadHoldingRegisters(7, 1, 0x0009, 1), (B{0, 7, 0, 0, 0, 6, 1, 0x03, 0x00, 0x09, 0x00, 0x01}));
  EXPECT_EQ(EncodeWriteSingleRegister(8, 1, 0x0009, 50), (B{0, 8, 0, 0, 0, 6, 1, 0x06, 0x00, 0x09, 0x00, 0x32}));
  EXPECT_EQ(EncodeReadDeviceId(9, 1), (B{0, 9, 0, 0, 0, 5, 1, 0x2B, 0x0E, 0x02, 0x00}));
  ModbusAnswer answer = DecodeAnswer(B{0, 7, 0, 0, 0, 5, 1, 0x03, 0x02, 0x00, 0x64}, 7, 0x03);
  EXPECT_TRUE(answer.valid);
  EXPECT_EQ(answer.values, (std::vector<std::uint16_t>{100}));
  answer = DecodeAnswer(B{0, 8, 0, 0, 0, 3, 1, 0x86, 0x02}, 8, 0x06);
  EXPECT_TRUE(answer.valid);
  EXPECT_EQ(answer.exception, 0x02);
  EXPECT_EQ(FormatModbusException(answer.exception), "Modbus exception 02 (illegal data address)");
  EXPECT_FALSE(DecodeAnswer(B{0, 7, 0, 0, 0, 5, 1, 0x03, 0x02, 0x00, 0x64}, 6, 0x03).valid);  // other transaction
  EXPECT_FALSE(DecodeAnswer(B{0, 7, 0, 0, 0, 5, 1, 0x03, 0x03, 0x00, 0x64}, 7, 0x03).valid);  // odd byte count
  const std::vector<DeviceIdObject> objects = DecodeDeviceIdAnswer(
      B{0, 9, 0, 0, 0, 0x14, 1, 0x2B, 0x0E, 0x02, 0x02, 0, 0, 2, 0x00, 0x02, 'T', 'O', 0x04, 0x06, 'V', 'F', '-', 'M',
        'B', '1'},
      9);
  ASSERT_EQ(objects.size(), 2u);
  EXPECT_EQ(objects[1].id, 0x04);
  EXPECT_EQ(objects[1].text, "VF-MB1");
}

TEST(IpeFileTransfer, InitiateAndTransferLayouts) {
  EXPECT_EQ(EncodeInitiateUpload(255), (B{0xFF}));
  EXPECT_EQ(EncodeUploadTransfer(3), (B{0x03}));
  const auto initiate = DecodeInitiateUploadReply(B{0x10, 0x27, 0x00, 0x00, 0xC8});
  ASSERT_TRUE(initiate);
  EXPECT_EQ(initiate->file_size, 10000u);
  EXPECT_EQ(initiate->transfer_size, 200);
  EXPECT_FALSE(DecodeInitiateUploadReply(B{0x10, 0x27, 0x00, 0x00}));
  EXPECT_FALSE(DecodeInitiateUploadReply(B{0x10, 0x27, 0x00, 0x00, 0xC8, 0x00}));

  const auto first = DecodeUploadTransferReply(B{0x00, 0x00, 'A', 'B'});
  ASSERT_TRUE(first);
  EXPECT_EQ(first->type, TransferPacket::kFirst);
  EXPECT_EQ(first->data, (B{'A', 'B'}));
  EXPECT_FALSE(first->checksum);
  const auto middle = DecodeUploadTransferReply(B{0x01, 0x01, 'C'});
  ASSERT_TRUE(middle);
  EXPECT_EQ(middle->transfer_number, 1);
  EXPECT_EQ(middle->type, TransferPacket::kMiddle);
  const auto last = DecodeUploadTransferReply(B{0x02, 0x02, 'D', 0x34, 0x12});
  ASSERT_TRUE(last);
  EXPECT_EQ(last->type, TransferPacket::kLast);
  EXPECT_EQ(last->data, (B{'D'}));
  EXPECT_EQ(last->checksum, 0x1234);
  const auto only = DecodeUploadTransferReply(B{0x00, 0x04, 'A', 'B', 'C', 0x3A, 0xFF});
  ASSERT_TRUE(only);
  EXPECT_EQ(only->type, TransferPacket::kFirstAndLast);
  EXPECT_EQ(only->checksum, FileChecksum(B{'A', 'B', 'C'}));
  EXPECT_FALSE(DecodeUploadTransferReply(B{0x00, 0x05, 'A'}));  // packet type 5 does not exist
  EXPECT_FALSE(DecodeUploadTransferReply(B{0x00, 0x02, 0x12}));  // a last packet without its checksum
  EXPECT_FALSE(DecodeUploadTransferReply(B{0x00}));
}

TEST(IpeFileTransfer, ChecksumIsTheTwosComplementOfTheByteSum) {
  EXPECT_EQ(FileChecksum(B{'A', 'B', 'C'}), 0xFF3A);  // 0x10000 - 198
  EXPECT_EQ(FileChecksum(B{}), 0x0000);
  EXPECT_EQ(FileChecksum(B(258, 0xFF)), static_cast<std::uint16_t>(0x10000 - (258 * 0xFF) % 0x10000));
}

TEST(IpeIoAssembly, Output21AsTheCardDecodesIt) {
  SpeedCommand command;
  command.run_forward = true;
  command.net_ctrl = true;
  command.net_ref = true;
  command.speed_rpm = 900;
  const std::array<std::uint8_t, 4> bytes = EncodeAssembly21(command);
  EXPECT_EQ(bytes, (std::array<std::uint8_t, 4>{0x61, 0x00, 0x84, 0x03}));
  cip::drive::DriveCommand decoded;
  ASSERT_TRUE(cip::drive::DecodeOutput(21, bytes, decoded));
  EXPECT_TRUE(decoded.run_forward);
  EXPECT_FALSE(decoded.run_reverse);
  EXPECT_TRUE(decoded.net_ctrl);
  EXPECT_TRUE(decoded.net_ref);
  EXPECT_EQ(decoded.speed_reference_rpm, 900);
}

TEST(IpeIoAssembly, Input71AsTheCardEncodesIt) {
  cip::drive::DriveFeedback feedback;
  feedback.state = cip::drive::SupervisorState::kEnabled;
  feedback.running_forward = true;
  feedback.ready = true;
  feedback.ctrl_from_net = true;
  feedback.ref_from_net = true;
  feedback.at_reference = true;
  feedback.speed_actual_rpm = 900;
  std::array<std::uint8_t, 4> bytes{};
  ASSERT_TRUE(cip::drive::EncodeInput(71, feedback, bytes));
  const std::optional<SpeedStatus> status = DecodeAssembly71(bytes);
  ASSERT_TRUE(status);
  EXPECT_TRUE(status->running_forward && status->ready && status->ctrl_from_net && status->ref_from_net &&
              status->at_reference);
  EXPECT_FALSE(status->faulted || status->warning || status->running_reverse);
  EXPECT_EQ(status->speed_rpm, 900);
  EXPECT_EQ(FormatSpeedStatus(*status, 3000),
            "running-fwd ready ctrl-from-net ref-from-net at-reference state=4 (enabled) speed=900 rpm (30.00 Hz)");
  EXPECT_FALSE(DecodeAssembly71(std::span<const std::uint8_t>(bytes).first(3)));
}

TEST(IpeIoAssembly, Datagrams) {
  const std::array<std::uint8_t, 4> assembly{0x61, 0x00, 0x84, 0x03};
  EXPECT_EQ(EncodeOutputDatagram(0x11223344, 5, 6, true, assembly),
            (B{0x02, 0x00, 0x02, 0x80, 0x08, 0x00, 0x44, 0x33, 0x22, 0x11, 0x05, 0x00, 0x00, 0x00, 0xB1, 0x00, 0x0A,
               0x00, 0x06, 0x00, 0x01, 0x00, 0x00, 0x00, 0x61, 0x00, 0x84, 0x03}));
  const B t_to_o{0x02, 0x00, 0x02, 0x80, 0x08, 0x00, 0x78, 0x56, 0x34, 0x12, 0x01, 0x00, 0x00, 0x00,
                 0xB1, 0x00, 0x06, 0x00, 0x01, 0x00, 0x54, 0x03, 0x84, 0x03};
  EXPECT_EQ(DecodeInputDatagram(t_to_o, 0x12345678), (B{0x54, 0x03, 0x84, 0x03}));
  EXPECT_FALSE(DecodeInputDatagram(t_to_o, 0x12345679));  // another connection's data
}

}  // namespace
}  // namespace ipe
