#include "base/crc32.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <span>
#include <string_view>

namespace {

std::span<const std::uint8_t> BytesOf(std::string_view text) {
  return {reinterpret_cast<const std::uint8_t*>(text.data()), text.size()};
}

TEST(Crc32, CheckValueAndEmptyInput) {
  EXPECT_EQ(base::Crc32(BytesOf("123456789")), 0xCBF43926U);
  EXPECT_EQ(base::Crc32({}), 0x00000000U);
}

TEST(Crc32, BuilderOverPiecesEqualsTheWhole) {
  const std::span<const std::uint8_t> all = BytesOf("123456789");
  for (std::size_t split = 0; split <= all.size(); ++split) {
    base::Crc32Builder crc;
    crc.Add(all.first(split));
    crc.Add(all.subspan(split));
    EXPECT_EQ(crc.value(), 0xCBF43926U) << "split at " << split;
  }
  EXPECT_EQ(base::Crc32Builder().value(), 0x00000000U);
}

}  // namespace
