#include "cip/epath.h"

namespace cip {
namespace {

constexpr std::uint8_t kSegmentTypeMask = 0xE0;
constexpr std::uint8_t kPortSegment = 0x00;
constexpr std::uint8_t kLogicalSegment = 0x20;
constexpr std::uint8_t kPortExtendedLinkAddress = 0x10;
constexpr std::uint8_t kPortIdMask = 0x0F;
constexpr std::uint8_t kPortIdExtended = 0x0F;
constexpr std::uint8_t kSimpleDataSegment = 0x80;
constexpr std::uint8_t kAnsiSymbolSegment = 0x91;
constexpr std::uint8_t kElectronicKeyFormat = 4;

// Logical types (bits 4-2) and formats (bits 1-0).
enum LogicalType : std::uint8_t {
  kLogicalClass = 0,
  kLogicalInstance = 1,
  kLogicalMember = 2,
  kLogicalConnectionPoint = 3,
  kLogicalAttribute = 4,
  kLogicalSpecial = 5,
  kLogicalServiceId = 6,
};
enum LogicalFormat : std::uint8_t { k8Bit = 0, k16Bit = 1, k32Bit = 2 };

SegmentKind KindOf(std::uint8_t logical_type) {
  switch (logical_type) {
    case kLogicalClass:
      return SegmentKind::kClass;
    case kLogicalInstance:
      return SegmentKind::kInstance;
    case kLogicalMember:
      return SegmentKind::kMember;
    case kLogicalConnectionPoint:
      return SegmentKind::kConnectionPoint;
    default:
      return SegmentKind::kAttribute;
  }
}

}  // namespace

bool EpathReader::Fail(base::Status status) {
  status_ = status;
  return false;
}

bool EpathReader::Next(PathSegment& segment) {
  if (!status_.ok() || in_.empty()) return false;
  segment = PathSegment{};
  const std::uint8_t first = in_.U8();
  bool ok = false;
  if ((first & kSegmentTypeMask) == kPortSegment) {
    ok = ReadPort(first, segment);
  } else if ((first & kSegmentTypeMask) == kLogicalSegment) {
    ok = ReadLogical(first, segment);
  } else if (first == kSimpleDataSegment) {
    segment.kind = SegmentKind::kSimpleData;
    const std::uint8_t words = in_.U8();
    segment.bytes = in_.Bytes(2U * words);
    ok = true;
  } else if (first == kAnsiSymbolSegment) {
    segment.kind = SegmentKind::kSymbol;
    const std::uint8_t length = in_.U8();
    segment.bytes = in_.Bytes(length);
    if (length % 2 != 0) in_.Skip(1);
    ok = true;
  } else {
    return Fail(base::InvalidArgument());
  }
  if (!ok) return false;
  if (!in_.ok()) return Fail(base::OutOfRange());
  return true;
}

bool EpathReader::ReadPort(std::uint8_t first, PathSegment& segment) {
  segment.kind = SegmentKind::kPort;
  std::size_t length = 1;
  std::size_t link_size = 1;
  if ((first & kPortExtendedLinkAddress) != 0) {
    link_size = in_.U8();
    ++length;
  }
  segment.value = first & kPortIdMask;
  if (segment.value == kPortIdExtended) {
    segment.value = in_.U16Le();
    length += 2;
  }
  segment.bytes = in_.Bytes(link_size);
  length += link_size;
  if (length % 2 != 0) in_.Skip(1);  // padded EPATH: every segment has an even length
  return true;
}

bool EpathReader::ReadLogical(std::uint8_t first, PathSegment& segment) {
  const std::uint8_t type = static_cast<std::uint8_t>((first >> 2) & 0x07);
  const std::uint8_t format = first & 0x03;
  if (type == kLogicalSpecial) {
    // Format 0 is the electronic key; the key format byte must say 4 (the only one defined).
    if (format != 0) return Fail(base::InvalidArgument());
    segment.kind = SegmentKind::kElectronicKey;
    const std::uint8_t key_format = in_.U8();
    segment.key.vendor_id = in_.U16Le();
    segment.key.device_type = in_.U16Le();
    segment.key.product_code = in_.U16Le();
    segment.key.major_revision = in_.U8();
    segment.key.minor_revision = in_.U8();
    if (in_.ok() && key_format != kElectronicKeyFormat) return Fail(base::InvalidArgument());
    return true;
  }
  if (type == kLogicalServiceId) {
    if (format != k8Bit) return Fail(base::InvalidArgument());
    segment.kind = SegmentKind::kServiceId;
    segment.value = in_.U8();
    return true;
  }
  if (type > kLogicalAttribute) return Fail(base::InvalidArgument());
  segment.kind = KindOf(type);
  switch (format) {
    case k8Bit:
      segment.value = in_.U8();
      return true;
    case k16Bit:
      in_.Skip(1);  // pad
      segment.value = in_.U16Le();
      return true;
    case k32Bit:
      // CIP defines the 32-bit format for instance, member and connection point only; for a class or an
      // attribute it is reserved (their IDs are 16-bit), so such a segment is refused like format 3.
      if (type == kLogicalClass || type == kLogicalAttribute) return Fail(base::InvalidArgument());
      in_.Skip(1);  // pad
      segment.value = in_.U32Le();
      return true;
    default:
      return Fail(base::InvalidArgument());
  }
}

base::Result<ApplicationPath> DecodeApplicationPath(std::span<const std::uint8_t> padded_path) {
  // Each segment must come after the ones before it in this order, at most once.
  enum Stage : std::uint8_t { kStart, kHaveClass, kHaveInstance, kHaveAttribute, kHaveMember };
  EpathReader reader(padded_path);
  ApplicationPath path;
  Stage stage = kStart;
  PathSegment segment;
  while (reader.Next(segment)) {
    if (segment.kind == SegmentKind::kClass && stage == kStart) {
      path.class_id = segment.value;
      stage = kHaveClass;
    } else if ((segment.kind == SegmentKind::kInstance || segment.kind == SegmentKind::kConnectionPoint) &&
               stage == kHaveClass) {
      path.instance = segment.value;
      stage = kHaveInstance;
    } else if (segment.kind == SegmentKind::kAttribute && stage == kHaveInstance) {
      path.attribute = segment.value;
      stage = kHaveAttribute;
    } else if (segment.kind == SegmentKind::kMember && (stage == kHaveInstance || stage == kHaveAttribute)) {
      path.member = segment.value;
      stage = kHaveMember;
    } else {
      return base::InvalidArgument();
    }
  }
  if (!reader.status().ok()) return reader.status();
  if (stage < kHaveInstance) return base::InvalidArgument();
  return path;
}

void EncodeLogicalSegment(SegmentKind kind, std::uint32_t value, base::ByteWriter& out) {
  std::uint8_t type = kLogicalClass;
  switch (kind) {
    case SegmentKind::kClass:
      type = kLogicalClass;
      break;
    case SegmentKind::kInstance:
      type = kLogicalInstance;
      break;
    case SegmentKind::kMember:
      type = kLogicalMember;
      break;
    case SegmentKind::kConnectionPoint:
      type = kLogicalConnectionPoint;
      break;
    default:
      type = kLogicalAttribute;
      break;
  }
  const std::uint8_t base = static_cast<std::uint8_t>(kLogicalSegment | type << 2);
  if (value <= 0xFF) {
    out.U8(base);
    out.U8(static_cast<std::uint8_t>(value));
  } else if (value <= 0xFFFF) {
    out.U8(base | k16Bit);
    out.U8(0);
    out.U16Le(static_cast<std::uint16_t>(value));
  } else {
    out.U8(base | k32Bit);
    out.U8(0);
    out.U32Le(value);
  }
}

void EncodePortSegment(std::uint16_t port, std::span<const std::uint8_t> link_address, base::ByteWriter& out) {
  const bool extended_link = link_address.size() != 1;
  const bool extended_port = port >= kPortIdExtended;
  std::uint8_t first = extended_port ? kPortIdExtended : static_cast<std::uint8_t>(port);
  if (extended_link) first |= kPortExtendedLinkAddress;
  std::size_t length = 1;
  out.U8(first);
  if (extended_link) {
    out.U8(static_cast<std::uint8_t>(link_address.size()));
    ++length;
  }
  if (extended_port) {
    out.U16Le(port);
    length += 2;
  }
  out.Bytes(link_address);
  length += link_address.size();
  if (length % 2 != 0) out.U8(0);
}

}  // namespace cip
