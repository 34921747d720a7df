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
  const UploadResult upload = UploadFile(
      [&session, &eds](std::uint8_t service, std::span<const std::uint8_t> data) {
        return session.Request(service, eds, data);
      },
      255);
  if (upload.exit_code != kExitOk) Fail(upload.exit_code, "eds: " + upload.error);
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(upload.content.data()), static_cast<std::streamsize>(upload.content.size()));
  out.close();
  if (!out) Fail(kExitUsage, "eds: cannot write " + file);
  std::fprintf(stderr, "eds: %zu bytes saved to %s (checksum ok)\n", upload.content.size(), file.c_str());
  return kExitOk;
}

}  // namespace ipe
