// libFuzzer target for the CIP drive objects 0x28/0x64/0x65 and their access journal (cip/drive), behind
// the message router, with the register fake of drive_link/test/drive_registers_fake.h completing accesses
// from the input.
//
// Input: byte 0 = n, the number of requests (1-3, n % 3 + 1); then per request one length byte and that
// many request bytes (message router requests, e.g. Get/Set/MSP of the three classes); the rest is the
// drive's script, read a byte at a time (0 when used up): before each pass one byte (bit 0 link down,
// bit 1 the proxy's pool full for the next access), then per completion round one byte for how many
// accesses complete and three per completion (an AccessError, the value).
//
// The requests run interleaved, as different requesters, the way the encapsulation server runs them:
// OnRequestStarted before each pass, a retry once ReadyToRetry, OnRequestFinished after the reply.
// Oracles:
// - replies decode, have the reply bit, and an error reply carries no data (but MSP 0x1E / routing);
// - a pass after which nothing completed starts no access (an access is never started twice);
// - a pending request has something to wait for: with no access outstanding it is ready to retry;
// - a request makes at most kMaxJournalEntries accesses; the journal is empty once every request ends;
// - completions after a request ended are ignored, not crashes.
#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "drive_objects_harness.h"

namespace {

void Require(bool condition) {
  if (!condition) __builtin_trap();
}

class Script {
 public:
  explicit Script(std::span<const std::uint8_t> bytes) : bytes_(bytes) {}
  std::uint8_t Next() { return position_ < bytes_.size() ? bytes_[position_++] : 0; }

 private:
  std::span<const std::uint8_t> bytes_;
  std::size_t position_ = 0;
};

struct Request {
  std::vector<std::uint8_t> bytes;
  std::uint32_t requester = 0;
  bool done = false;
  std::size_t accesses_at_start = 0;
};

void CheckReply(const std::vector<std::uint8_t>& reply) {
  const base::Result<cip::MessageRouterReply> decoded = cip::DecodeMessageRouterReply(reply);
  Require(decoded.ok());
  Require((decoded->service & cip::kReplyServiceBit) != 0);
  if (decoded->general != cip::GeneralStatus::kSuccess) {
    const bool msp = decoded->general == cip::GeneralStatus::kEmbeddedServiceError;
    const bool routing = decoded->general == cip::GeneralStatus::kConnectionFailure;
    Require(decoded->data.empty() || msp || (routing && decoded->data.size() == 2));
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::span<const std::uint8_t> input(data, size);
  const std::size_t count = input[0] % 3 + 1;
  std::size_t position = 1;
  std::vector<Request> requests;
  for (std::size_t i = 0; i < count && position < input.size(); ++i) {
    const std::size_t declared = input[position];
    ++position;
    const std::size_t length = std::min(declared, input.size() - position);
    Request request;
    request.bytes.assign(input.begin() + static_cast<std::ptrdiff_t>(position),
                         input.begin() + static_cast<std::ptrdiff_t>(position + length));
    request.requester = static_cast<std::uint32_t>(i + 1);
    position += length;
    requests.push_back(std::move(request));
  }
  Script script(input.subspan(position));
  cip::drive::test::DriveObjectsHarness h;

  auto run_pass = [&](Request& request) {
    const std::uint8_t flags = script.Next();
    h.drive.link_down = (flags & 1) != 0;
    h.drive.busy_next = (flags & 2) != 0 ? 1 : 0;
    const cip::drive::test::PassResult result = h.Pass(request.bytes, request.requester);
    h.drive.busy_next = 0;
    Require(h.drive.log.size() - request.accesses_at_start <= cip::drive::kMaxJournalEntries);
    if (!result.pending) {
      CheckReply(result.reply);
      h.journal.OnRequestFinished(request.requester);
      request.done = true;
      return;
    }
    Require(h.drive.pending() > 0 || h.journal.ReadyToRetry(request.requester));
  };

  for (Request& request : requests) {
    request.accesses_at_start = h.drive.log.size();
    run_pass(request);
  }
  for (int round = 0; round < 64; ++round) {
    if (std::all_of(requests.begin(), requests.end(), [](const Request& r) { return r.done; })) break;
    for (Request& request : requests) {
      if (request.done) continue;
      if (h.journal.ReadyToRetry(request.requester)) {
        run_pass(request);
        continue;
      }
      // Not ready, and nothing completed since this request's last pass: a retry anyway (a spurious
      // one) pends again and starts nothing. (Each service of these objects makes at most one access
      // and the router stops at the first pending member, so no call of the pass is a new one.)
      h.drive.link_down = false;
      const std::size_t before = h.drive.log.size();
      const cip::drive::test::PassResult early = h.Pass(request.bytes, request.requester);
      Require(early.pending);
      Require(h.drive.log.size() == before);
    }
    // Complete some accesses (at least one when any is outstanding, so that every round moves on).
    const std::size_t completions = std::max<std::size_t>(1, script.Next() % 4);
    for (std::size_t i = 0; i < completions && h.drive.pending() > 0; ++i) {
      drive_link::AccessResult result;
      result.error = static_cast<drive_link::AccessError>(script.Next() % 9);
      const std::uint8_t low = script.Next();
      const std::uint8_t high = script.Next();
      result.value = static_cast<std::uint16_t>(low | high << 8);
      Require(h.drive.CompleteWith(result));
    }
  }
  // Requests still pending end as if their connections closed; late completions are ignored.
  for (Request& request : requests) {
    if (!request.done) h.journal.OnRequestFinished(request.requester);
  }
  const std::uint32_t completions_before = h.journal.completions();
  h.drive.CompleteAll();
  Require(h.journal.completions() == completions_before);
  Require(h.journal.active_requesters() == 0);
  return 0;
}
