// libFuzzer target for the message router and EPATH decoding (cip/), with the standard objects of a
// CipDevice on the fakes of cip/test/cip_fakes.h and a test assembly registered.
//
// Input: byte 0 sets the reply buffer size (8 + byte 0 * 4: every error reply fits, the overflow paths of
// longer replies are reached); the rest is
// one message router request. Oracles:
// - the reply fits the buffer, decodes as a reply, has the reply bit set, and an error reply carries
//   no data unless it is a Multiple Service Packet's 0x1E or an Unconnected_Send routing error;
// - EPATH: every segment walk ends (progress) and stays inside the path; an application path that
//   decodes re-encodes to a path that decodes to the same values (round trip).
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "cip/epath.h"
#include "cip/message_router.h"
#include "cip_fakes.h"

namespace {

void Require(bool condition) {
  if (!condition) __builtin_trap();
}

void CheckPath(std::span<const std::uint8_t> path) {
  cip::EpathReader reader(path);
  cip::PathSegment segment;
  std::size_t segments = 0;
  while (reader.Next(segment)) {
    ++segments;
    Require(segments <= path.size());  // every segment takes at least one byte
    if (!segment.bytes.empty()) {
      Require(segment.bytes.data() >= path.data() && segment.bytes.data() + segment.bytes.size() <= path.data() + path.size());
    }
  }
  const base::Result<cip::ApplicationPath> decoded = cip::DecodeApplicationPath(path);
  if (!decoded.ok()) return;
  std::array<std::uint8_t, 32> buffer{};
  base::ByteWriter out(buffer);
  cip::EncodeLogicalSegment(cip::SegmentKind::kClass, decoded->class_id, out);
  cip::EncodeLogicalSegment(cip::SegmentKind::kInstance, decoded->instance, out);
  if (decoded->attribute) cip::EncodeLogicalSegment(cip::SegmentKind::kAttribute, *decoded->attribute, out);
  if (decoded->member) cip::EncodeLogicalSegment(cip::SegmentKind::kMember, *decoded->member, out);
  Require(out.ok());
  const base::Result<cip::ApplicationPath> again = cip::DecodeApplicationPath(out.written());
  Require(again.ok() && *again == *decoded);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::span<const std::uint8_t> request(data + 1, size - 1);
  std::array<std::uint8_t, 8> assembly_data{};
  cip::test::FakeCard card;
  (void)card.cip.assemblies().Register(100, cip::AssemblyDirection::kOutput, assembly_data);

  std::vector<std::uint8_t> reply(8 + static_cast<std::size_t>(data[0]) * 4);
  cip::RequestContext context;
  const std::size_t reply_size = card.cip.router().HandleUnconnected(request, context, reply);
  Require(reply_size >= 4 && reply_size <= reply.size());
  const base::Result<cip::MessageRouterReply> decoded =
      cip::DecodeMessageRouterReply(std::span<const std::uint8_t>(reply).first(reply_size));
  Require(decoded.ok());
  Require((decoded->service & cip::kReplyServiceBit) != 0);
  if (decoded->general != cip::GeneralStatus::kSuccess) {
    const bool msp = decoded->general == cip::GeneralStatus::kEmbeddedServiceError;
    const bool routing = decoded->general == cip::GeneralStatus::kConnectionFailure;
    // A routing error carries the remaining path size and a reserved byte.
    Require(decoded->data.empty() || msp || (routing && decoded->data.size() == 2));
  }

  const base::Result<cip::MessageRouterRequest> parsed = cip::DecodeMessageRouterRequest(request);
  if (parsed.ok()) CheckPath(parsed->path);
  CheckPath(request);
  return 0;
}
