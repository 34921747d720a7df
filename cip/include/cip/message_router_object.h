// Message Router object 0x02 (manual §4.2): one instance.
//
//   class attributes  1 revision 1, 2 max instance 1, 3 instances 1, 4 optional attributes (2, 3),
//                     6 max class attribute 7, 7 max instance attribute 3
//   class services    Get_Attribute_Single 0x0E
//   instance          2 number available 16 (UINT), 3 number active (UINT, from the connection manager)
//   instance services Get_Attribute_Single 0x0E; Multiple Service Packet 0x0A is answered by the
//                     MessageRouter itself (message_router.h)
#pragma once

#include <cstdint>
#include <span>

#include "cip/object_model.h"
#include "cip/providers.h"

namespace cip {

// The connections the card accepts (lwipopts IPE_MAX_CIP_CONNECTIONS, §4.2 "Number Available").
inline constexpr std::uint16_t kMaxCipConnections = 16;

class MessageRouterObject final : public AttributeHandler {
 public:
  // `connections` may be null until the connection manager exists: attribute 3 then reads 0.
  explicit MessageRouterObject(const ConnectionCountProvider* connections);

  CipObject& object() { return object_; }
  void set_connection_counter(const ConnectionCountProvider* connections) { connections_ = connections; }

  std::uint32_t MaxInstance() const override { return 1; }
  std::span<const AttributeSpec> InstanceAttributes(std::uint32_t instance) const override;
  void GetInstanceAttribute(std::uint32_t instance, std::uint16_t id, base::ByteWriter& out) override;

 private:
  const ConnectionCountProvider* connections_;
  AttributeObject object_;
};

}  // namespace cip
