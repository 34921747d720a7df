// eds: the card's EDS through the CIP File object (class 0x37, instance 0xC8).
#include <cstdio>
#include <fstream>

#include "commands.h"
#include "failure.h"
#include "file_transfer.h"

namespace ipe {

int RunEds(const Options& options) {
  const std::string& file = options.args[1];
  EipSession session(options.args[0], DefaultPort(options), static_cast<int>(options.timeout_ms));
  const CipPath eds{kClassFile, kEdsFileInstance, std::nullopt};
  const CipReply initiate = session.Request(kServiceInitiateUpload, eds, EncodeInitiateUpload(255));
  if (!initiate.ok()) Fail(kExitRefused, "eds: Initiate_Upload refused by the card: " + FormatCipStatus(initiate));
  const std::optional<InitiateUploadReply> size = DecodeInitiateUploadReply(initiate.data);
  if (!size || size->transfer_size == 0) Fail(kExitUnreachable, "eds: the Initiate_Upload reply does not decode");

  std::vector<std::uint8_t> content;
  const std::size_t most_packets = size->file_size / size->transfer_size + 2;
  std::uint8_t number = 0;
  for (std::size_t packet = 0;; ++packet, ++number) {
    if (packet >= most_packets) Fail(kExitUnreachable, "eds: the card sent more packets than the file size allows");
    const CipReply reply = session.Request(kServiceUploadTransfer, eds, EncodeUploadTransfer(number));
    if (!reply.ok()) Fail(kExitRefused, "eds: Upload_Transfer refused by the card: " + FormatCipStatus(reply));
    const std::optional<UploadTransferReply> transfer = DecodeUploadTransferReply(reply.data);
    if (!transfer || transfer->transfer_number != number) {
      Fail(kExitUnreachable, "eds: Upload_Transfer reply " + std::to_string(number) + " does not decode");
    }
    if (transfer->type == TransferPacket::kAbort) Fail(kExitRefused, "eds: the card aborted the transfer");
    content.insert(content.end(), transfer->data.begin(), transfer->data.end());
    if (content.size() > size->file_size) Fail(kExitUnreachable, "eds: more data than the announced file size");
    if (transfer->checksum) {
      if (content.size() != size->file_size) {
        Fail(kExitUnreachable, "eds: " + std::to_string(content.size()) + " bytes received, " +
                                   std::to_string(size->file_size) + " announced");
      }
      if (*transfer->checksum != FileChecksum(content)) Fail(kExitUnreachable, "eds: checksum mismatch");
      break;
    }
  }
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(content.data()), static_cast<std::streamsize>(content.size()));
  out.close();
  if (!out) Fail(kExitUsage, "eds: cannot write " + file);
  std::fprintf(stderr, "eds: %zu bytes saved to %s (checksum ok)\n", content.size(), file.c_str());
  return kExitOk;
}

}  // namespace ipe
