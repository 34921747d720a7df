#include "cip/port_object.h"

#include <array>
#include <string_view>

#include "cip/epath.h"

namespace cip {
namespace {

constexpr std::array<std::uint16_t, 7> kClassAttributes = {1, 2, 3, 6, 7, 8, 9};
constexpr std::array<std::uint8_t, 2> kServices = {kServiceGetAttributesAll, kServiceGetAttributeSingle};
constexpr ClassSpec kPortClass = {
    kClassPort, 1, kClassAttributes, {}, {}, 9, 7, kServices, kServices,
};
constexpr std::array<AttributeSpec, 5> kAttributes = {{
    {1, Access::kGet, true},
    {2, Access::kGet, true},
    {3, Access::kGet, true},
    {4, Access::kGet, true},
    {7, Access::kGet, true},
}};
constexpr std::uint16_t kEntryPort = 1;  // instance of the port requests come in through
constexpr std::string_view kPortName = "EtherNet/IP";

}  // namespace

std::size_t FormatIpv4(std::uint32_t address, std::span<std::uint8_t, 15> out) {
  std::size_t size = 0;
  for (int shift = 24; shift >= 0; shift -= 8) {
    const std::uint32_t octet = (address >> shift) & 0xFF;
    if (octet >= 100) out[size++] = static_cast<std::uint8_t>('0' + octet / 100);
    if (octet >= 10) out[size++] = static_cast<std::uint8_t>('0' + octet / 10 % 10);
    out[size++] = static_cast<std::uint8_t>('0' + octet % 10);
    if (shift != 0) out[size++] = '.';
  }
  return size;
}

PortObject::PortObject(const TcpIpProvider& tcpip) : tcpip_(tcpip), object_(kPortClass, *this) {}

std::span<const AttributeSpec> PortObject::InstanceAttributes(std::uint32_t) const { return kAttributes; }

void PortObject::GetInstanceAttribute(std::uint32_t, std::uint16_t id, base::ByteWriter& out) {
  switch (id) {
    case 1:
      out.U16Le(kPortType);
      break;
    case 2:
      out.U16Le(kPortNumber);
      break;
    case 3: {
      std::array<std::uint8_t, 8> path{};
      base::ByteWriter link(path);
      EncodeLogicalSegment(SegmentKind::kClass, kClassTcpIpInterface, link);
      EncodeLogicalSegment(SegmentKind::kInstance, 1, link);
      PutSizedPath(link.written(), out);
      break;
    }
    case 4:
      PutShortString(std::span(reinterpret_cast<const std::uint8_t*>(kPortName.data()), kPortName.size()), out);
      break;
    case 7: {
      std::array<std::uint8_t, 15> text{};
      const std::size_t size = FormatIpv4(tcpip_.ActiveConfiguration().ip_address, text);
      EncodePortSegment(kPortNumber, std::span<const std::uint8_t>(text).first(size), out);
      break;
    }
    default:
      break;
  }
}

void PortObject::GetClassAttribute(std::uint16_t id, base::ByteWriter& out) {
  if (id == 8) out.U16Le(kEntryPort);
  if (id == 9) {
    // One entry per instance, starting with instance 0 (the class), which has type and number 0.
    out.U16Le(0);
    out.U16Le(0);
    out.U16Le(kPortType);
    out.U16Le(kPortNumber);
  }
}

}  // namespace cip
