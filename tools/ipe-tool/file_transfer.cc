#include "file_transfer.h"

#include "base/byte_reader.h"
#include "base/byte_writer.h"
#include "eip_codec.h"
#include "failure.h"

namespace ipe {

std::vector<std::uint8_t> EncodeInitiateUpload(std::uint8_t max_transfer_size) { return {max_transfer_size}; }

std::vector<std::uint8_t> EncodeUploadTransfer(std::uint8_t transfer_number) { return {transfer_number}; }

std::optional<InitiateUploadReply> DecodeInitiateUploadReply(std::span<const std::uint8_t> data) {
  base::ByteReader in(data);
  InitiateUploadReply reply;
  reply.file_size = in.U32Le();
  reply.transfer_size = in.U8();
  if (!in.ok() || !in.empty()) return std::nullopt;
  return reply;
}

std::optional<UploadTransferReply> DecodeUploadTransferReply(std::span<const std::uint8_t> data) {
  base::ByteReader in(data);
  UploadTransferReply reply;
  reply.transfer_number = in.U8();
  const std::uint8_t type = in.U8();
  if (!in.ok() || type > static_cast<std::uint8_t>(TransferPacket::kFirstAndLast)) return std::nullopt;
  reply.type = static_cast<TransferPacket>(type);
  const bool last = reply.type == TransferPacket::kLast || reply.type == TransferPacket::kFirstAndLast;
  if (last && in.remaining() < 2) return std::nullopt;
  const std::span<const std::uint8_t> bytes = in.Bytes(in.remaining() - (last ? 2 : 0));
  reply.data.assign(bytes.begin(), bytes.end());
  if (last) reply.checksum = in.U16Le();
  if (!in.ok()) return std::nullopt;
  return reply;
}

std::uint16_t FileChecksum(std::span<const std::uint8_t> file) {
  std::uint16_t sum = 0;
  for (std::uint8_t byte : file) sum = static_cast<std::uint16_t>(sum + byte);
  return static_cast<std::uint16_t>(0x10000u - sum);
}

UploadResult UploadFile(const FileRequest& request, std::uint8_t max_transfer_size) {
  UploadResult result;
  auto fail = [&result](int code, std::string error) {
    result.exit_code = code;
    result.error = std::move(error);
    result.content.clear();
    return result;
  };
  const CipReply initiate = request(kServiceInitiateUpload, EncodeInitiateUpload(max_transfer_size));
  if (!initiate.ok()) return fail(kExitRefused, "Initiate_Upload refused by the card: " + FormatCipStatus(initiate));
  const std::optional<InitiateUploadReply> size = DecodeInitiateUploadReply(initiate.data);
  if (!size || size->transfer_size == 0) return fail(kExitUnreachable, "the Initiate_Upload reply does not decode");

  const std::size_t most_packets = size->file_size / size->transfer_size + 1;
  std::uint8_t number = 0;
  for (std::size_t packet = 0;; ++packet, ++number) {
    if (packet >= most_packets) return fail(kExitUnreachable, "more packets than the announced file size allows");
    const CipReply reply = request(kServiceUploadTransfer, EncodeUploadTransfer(number));
    if (!reply.ok()) return fail(kExitRefused, "Upload_Transfer refused by the card: " + FormatCipStatus(reply));
    const std::optional<UploadTransferReply> transfer = DecodeUploadTransferReply(reply.data);
    if (!transfer) return fail(kExitUnreachable, "Upload_Transfer reply " + std::to_string(number) + " does not decode");
    if (transfer->transfer_number != number) {
      return fail(kExitUnreachable, "Upload_Transfer " + std::to_string(number) + " answered as " +
                                        std::to_string(transfer->transfer_number));
    }
    if (transfer->type == TransferPacket::kAbort) return fail(kExitRefused, "the card aborted the transfer");
    result.content.insert(result.content.end(), transfer->data.begin(), transfer->data.end());
    if (result.content.size() > size->file_size) return fail(kExitUnreachable, "more data than the announced file size");
    if (!transfer->checksum) continue;
    if (result.content.size() != size->file_size) {
      return fail(kExitUnreachable, std::to_string(result.content.size()) + " bytes received, " +
                                        std::to_string(size->file_size) + " announced");
    }
    if (*transfer->checksum != FileChecksum(result.content)) return fail(kExitUnreachable, "checksum mismatch");
    return result;
  }
}

}  // namespace ipe
