// Message router request/reply format (CIP Vol. 1 ch. 2) and the router that answers explicit requests.
//
//   request: service, path size in 16-bit words, padded EPATH, request data
//   reply:   service | 0x80, reserved 0, general status, additional status size in words, the
//            additional status words, reply data
//
// Besides dispatching to the objects of an ObjectRegistry, the router itself implements two services
// the manual's card lacks (requirement BEY-1):
// - Multiple Service Packet 0x0A to the Message Router (class 2 instance 1): each embedded request is
//   answered in turn; the reply lists every embedded reply; general status 0x1E when any failed.
// - Unconnected_Send 0x52 to the Connection Manager (class 6 instance 1) whose route path is empty or
//   only port 1 / link address 0 (a Logix-style "backplane slot 0", i.e. this device): the embedded
//   request is answered and its reply is the reply. Other routes: 0x01 with 0x0311 (no such port) or
//   0x0312 (port exists but the card routes nowhere), 0x0315 for a segment that is not a port segment,
//   each followed by the remaining path size (the route path's size in words).
// Nesting (MSP or Unconnected_Send inside one another) is allowed kMaxNesting levels deep; deeper, the
// embedded MSP/Unconnected_Send is answered with 0x02 (resource unavailable).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

#include "base/status.h"
#include "base/byte_reader.h"
#include "base/byte_writer.h"
#include "cip/cip_status.h"
#include "cip/epath.h"
#include "cip/explicit_messaging.h"
#include "cip/object_model.h"

namespace cip {

inline constexpr int kMaxNesting = 2;

struct MessageRouterRequest {
  std::uint8_t service = 0;
  std::span<const std::uint8_t> path;  // padded EPATH, an even number of bytes
  std::span<const std::uint8_t> data;
};

// kOutOfRange when the service or path size byte is missing or the path runs past the end.
base::Result<MessageRouterRequest> DecodeMessageRouterRequest(std::span<const std::uint8_t> bytes);
void EncodeMessageRouterRequest(const MessageRouterRequest& request, base::ByteWriter& out);

struct MessageRouterReply {
  std::uint8_t service = 0;  // with the reply bit
  GeneralStatus general = GeneralStatus::kSuccess;
  std::span<const std::uint8_t> additional_status;  // 2 bytes per word
  std::span<const std::uint8_t> data;
};
base::Result<MessageRouterReply> DecodeMessageRouterReply(std::span<const std::uint8_t> bytes);

// Writes a complete reply with no data.
void EncodeErrorReply(std::uint8_t request_service, const ServiceStatus& status, base::ByteWriter& out);

// Decides whether the originator of a request may have it executed (the firmware's ControlLock,
// docs/security.md "Exclusive-owner write lock"). The router asks after the class, instance, service and
// member checks (0x05, 0x16, 0x08) and before the object looks at the attribute or the data, for every
// request it dispatches: unconnected, class 3, and each member of a Multiple Service Packet or
// Unconnected_Send.
class RequestGuard {
 public:
  virtual ~RequestGuard() = default;
  // Success to let the object execute the request, or the error to answer instead.
  virtual ServiceStatus Admit(const ServiceRequest& request) = 0;
};

class MessageRouter final : public UnconnectedMessageHandler {
 public:
  explicit MessageRouter(ObjectRegistry& objects) : objects_(objects) {}

  // nullptr (the default): every request is dispatched.
  void set_guard(RequestGuard* guard) { guard_ = guard; }

  std::size_t HandleUnconnected(std::span<const std::uint8_t> request, RequestContext& context,
                                std::span<std::uint8_t> reply) override {
    return Handle(request, context, reply, 0);
  }
  // For the connection manager (class 3 requests) and nested requests. Returns the reply's size; 0
  // only when `reply` cannot hold even an error reply.
  std::size_t Handle(std::span<const std::uint8_t> request, RequestContext& context, std::span<std::uint8_t> reply,
                     int depth);

 private:
  ServiceStatus Dispatch(const MessageRouterRequest& request, const ApplicationPath& path, RequestContext& context,
                         base::ByteWriter& reply);
  ServiceStatus MultipleServicePacket(std::span<const std::uint8_t> data, RequestContext& context, base::ByteWriter& reply,
                                      int depth);
  std::size_t UnconnectedSend(const MessageRouterRequest& request, RequestContext& context,
                              std::span<std::uint8_t> reply, int depth);

  ObjectRegistry& objects_;
  RequestGuard* guard_ = nullptr;
};

}  // namespace cip
