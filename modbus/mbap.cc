#include "modbus/mbap.h"

namespace modbus {

FrameResult FindFrame(std::span<const std::uint8_t> stream) {
  FrameResult result;
  // Protocol id and length are bytes 2-5: enough to judge the header.
  constexpr std::size_t kJudgeBytes = 6;
  if (stream.size() < kJudgeBytes) return result;
  base::ByteReader reader(stream);
  MbapHeader header;
  header.transaction_id = reader.U16Be();
  header.protocol_id = reader.U16Be();
  header.length = reader.U16Be();
  if (header.protocol_id != 0) {
    result.check = FrameCheck::kBadHeader;
    result.fault = HeaderFault::kProtocolId;
    return result;
  }
  if (header.length < kMinLengthField) {
    result.check = FrameCheck::kBadHeader;
    result.fault = HeaderFault::kLengthTooShort;
    return result;
  }
  if (header.length > kMaxLengthField) {
    result.check = FrameCheck::kBadHeader;
    result.fault = HeaderFault::kLengthTooLong;
    return result;
  }
  const std::size_t adu_length = kJudgeBytes + header.length;
  if (stream.size() < adu_length) return result;
  header.unit_id = reader.U8();
  result.check = FrameCheck::kComplete;
  result.adu_length = adu_length;
  result.header = header;
  return result;
}

void WriteMbapHeader(base::ByteWriter& writer, const MbapHeader& request, std::size_t answer_pdu_length) {
  writer.U16Be(request.transaction_id);
  writer.U16Be(0);
  writer.U16Be(static_cast<std::uint16_t>(answer_pdu_length + 1));
  writer.U8(request.unit_id);
}

}  // namespace modbus
