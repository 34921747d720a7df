// libFuzzer target for the drive profile at run time (cip/drive): DriveAssemblies as the Connection
// Manager's IoApplication and as the assemblies' explicit write handler, the runtime behind them and the
// Control Supervisor / AC/DC Drive objects, on the fakes of cip/test/drive_channel_fake.h.
//
// Input: a sequence of records, each an operation byte and its operands read from the input (0 once it is
// used up):
//   0 Describe(configuration?, consumed, produced, requested sizes)   1 Consume(point, n bytes, run)
//   2 Produce(point, size)                                            3 explicit Set of assembly data
//   4 the inverter's status (FD01, FD00, FE02)                        5 Poll after some time
//   6 complete the pending parameter accesses                          7 ownership / connections changed
//   8 a message router request to 0x29/0x2A (n bytes)
// Oracles:
// - Describe accepts a connection only with sizes its points can have (IsValidSize for data points, 0 for
//   heartbeats) and refuses with one of 0x0129/0x012A/0x012B/0x012F;
// - idle data (run = false) changes nothing the drive sees: no drive command, no scanner words;
// - an explicit write of an owned data output is refused and changes nothing;
// - Produce fills exactly the buffer it is given (bytes beyond it stay untouched);
// - router replies decode and carry the reply bit.
#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "cip/drive/assembly_codec.h"
#include "drive_channel_fake.h"

namespace {

using cip::drive::test::DriveCard;

void Require(bool condition) {
  if (!condition) __builtin_trap();
}

class Input {
 public:
  explicit Input(std::span<const std::uint8_t> bytes) : bytes_(bytes) {}
  bool more() const { return position_ < bytes_.size(); }
  std::uint8_t U8() { return position_ < bytes_.size() ? bytes_[position_++] : 0; }
  std::uint16_t U16() { return static_cast<std::uint16_t>(U8() | U8() << 8); }
  std::vector<std::uint8_t> Bytes(std::size_t n) {
    std::vector<std::uint8_t> out;
    for (std::size_t i = 0; i < n; ++i) out.push_back(U8());
    return out;
  }

 private:
  std::span<const std::uint8_t> bytes_;
  std::size_t position_ = 0;
};

// The points the fuzzer picks from: every assembly, the heartbeats, configuration 1, and a few others.
constexpr std::array<std::uint32_t, 20> kPoints = {1,   20,  21,  70,  71,  100, 101, 102, 105, 150,
                                                   151, 152, 155, 198, 199, 0,   2,   103, 200, 0xFFFF};

std::uint32_t Point(Input& in) { return kPoints[in.U8() % kPoints.size()]; }

void CheckDescribe(const cip::IoConnectionSpec& spec, const cip::IoPoints& points) {
  if (spec.extended != 0) {
    Require(spec.extended == cip::kExtendedConfigurationPath || spec.extended == cip::kExtendedConsumingPath ||
            spec.extended == cip::kExtendedProducingPath || spec.extended == cip::kExtendedInconsistentPaths);
    return;
  }
  const bool heartbeat = points.consumed == 198 || points.consumed == 199;
  if (heartbeat) {
    Require(spec.consumed_size == 0);
  } else {
    Require(cip::drive::IsValidSize(points.consumed, spec.consumed_size));
  }
  Require(cip::drive::IsValidSize(points.produced, spec.produced_size));
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  DriveCard card;
  Input in(std::span<const std::uint8_t>(data, size));
  hal::Micros now = 1000000;
  for (int step = 0; step < 64 && in.more(); ++step) {
    switch (in.U8() % 9) {
      case 0: {
        cip::IoPoints points;
        if (in.U8() & 1) points.configuration = Point(in);
        points.consumed = Point(in);
        points.produced = Point(in);
        const cip::IoRequestedSizes requested{in.U8(), in.U8()};
        CheckDescribe(card.assemblies.Describe(points, requested), points);
        break;
      }
      case 1: {
        const std::uint32_t point = Point(in);
        const bool run = (in.U8() & 1) != 0;
        const std::vector<std::uint8_t> bytes = in.Bytes(in.U8() % 20);
        const std::size_t commands = card.channel.commands.size();
        const std::size_t masked = card.channel.masked.size();
        card.assemblies.Consume(point, bytes, run);
        if (!run) Require(card.channel.commands.size() == commands && card.channel.masked.size() == masked);
        break;
      }
      case 2: {
        const std::uint32_t point = Point(in);
        const std::size_t length = in.U8() % 20;
        std::array<std::uint8_t, 24> out;
        out.fill(0xA5);
        card.assemblies.Produce(point, std::span<std::uint8_t>(out.data(), length));
        Require(std::all_of(out.begin() + static_cast<std::ptrdiff_t>(length), out.end(),
                            [](std::uint8_t b) { return b == 0xA5; }));
        break;
      }
      case 3: {
        const std::uint32_t point = Point(in);
        const std::vector<std::uint8_t> bytes = in.Bytes(in.U8() % 20);
        // Only an exclusive owner owns a point, and those consume the data outputs (not heartbeats).
        const bool owned = card.ownership.IsOwned(point) && cip::drive::IsOutputInstance(point) &&
                           cip::drive::AssemblySize(point) > 0;
        const std::size_t commands = card.channel.commands.size();
        const cip::ServiceStatus status = card.assemblies.OnExplicitWrite(point, bytes);
        if (owned) Require(!status.ok() && card.channel.commands.size() == commands);
        break;
      }
      case 4:
        card.Drive(in.U16(), in.U16(), in.U16());
        break;
      case 5:
        now += in.U16() * hal::kMicrosPerMilli;
        card.assemblies.Poll(now);
        break;
      case 6:
        card.registers.CompleteAll();
        break;
      case 7: {
        const std::uint32_t point = Point(in);
        if (in.U8() & 1) {
          card.ownership.owned.insert(point);
        } else {
          card.ownership.owned.erase(point);
        }
        card.assemblies.OnConnectionsChanged();
        break;
      }
      case 8: {
        const std::vector<std::uint8_t> request = in.Bytes(in.U8() % 24);
        const cip::test::Bytes reply = card.Ask(request);
        if (!reply.empty()) {
          const base::Result<cip::MessageRouterReply> decoded = cip::DecodeMessageRouterReply(reply);
          Require(decoded.ok());
          Require((decoded->service & cip::kReplyServiceBit) != 0);
        }
        break;
      }
    }
  }
  return 0;
}
