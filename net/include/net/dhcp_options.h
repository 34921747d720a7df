// BOOTP vendor extensions and DHCP options (RFC 1497, RFC 2132; docs/network.md "BOOTP"): the
// options area that follows the magic cookie 63 82 53 63 in the BOOTP "vend" field and in every DHCP
// message. A bounded TLV walk: code 0 (pad) and 255 (end) are one byte, every other option is code,
// length, data; nothing is read past the area, and a length that runs past it makes the rest unusable.
//
// Not supported (documented limits, not errors): option overload (52: more options in "sname"/"file";
// such options are simply not seen), and RFC 3396 long options split over several instances (the first
// instance of a code is the one used).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>

#include "base/addresses.h"
#include "base/status.h"

namespace net {

inline constexpr std::array<std::uint8_t, 4> kMagicCookie = {0x63, 0x82, 0x53, 0x63};  // 99.130.83.99

enum class DhcpOptionCode : std::uint8_t {
  kPad = 0,
  kSubnetMask = 1,
  kRouter = 3,
  kDomainNameServer = 6,
  kHostName = 12,
  kDomainName = 15,
  kOverload = 52,
  kMessageType = 53,
  kClientIdentifier = 61,
  kEnd = 255,
};

struct DhcpOption {
  std::uint8_t code = 0;
  std::span<const std::uint8_t> data;  // inside the area that was read
};

// Reads the options of one area (the bytes after the cookie), in order, pads skipped.
class DhcpOptionReader {
 public:
  explicit DhcpOptionReader(std::span<const std::uint8_t> options) : rest_(options) {}

  // kOk: `option` is the next one. kNotFound: the end option or the end of the area was reached (a
  // missing end option is tolerated: the area's end ends the list). kDataLoss: an option's length byte
  // or data runs past the area; it and everything after it are unusable, and Next keeps answering
  // kDataLoss.
  base::Status Next(DhcpOption& option);

 private:
  std::span<const std::uint8_t> rest_;
  bool failed_ = false;
};

// The options after the magic cookie of a vendor area; kNotFound when the area is shorter than the
// cookie or starts with something else (an RFC 951 vendor area in another format: no options for us).
base::Result<std::span<const std::uint8_t>> OptionsAfterCookie(std::span<const std::uint8_t> vendor_area);

// What the card takes from a BOOTP or DHCP reply. The first instance of each option counts.
struct IpOptions {
  std::optional<base::Ipv4Address> subnet_mask;  // option 1
  std::optional<base::Ipv4Address> router;       // option 3: the first router listed
};

// One pass over `options` (after the cookie). kDataLoss: truncated (see DhcpOptionReader).
// kInvalidArgument: option 1 not exactly 4 bytes, option 3 empty or not a multiple of 4; a reply that
// gets these wrong is not trusted for the rest either. Other options are skipped by their length.
base::Result<IpOptions> ParseIpOptions(std::span<const std::uint8_t> options);

// Writes options into a fixed buffer. Errors stick: a write that does not fit sets kResourceExhausted,
// writes nothing more, and status() reports it once at the end.
class DhcpOptionWriter {
 public:
  explicit DhcpOptionWriter(std::span<std::uint8_t> out) : out_(out) {}

  void Cookie();
  void Option(DhcpOptionCode code, std::span<const std::uint8_t> data);  // data at most 255 bytes
  void End();

  std::size_t size() const { return used_; }
  base::Status status() const { return status_; }

 private:
  bool Reserve(std::size_t bytes);

  std::span<std::uint8_t> out_;
  std::size_t used_ = 0;
  base::Status status_;
};

}  // namespace net
