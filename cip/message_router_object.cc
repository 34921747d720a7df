#include "cip/message_router_object.h"

#include <array>

namespace cip {
namespace {

constexpr std::array<std::uint16_t, 6> kClassAttributes = {1, 2, 3, 4, 6, 7};
constexpr std::array<std::uint16_t, 2> kOptionalAttributes = {2, 3};
constexpr std::array<std::uint8_t, 1> kServices = {kServiceGetAttributeSingle};
constexpr ClassSpec kMessageRouterClass = {
    kClassMessageRouter, 1, kClassAttributes, kOptionalAttributes, {}, 7, 3, kServices, kServices,
};
constexpr std::array<AttributeSpec, 2> kAttributes = {{
    {2, Access::kGet, true},
    {3, Access::kGet, true},
}};

}  // namespace

MessageRouterObject::MessageRouterObject(const ConnectionCountProvider* connections)
    : connections_(connections), object_(kMessageRouterClass, *this) {}

std::span<const AttributeSpec> MessageRouterObject::InstanceAttributes(std::uint32_t) const { return kAttributes; }

void MessageRouterObject::GetInstanceAttribute(std::uint32_t, std::uint16_t id, base::ByteWriter& out) {
  if (id == 2) out.U16Le(kMaxCipConnections);
  if (id == 3) out.U16Le(connections_ != nullptr ? connections_->ActiveConnections() : 0);
}

}  // namespace cip
