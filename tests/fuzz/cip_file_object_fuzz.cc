// libFuzzer target for the File object 0x37 (cip/file_object.h): its request parsing (Initiate_Upload,
// Upload_Transfer, attribute reads) behind the message router of a CipDevice on the fakes of
// cip/test/cip_fakes.h, serving a ByteSpanFile.
//
// Input: byte 0 = the file's size / 3 (0..765 bytes of a known pattern); then requests, each one byte of
// length, one byte of origin (bit 0: session 1 or 2; bits 1-7: seconds to advance the clock) and that
// many message router request bytes. Oracles:
// - every reply decodes, has the reply bit, and an error reply carries no data;
// - the uploaded bytes (Multiple Service Packet and Unconnected_Send requests are skipped: the model
//   would not see what they carry) are the file's: a model follows the one upload that exists (restarted by each
//   successful Initiate_Upload); each successful Upload_Transfer is the packet the model expects or the
//   packet sent last again, with its number, packet type, at most the transfer size of data equal to the
//   file's bytes at that offset, and after the last packet's data the file's checksum.
#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "cip/byte_span_file.h"
#include "cip/file_object.h"
#include "cip/message_router.h"
#include "cip_fakes.h"

namespace {

void Require(bool condition) {
  if (!condition) __builtin_trap();
}

struct UploadModel {
  bool active = false;
  std::size_t transfer_size = 0;
  std::size_t next_offset = 0;
  bool sent_any = false;
  std::uint8_t last_number = 0;
  std::vector<std::uint8_t> last_packet;
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  std::vector<std::uint8_t> file_bytes(static_cast<std::size_t>(data[0]) * 3);
  for (std::size_t i = 0; i < file_bytes.size(); ++i) file_bytes[i] = static_cast<std::uint8_t>(i * 7 + 3);
  const cip::ByteSpanFile content(file_bytes);
  cip::test::FakeCard card;
  cip::FileObject file_object(cip::ServedFile{&content, "fuzz.eds", 1, 0});
  Require(card.cip.objects().Register(file_object.object()).ok());

  UploadModel model;
  hal::Micros now = 0;
  std::size_t position = 1;
  while (position + 2 <= size) {
    const std::size_t length = std::min<std::size_t>(data[position], size - position - 2);
    const std::uint8_t origin = data[position + 1];
    const std::span<const std::uint8_t> request(data + position + 2, length);
    position += 2 + length;
    now += static_cast<hal::Micros>(origin >> 1) * hal::kMicrosPerSecond;
    // Requests that carry others (Multiple Service Packet, Unconnected_Send) would move the upload
    // without the model seeing the embedded replies: the router's own fuzz target covers them.
    if (!request.empty() && (request[0] == cip::kServiceMultipleServicePacket || request[0] == cip::kServiceUnconnectedSend)) {
      continue;
    }

    std::array<std::uint8_t, cip::kMaxEncapsulationData> reply{};
    cip::RequestContext context;
    context.session_handle = 1 + (origin & 1);
    context.now = now;
    const std::size_t reply_size = card.cip.router().HandleUnconnected(request, context, reply);
    Require(reply_size >= 4 && reply_size <= reply.size());
    const base::Result<cip::MessageRouterReply> decoded =
        cip::DecodeMessageRouterReply(std::span<const std::uint8_t>(reply).first(reply_size));
    Require(decoded.ok());
    Require((decoded->service & cip::kReplyServiceBit) != 0);
    if (decoded->general != cip::GeneralStatus::kSuccess) {
      Require(decoded->data.empty() || decoded->general == cip::GeneralStatus::kEmbeddedServiceError);
      continue;
    }
    const std::uint8_t service = decoded->service & 0x7F;
    const base::Result<cip::MessageRouterRequest> parsed = cip::DecodeMessageRouterRequest(request);
    Require(parsed.ok());
    const base::Result<cip::ApplicationPath> path = cip::DecodeApplicationPath(parsed->path);
    if (!path.ok() || path->class_id != cip::kClassFile) continue;
    const std::span<const std::uint8_t> answer = decoded->data;
    if (service == cip::kServiceInitiateUpload) {
      Require(answer.size() == 5);
      Require((answer[0] | answer[1] << 8 | answer[2] << 16 | answer[3] << 24) ==
              static_cast<int>(file_bytes.size()));
      Require(answer[4] != 0 && answer[4] == parsed->data[0]);
      model = UploadModel{true, answer[4], 0, false, 0, {}};
    } else if (service == cip::kServiceUploadTransfer) {
      Require(model.active && answer.size() >= 2 && answer[0] == parsed->data[0]);
      if (model.sent_any && answer[0] == model.last_number) {
        Require(std::equal(answer.begin(), answer.end(), model.last_packet.begin(), model.last_packet.end()));
        continue;
      }
      Require(answer[0] == (model.sent_any ? static_cast<std::uint8_t>(model.last_number + 1) : 0));
      const std::size_t offset = model.next_offset;
      const std::size_t count = std::min(model.transfer_size, file_bytes.size() - offset);
      const bool first = offset == 0;
      const bool last = offset + count == file_bytes.size();
      const std::uint8_t type = first && last ? 4 : first ? 0 : last ? 2 : 1;
      Require(answer[1] == type);
      Require(answer.size() == 2 + count + (last ? 2 : 0));
      Require(std::equal(answer.begin() + 2, answer.begin() + 2 + static_cast<std::ptrdiff_t>(count),
                         file_bytes.begin() + static_cast<std::ptrdiff_t>(offset)));
      if (last) Require((answer[2 + count] | answer[3 + count] << 8) == content.Checksum());
      model.sent_any = true;
      model.last_number = answer[0];
      model.last_packet.assign(answer.begin(), answer.end());
      model.next_offset = offset + count;
    }
  }
  return 0;
}
