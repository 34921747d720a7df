#include "cip/byte_span_file.h"

#include <algorithm>

namespace cip {

std::size_t ByteSpanFile::ReadAt(std::uint32_t offset, std::span<std::uint8_t> out) const {
  if (offset >= bytes_.size()) return 0;
  const std::size_t count = std::min<std::size_t>(out.size(), bytes_.size() - offset);
  std::copy_n(bytes_.begin() + offset, count, out.begin());
  return count;
}

}  // namespace cip
