#include "net/lldp_agent.h"

#include <algorithm>

namespace net {
namespace {

// Port ID (subtype 7, locally assigned) = the Ethernet Link object instance of the port.
constexpr std::array<std::string_view, kLldpPorts> kPortIds = {"1", "2"};
constexpr std::array<std::string_view, kLldpPorts> kPortDescriptions = {"port L", "port R"};
constexpr std::uint32_t kIpInterfaceNumber = 1;  // the card's one IP interface
constexpr std::size_t kFrameCapacity = 512;      // the card's LLDPDU is about 150 bytes

bool SameKey(const LldpNeighbour& entry, std::size_t port, const LldpNeighbourInfo& info) {
  return entry.port == port && entry.info.chassis == info.chassis && entry.info.port == info.port;
}

}  // namespace

LldpAgent::LldpAgent(const LldpIdentity& identity, LldpSink& sink) : identity_(identity), sink_(sink) {
  SetSystemName({});
}

void LldpAgent::SetSystemName(std::string_view name) {
  std::array<char, kLldpSystemNameMax> text{};
  std::size_t size = std::min(name.size(), text.size());
  std::copy_n(name.begin(), size, text.begin());
  if (size == 0) {
    static constexpr char kHex[] = "0123456789ABCDEF";
    size = std::min(identity_.product.size(), text.size() - 7);
    std::copy_n(identity_.product.begin(), size, text.begin());
    text[size++] = '-';
    for (std::size_t i = 3; i < base::MacAddress::kSize; ++i) {
      text[size++] = kHex[identity_.mac.octets()[i] >> 4];
      text[size++] = kHex[identity_.mac.octets()[i] & 0xF];
    }
  }
  if (size == name_size_ && text == name_) return;
  name_ = text;
  name_size_ = size;
  AdvertiseChange();
}

void LldpAgent::SetManagementAddress(base::Ipv4Address address) {
  if (address == management_) return;
  management_ = address;
  AdvertiseChange();
}

void LldpAgent::AdvertiseChange() {
  for (std::size_t port = 0; port < kLldpPorts; ++port) {
    if (up_[port]) next_tx_[port] = std::min(next_tx_[port], earliest_tx_[port]);
  }
}

void LldpAgent::LinkUp(std::size_t port, hal::Micros now) {
  if (port >= kLldpPorts || up_[port]) return;
  up_[port] = true;
  earliest_tx_[port] = now + kLldpFirstFrameDelay;
  next_tx_[port] = earliest_tx_[port];
}

void LldpAgent::LinkDown(std::size_t port) {
  if (port >= kLldpPorts) return;
  up_[port] = false;
  next_tx_[port] = hal::kNever;
  for (std::size_t i = count_; i > 0; --i) {
    if (table_[i - 1].port == port) Remove(i - 1);
  }
}

bool LldpAgent::OnFrame(std::size_t port, std::span<const std::uint8_t> frame, hal::Micros now) {
  const base::Result<LldpNeighbourInfo> parsed = ParseLldpFrame(frame);
  if (parsed.status().code() == base::StatusCode::kNotFound) return false;
  ++counters_.frames_in;
  if (!parsed.ok() || port >= kLldpPorts) {
    ++counters_.malformed;
    return true;
  }
  const LldpNeighbourInfo& info = parsed.value();
  std::size_t index = 0;
  while (index < count_ && !SameKey(table_[index], port, info)) ++index;
  if (info.ttl_seconds == 0) {  // the neighbour is leaving (shutdown LLDPDU)
    if (index < count_) Remove(index);
    return true;
  }
  if (index == count_) {
    if (count_ == table_.size()) {
      ++counters_.table_full;
      return true;
    }
    ++count_;
  }
  LldpNeighbour& entry = table_[index];
  entry.port = static_cast<std::uint8_t>(port);
  entry.info = info;
  entry.expires = now + info.ttl_seconds * hal::kMicrosPerSecond;
  return true;
}

void LldpAgent::Poll(hal::Micros now) {
  for (std::size_t i = count_; i > 0; --i) {
    if (table_[i - 1].expires <= now) {
      Remove(i - 1);
      ++counters_.aged_out;
    }
  }
  for (std::size_t port = 0; port < kLldpPorts; ++port) {
    if (up_[port] && next_tx_[port] <= now) Send(port, now);
  }
}

hal::Micros LldpAgent::NextDeadline() const {
  hal::Micros deadline = std::min(next_tx_[0], next_tx_[1]);
  for (std::size_t i = 0; i < count_; ++i) deadline = std::min(deadline, table_[i].expires);
  return deadline;
}

void LldpAgent::Remove(std::size_t index) {
  // The table stays in arrival order: the entries after `index` move up by one.
  std::copy(table_.begin() + static_cast<std::ptrdiff_t>(index) + 1,
            table_.begin() + static_cast<std::ptrdiff_t>(count_), table_.begin() + static_cast<std::ptrdiff_t>(index));
  --count_;
}

void LldpAgent::Send(std::size_t port, hal::Micros now) {
  const LldpAdvert advert{
      .mac = identity_.mac,
      .port_id = kPortIds[port],
      .ttl_seconds = kLldpTtlSeconds,
      .port_description = kPortDescriptions[port],
      .system_name = system_name(),
      .system_description = identity_.system_description,
      .management = management_,
      .interface_number = kIpInterfaceNumber,
  };
  std::array<std::uint8_t, kFrameCapacity> frame;
  const base::Result<std::size_t> size = BuildLldpFrame(advert, frame);
  earliest_tx_[port] = now + kLldpMinGap;
  next_tx_[port] = now + kLldpTxInterval;
  if (!size.ok()) return;  // cannot happen: the advert's strings are bounded far below the capacity
  sink_.SendLldp(port, std::span<const std::uint8_t>(frame.data(), size.value()));
  ++counters_.frames_out;
}

}  // namespace net
