#include "net/bootp_client.h"

#include <algorithm>

namespace net {
namespace {

constexpr std::uint8_t kBootRequest = 1;
constexpr std::uint8_t kBootReply = 2;
constexpr std::uint8_t kHtypeEthernet = 1;
constexpr std::uint8_t kHlenEthernet = 6;

// Field offsets of RFC 951 §3.
constexpr std::size_t kXid = 4;
constexpr std::size_t kFlags = 10;
constexpr std::size_t kYiaddr = 16;
constexpr std::size_t kSiaddr = 20;
constexpr std::size_t kChaddr = 28;

}  // namespace

void EncodeBootRequest(const BootRequest& request, std::span<std::uint8_t, kBootpMessageSize> out) {
  std::fill(out.begin(), out.end(), std::uint8_t{0});  // hops, addresses, sname, file, padding
  // The fields up to chaddr fit the fixed part's 236 bytes: the writer cannot fail.
  base::ByteWriter fixed(out.first<kBootpFixedSize>());
  fixed.U8(kBootRequest);
  fixed.U8(kHtypeEthernet);
  fixed.U8(kHlenEthernet);
  fixed.Zeros(kXid - 3);  // hops
  fixed.U32Be(request.xid);
  fixed.U16Be(request.secs);
  fixed.U16Be(request.broadcast ? kBootpBroadcastFlag : std::uint16_t{0});
  fixed.Zeros(kChaddr - kFlags - 2);  // ciaddr, yiaddr, siaddr, giaddr
  request.mac.Write(fixed);
  // RFC 1497: the cookie says "options follow"; none are asked for, so only the end option.
  DhcpOptionWriter vendor(out.subspan<kBootpFixedSize, kBootpVendorSize>());
  vendor.Cookie();
  vendor.End();
  vendor.status().IgnoreError();  // 5 bytes into 64: cannot fail
}

bool IsUsableUnicast(base::Ipv4Address address) {
  const std::uint32_t first = address.octets()[0];
  return first != 0 && first != 127 && first < 224;
}

bool IsContiguousMask(base::Ipv4Address mask) {
  // Ones from the top, then zeros: the inverted mask plus one is a power of two.
  const std::uint32_t inverted = ~mask.HostOrder();
  return !mask.IsUnspecified() && (inverted & (inverted + 1)) == 0;
}

base::Result<BootReply> ParseBootReply(std::span<const std::uint8_t> payload, std::uint32_t xid,
                                       const base::MacAddress& mac) {
  if (payload.size() < kBootpFixedSize) return base::OutOfRange();
  // Every field read lies in the fixed part, which is there: the reader cannot fail.
  base::ByteReader fixed(payload.first(kBootpFixedSize));
  const std::uint8_t op = fixed.U8();
  const std::uint8_t htype = fixed.U8();
  const std::uint8_t hlen = fixed.U8();
  fixed.Skip(kXid - 3);  // hops
  const std::uint32_t reply_xid = fixed.U32Be();
  fixed.Skip(kYiaddr - kXid - 4);  // secs, flags, ciaddr
  BootReply reply;
  reply.your_address = base::Ipv4Address::Read(fixed);
  reply.server_address = base::Ipv4Address::Read(fixed);
  fixed.Skip(kChaddr - kSiaddr - 4);  // giaddr
  const base::MacAddress reply_mac = base::MacAddress::Read(fixed);
  if (op != kBootReply || htype != kHtypeEthernet || hlen != kHlenEthernet) return base::InvalidArgument();
  if (reply_xid != xid || reply_mac != mac) return base::NotFound();
  if (!IsUsableUnicast(reply.your_address)) return base::InvalidArgument();
  const base::Result<std::span<const std::uint8_t>> options = OptionsAfterCookie(payload.subspan(kBootpFixedSize));
  if (!options.ok()) return reply;  // no RFC 1497 vendor information: address only
  const base::Result<IpOptions> parsed = ParseIpOptions(options.value());
  if (!parsed.ok()) return parsed.status();
  if (parsed->subnet_mask && !IsContiguousMask(*parsed->subnet_mask)) return base::InvalidArgument();
  reply.subnet_mask = parsed->subnet_mask;
  reply.router = parsed->router;
  return reply;
}

void BootpClient::Start(hal::Micros now) {
  state_ = State::kRequesting;
  xid_ = random_.NextU32();
  started_ = now;
  deadline_ = now;
  transmissions_ = 0;
  lease_ = BootReply{};
}

void BootpClient::Stop() {
  state_ = State::kIdle;
  deadline_ = hal::kNever;
}

std::size_t BootpClient::Poll(hal::Micros now, std::span<std::uint8_t, kBootpMessageSize> out) {
  if (state_ != State::kRequesting || now < deadline_) return 0;
  const hal::Micros elapsed_s = (now - started_) / hal::kMicrosPerSecond;
  const BootRequest request{.mac = mac_,
                            .xid = xid_,
                            .secs = static_cast<std::uint16_t>(std::min<hal::Micros>(elapsed_s, 0xFFFF)),
                            .broadcast = true};
  EncodeBootRequest(request, out);
  deadline_ = now + RetransmitDelay();
  ++transmissions_;
  return kBootpMessageSize;
}

hal::Micros BootpClient::RetransmitDelay() {
  // 4 s doubled per transmission already made, capped at 64 s, +-1 s at random.
  const std::uint32_t doublings = std::min<std::uint32_t>(transmissions_, 4);
  const hal::Micros base = std::min(kBootpFirstRetransmit << doublings, kBootpMaxRetransmit);
  const hal::Micros spread = 2 * kBootpRetransmitJitter + 1;
  return base - kBootpRetransmitJitter + static_cast<hal::Micros>(random_.NextU32()) % spread;
}

base::Status BootpClient::OnReply(std::span<const std::uint8_t> payload) {
  if (state_ != State::kRequesting) return base::FailedPrecondition();
  const base::Result<BootReply> reply = ParseBootReply(payload, xid_, mac_);
  if (!reply.ok()) return reply.status();
  lease_ = reply.value();
  state_ = State::kBound;
  deadline_ = hal::kNever;
  return base::OkStatus();
}

}  // namespace net
