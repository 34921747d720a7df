// tools/ipe: every decoder of what a card (or anything answering in its place) sends back, and the
// backup file parser, on arbitrary bytes. The first byte chooses the decoder.
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>

#include "backup_format.h"
#include "eip_codec.h"
#include "file_transfer.h"
#include "io_assembly.h"
#include "modbus_codec.h"
#include "values.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::span<const std::uint8_t> bytes(data + 1, size - 1);
  const std::string text(bytes.begin(), bytes.end());
  switch (data[0] % 10) {
    case 0: (void)ipe::DecodeSendRRDataReply(bytes); break;
    case 1: (void)ipe::DecodeListIdentityReply(bytes); break;
    case 2: (void)ipe::DecodeIdentityAttributes(bytes); break;
    case 3: (void)ipe::DecodeAnswer(bytes, 1, 0x03); (void)ipe::DecodeAnswer(bytes, 1, 0x06); break;
    case 4: (void)ipe::DecodeDeviceIdAnswer(bytes, 1); break;
    case 5: (void)ipe::DecodeInitiateUploadReply(bytes); (void)ipe::DecodeUploadTransferReply(bytes); break;
    case 6: (void)ipe::DecodeInputDatagram(bytes, 1); (void)ipe::DecodeAssembly71(bytes); break;
    case 7: (void)ipe::ParseBackup(text); break;
    case 8: {
      const std::optional<ipe::ParameterInfo> acc = ipe::FindParameter("acc", ipe::Model::kVfMb1);
      if (acc) (void)ipe::ParseValue(text, *acc);
      const std::optional<ipe::ParameterInfo> fa06 = ipe::FindParameter("fa06", ipe::Model::kVfMb1);
      if (fa06) (void)ipe::ParseValue(text, *fa06);
      break;
    }
    default: {
      std::uint32_t ms = 0;
      (void)ipe::ParseMillis(text, ms);
      break;
    }
  }
  return 0;
}
