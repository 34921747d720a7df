// Padded EPATH decoding (CIP Vol. 1 Appendix C): the path of a message router request, the route path
// of Unconnected_Send, and (for the connection manager) connection paths.
//
// EpathReader walks segments one by one over a bounded span and never reads past it. Segment types it
// understands:
//   port        000E PPPP  [link size if E][16-bit port if PPPP = 15][link address][pad to even]
//   logical     001T TTFF  class 0, instance 1, member 2, connection point 3, attribute 4: 8-bit value,
//                          or a pad byte and a 16- or 32-bit value (FF = 0, 1, 2; 3 is reserved, and so
//                          is the 32-bit format of a class or an attribute);
//                          special 5 = electronic key (format 4, 8 bytes); service ID 6 (8-bit)
//   data        1000 0000  simple data: word count, words
//   symbolic    1001 0001  ANSI extended symbol: length, characters, pad to even
// Anything else (network segments, other data and symbolic forms, reserved types and formats) is an
// error: the reader stops and reports kInvalidArgument; a segment cut short by the end reports
// kOutOfRange. Both become general status 0x04 (path segment error) in a reply.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>

#include "base/status.h"
#include "base/byte_reader.h"
#include "base/byte_writer.h"

namespace cip {

enum class SegmentKind : std::uint8_t {
  kPort,
  kClass,
  kInstance,
  kMember,
  kConnectionPoint,
  kAttribute,
  kElectronicKey,
  kServiceId,
  kSimpleData,
  kSymbol,
};

struct ElectronicKey {
  std::uint16_t vendor_id = 0;
  std::uint16_t device_type = 0;
  std::uint16_t product_code = 0;
  std::uint8_t major_revision = 0;  // bit 7 is the compatibility bit
  std::uint8_t minor_revision = 0;
};

struct PathSegment {
  SegmentKind kind = SegmentKind::kClass;
  std::uint32_t value = 0;                     // logical value, or the port number of a port segment
  std::span<const std::uint8_t> bytes;         // link address, data words, or symbol characters
  ElectronicKey key;                           // kElectronicKey only
};

class EpathReader {
 public:
  explicit EpathReader(std::span<const std::uint8_t> padded_path) : in_(padded_path) {}

  // Decodes the next segment into `segment`. False at the end of the path or on an error; status()
  // tells which (ok at the end).
  bool Next(PathSegment& segment);
  base::Status status() const { return status_; }
  bool at_end() const { return status_.ok() && in_.empty(); }

 private:
  bool Fail(base::Status status);
  bool ReadPort(std::uint8_t first, PathSegment& segment);
  bool ReadLogical(std::uint8_t first, PathSegment& segment);

  base::ByteReader in_;
  base::Status status_;
};

// The path of a message router request: class, then instance (or connection point), then optionally
// an attribute and a member. A class and an instance are required; any other segment, order or repeat
// is kInvalidArgument.
struct ApplicationPath {
  std::uint32_t class_id = 0;
  std::uint32_t instance = 0;
  std::optional<std::uint32_t> attribute;
  std::optional<std::uint32_t> member;

  constexpr bool operator==(const ApplicationPath&) const = default;
};
base::Result<ApplicationPath> DecodeApplicationPath(std::span<const std::uint8_t> padded_path);

// Encoders for what the card itself sends (Port and TCP/IP object attributes, tests): logical segments
// in the smallest format that holds the value (class and attribute values must fit 16 bits: their 32-bit
// format is reserved), and a port segment.
void EncodeLogicalSegment(SegmentKind kind, std::uint32_t value, base::ByteWriter& out);
void EncodePortSegment(std::uint16_t port, std::span<const std::uint8_t> link_address, base::ByteWriter& out);

}  // namespace cip
