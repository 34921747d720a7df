#include "file_transfer.h"

#include "cip/byte_io.h"

namespace ipe {

std::vector<std::uint8_t> EncodeInitiateUpload(std::uint8_t max_transfer_size) { return {max_transfer_size}; }

std::vector<std::uint8_t> EncodeUploadTransfer(std::uint8_t transfer_number) { return {transfer_number}; }

std::optional<InitiateUploadReply> DecodeInitiateUploadReply(std::span<const std::uint8_t> data) {
  cip::ByteReader in(data);
  InitiateUploadReply reply;
  reply.file_size = in.U32();
  reply.transfer_size = in.U8();
  if (!in.ok() || !in.empty()) return std::nullopt;
  return reply;
}

std::optional<UploadTransferReply> DecodeUploadTransferReply(std::span<const std::uint8_t> data) {
  cip::ByteReader in(data);
  UploadTransferReply reply;
  reply.transfer_number = in.U8();
  const std::uint8_t type = in.U8();
  if (!in.ok() || type > static_cast<std::uint8_t>(TransferPacket::kFirstAndLast)) return std::nullopt;
  reply.type = static_cast<TransferPacket>(type);
  const bool last = reply.type == TransferPacket::kLast || reply.type == TransferPacket::kFirstAndLast;
  if (last && in.remaining() < 2) return std::nullopt;
  const std::span<const std::uint8_t> bytes = in.Bytes(in.remaining() - (last ? 2 : 0));
  reply.data.assign(bytes.begin(), bytes.end());
  if (last) reply.checksum = in.U16();
  if (!in.ok()) return std::nullopt;
  return reply;
}

std::uint16_t FileChecksum(std::span<const std::uint8_t> file) {
  std::uint16_t sum = 0;
  for (std::uint8_t byte : file) sum = static_cast<std::uint16_t>(sum + byte);
  return static_cast<std::uint16_t>(0x10000u - sum);
}

}  // namespace ipe
