// CIP File object (class 0x37) upload, client side (CIP Vol. 1 §5A-42; the EDS file instance 0xC8):
//
//   Initiate_Upload 0x4B     request: maximum transfer size (USINT)
//                            reply:   file size (UDINT), transfer size (USINT)
//   Upload_Transfer 0x4F     request: transfer number (USINT, 0 first, wrapping at 256)
//                            reply:   transfer number (USINT), packet type (USINT: 0 first, 1 middle,
//                                     2 last, 3 abort, 4 first and last), file data, and after the data of
//                                     a last (2 or 4) packet the checksum (UINT)
//   checksum: the two's complement of the 16-bit sum of every byte of the file.
// Pure encoders/decoders; nothing read past a span's end.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <span>
#include <vector>

namespace ipe {

inline constexpr std::uint16_t kClassFile = 0x37;
inline constexpr std::uint32_t kEdsFileInstance = 0xC8;
inline constexpr std::uint8_t kServiceInitiateUpload = 0x4B;
inline constexpr std::uint8_t kServiceUploadTransfer = 0x4F;

enum class TransferPacket : std::uint8_t { kFirst = 0, kMiddle = 1, kLast = 2, kAbort = 3, kFirstAndLast = 4 };

std::vector<std::uint8_t> EncodeInitiateUpload(std::uint8_t max_transfer_size);
std::vector<std::uint8_t> EncodeUploadTransfer(std::uint8_t transfer_number);

struct InitiateUploadReply {
  std::uint32_t file_size = 0;
  std::uint8_t transfer_size = 0;
};
// Exactly 5 bytes; nothing otherwise.
std::optional<InitiateUploadReply> DecodeInitiateUploadReply(std::span<const std::uint8_t> data);

struct UploadTransferReply {
  std::uint8_t transfer_number = 0;
  TransferPacket type = TransferPacket::kFirst;
  std::vector<std::uint8_t> data;
  std::optional<std::uint16_t> checksum;  // last packets only
};
// Nothing when shorter than its fixed fields, a packet type above 4, or a last packet without room for
// its checksum.
std::optional<UploadTransferReply> DecodeUploadTransferReply(std::span<const std::uint8_t> data);

std::uint16_t FileChecksum(std::span<const std::uint8_t> file);

// One request to the file instance: service and request data in, the reply (eip_codec.h's CipReply) out.
struct CipReply;
using FileRequest = std::function<CipReply(std::uint8_t service, std::span<const std::uint8_t> data)>;

// The whole upload: Initiate_Upload, then Upload_Transfer 0, 1, ... (wrapping at 256) until a last
// packet, checked against the announced size and the checksum. exit_code (failure.h) 0 with the file,
// 1 when the card refused or aborted (error names the status), 3 when a reply does not decode, the
// numbers do not follow, the size or the checksum is wrong, or the card sends more packets than the
// size allows.
struct UploadResult {
  int exit_code = 0;
  std::string error;
  std::vector<std::uint8_t> content;
};
UploadResult UploadFile(const FileRequest& request, std::uint8_t max_transfer_size);

}  // namespace ipe
