#include "net/dhcp_options.h"

#include <algorithm>

namespace net {

base::Status DhcpOptionReader::Next(DhcpOption& option) {
  if (failed_) return base::DataLoss();
  while (!rest_.empty()) {
    const std::uint8_t code = rest_[0];
    if (code == static_cast<std::uint8_t>(DhcpOptionCode::kPad)) {
      rest_ = rest_.subspan(1);
      continue;
    }
    if (code == static_cast<std::uint8_t>(DhcpOptionCode::kEnd)) {
      rest_ = {};
      return base::NotFound();
    }
    // Code and length, then `length` bytes, all inside the area.
    if (rest_.size() < 2 || rest_.size() - 2 < rest_[1]) {
      failed_ = true;
      rest_ = {};
      return base::DataLoss();
    }
    const std::size_t length = rest_[1];
    option.code = code;
    option.data = rest_.subspan(2, length);
    rest_ = rest_.subspan(2 + length);
    return base::OkStatus();
  }
  return base::NotFound();
}

base::Result<std::span<const std::uint8_t>> OptionsAfterCookie(std::span<const std::uint8_t> vendor_area) {
  if (vendor_area.size() < kMagicCookie.size() ||
      !std::equal(kMagicCookie.begin(), kMagicCookie.end(), vendor_area.begin())) {
    return base::NotFound();
  }
  return vendor_area.subspan(kMagicCookie.size());
}

base::Result<IpOptions> ParseIpOptions(std::span<const std::uint8_t> options) {
  IpOptions result;
  DhcpOptionReader reader(options);
  DhcpOption option;
  while (true) {
    const base::Status status = reader.Next(option);
    if (status.code() == base::StatusCode::kNotFound) return result;
    if (!status.ok()) return status;
    const auto code = static_cast<DhcpOptionCode>(option.code);
    if (code == DhcpOptionCode::kSubnetMask) {
      if (option.data.size() != 4) return base::InvalidArgument();
      if (!result.subnet_mask) {
        base::ByteReader data(option.data);
        result.subnet_mask = base::Ipv4Address::Read(data);
      }
    } else if (code == DhcpOptionCode::kRouter) {
      if (option.data.empty() || option.data.size() % 4 != 0) return base::InvalidArgument();
      if (!result.router) {
        base::ByteReader data(option.data);
        result.router = base::Ipv4Address::Read(data);
      }
    }
  }
}

bool DhcpOptionWriter::Reserve(std::size_t bytes) {
  if (!status_.ok()) return false;
  if (out_.size() - used_ < bytes) {
    status_ = base::ResourceExhausted();
    return false;
  }
  return true;
}

void DhcpOptionWriter::Cookie() {
  if (!Reserve(kMagicCookie.size())) return;
  std::copy(kMagicCookie.begin(), kMagicCookie.end(), out_.begin() + static_cast<std::ptrdiff_t>(used_));
  used_ += kMagicCookie.size();
}

void DhcpOptionWriter::Option(DhcpOptionCode code, std::span<const std::uint8_t> data) {
  if (data.size() > 255) {
    if (status_.ok()) status_ = base::InvalidArgument();
    return;
  }
  if (!Reserve(2 + data.size())) return;
  out_[used_] = static_cast<std::uint8_t>(code);
  out_[used_ + 1] = static_cast<std::uint8_t>(data.size());
  std::copy(data.begin(), data.end(), out_.begin() + static_cast<std::ptrdiff_t>(used_ + 2));
  used_ += 2 + data.size();
}

void DhcpOptionWriter::End() {
  if (!Reserve(1)) return;
  out_[used_] = static_cast<std::uint8_t>(DhcpOptionCode::kEnd);
  used_ += 1;
}

}  // namespace net
