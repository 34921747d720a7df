#include "placeholder_eds.h"

#include <array>
#include <cstddef>
#include <cstdint>

#include "cip/byte_span_file.h"

namespace firmware {
namespace {

template <std::size_t N>
constexpr std::array<std::uint8_t, N - 1> TextBytes(const char (&text)[N]) {
  std::array<std::uint8_t, N - 1> bytes{};
  for (std::size_t i = 0; i + 1 < N; ++i) bytes[i] = static_cast<std::uint8_t>(text[i]);
  return bytes;
}

constexpr auto kText = TextBytes(
    "$ IPE002Z EtherNet/IP option card for VF-MB1 / VF-S15.\r\n"
    "$ Placeholder: the EDS generated from the firmware's tables replaces this file (issue 19).\r\n"
    "[File]\r\n"
    "        DescText = \"IPE002Z placeholder EDS\";\r\n"
    "        CreateDate = 11-27-2026;\r\n"
    "        CreateTime = 00:00:00;\r\n"
    "        Revision = 0.1;\r\n");

// In flash: the bytes and the file over them are constants.
constinit const cip::ByteSpanFile kFile(kText);

}  // namespace

cip::ServedFile PlaceholderEds() { return {&kFile, "ipe002z-placeholder.eds", 0, 1}; }

}  // namespace firmware
