// libFuzzer target for the BOOTP client and the BOOTP/DHCP options walk (net/bootp_client.h,
// net/dhcp_options.h). The input is a UDP payload received on port 68.
// Oracles: nothing is read outside the input (ASan); every option's data lies inside the area walked and
// the walk ends within as many steps as the area has bytes; an accepted reply has a usable unicast
// address and a contiguous mask; the client accepts exactly the replies ParseBootReply accepts (with the
// input's own xid and chaddr, so the deep checks are reached), binds on them and then sends nothing.
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "base/addresses.h"
#include "base/byte_reader.h"
#include "hal/random.h"
#include "net/bootp_client.h"
#include "net/dhcp_options.h"

namespace {

void Require(bool condition) {
  if (!condition) __builtin_trap();
}

// Hands out one fixed value: the client's xid becomes whatever the input carries.
class FixedRandom final : public hal::RandomSource {
 public:
  explicit FixedRandom(std::uint32_t value) : value_(value) {}
  void Fill(std::span<std::uint8_t> out) override {
    for (std::size_t i = 0; i < out.size(); ++i) out[i] = static_cast<std::uint8_t>(value_ >> (8 * (i % 4)));
  }

 private:
  std::uint32_t value_;
};

void WalkOptions(std::span<const std::uint8_t> area) {
  net::DhcpOptionReader reader(area);
  net::DhcpOption option;
  std::size_t steps = 0;
  base::Status status;
  while ((status = reader.Next(option)).ok()) {
    Require(++steps <= area.size());
    Require(option.data.empty() ||
            (option.data.data() >= area.data() && option.data.data() + option.data.size() <= area.data() + area.size()));
    Require(option.code != 0 && option.code != 255);
  }
  Require(status.code() == base::StatusCode::kNotFound || status.code() == base::StatusCode::kDataLoss);
  Require(reader.Next(option) == status);  // the end, or the failure, sticks
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::span<const std::uint8_t> input(data, size);
  WalkOptions(input);
  const base::Result<std::span<const std::uint8_t>> after_cookie = net::OptionsAfterCookie(input);
  if (after_cookie.ok()) {
    WalkOptions(after_cookie.value());
    (void)net::ParseIpOptions(after_cookie.value());
  }

  std::uint32_t xid = 0;
  base::MacAddress mac{};
  if (size >= net::kBootpFixedSize) {
    base::ByteReader xid_field(input.subspan(4, 4));
    xid = xid_field.U32Be();
    base::ByteReader mac_field(input.subspan(28, 6));
    mac = base::MacAddress::Read(mac_field);
  }
  const base::Result<net::BootReply> reply = net::ParseBootReply(input, xid, mac);
  if (reply.ok()) {
    Require(net::IsUsableUnicast(reply->your_address));
    Require(!reply->subnet_mask || net::IsContiguousMask(*reply->subnet_mask));
  }

  FixedRandom random(xid);
  net::BootpClient client(mac, random);
  client.Start(0);
  std::array<std::uint8_t, net::kBootpMessageSize> request{};
  Require(client.Poll(0, request) == net::kBootpMessageSize);
  const base::Status status = client.OnReply(input);
  Require(status == reply.status());
  Require((client.state() == net::BootpClient::State::kBound) == status.ok());
  if (status.ok()) {
    Require(client.Lease() == reply.value());
    Require(client.Poll(100 * hal::kMicrosPerSecond, request) == 0);
  }
  return 0;
}
