// Assembly instances and connection points of the drive profile (drive_assemblies.h).
#include "cip/drive/drive_assemblies.h"

#include <algorithm>

namespace cip::drive {

namespace {

// The connection manager's I/O datagrams are sized for the card's assemblies (cip::kMaxIoData).
static_assert(kMaxAssemblySize <= cip::kMaxIoData, "every assembly must fit the connection manager's I/O buffers");

// Refusals of IoApplication::Describe (docs/connections.md).
constexpr std::uint16_t kNoSuchConfigurationPoint = 0x0129;
constexpr std::uint16_t kNoSuchConsumedPoint = 0x012A;
constexpr std::uint16_t kNoSuchProducedPoint = 0x012B;
constexpr std::uint16_t kPointsDoNotConnect = 0x012F;

constexpr bool IsHeartbeat(std::uint32_t point) {
  return point == kListenOnlyHeartbeat || point == kInputOnlyHeartbeat;
}

bool IsCardPoint(std::uint32_t point) {
  return IsOutputInstance(point) || IsInputInstance(point) || IsHeartbeat(point) || point == kConfigurationInstance;
}

// 100/150: the size asked for when it is one of theirs, else the largest as the one to suggest.
std::uint16_t ConnectionSize(std::uint32_t point, std::uint16_t requested) {
  if (point == kNativeOutput || point == kNativeInput) {
    return IsValidSize(point, requested) ? requested : static_cast<std::uint16_t>(AssemblySize(point));
  }
  return static_cast<std::uint16_t>(AssemblySize(point));
}

// Where an instance's bytes start in the memory: outputs in kOutputInstances order, then inputs.
std::size_t MemoryOffset(std::uint32_t instance, bool& found) {
  std::size_t offset = 0;
  using Instances = std::span<const std::uint16_t>;
  for (const Instances instances : {Instances(kOutputInstances), Instances(kInputInstances)}) {
    for (std::uint16_t candidate : instances) {
      if (candidate == instance) {
        found = true;
        return offset;
      }
      offset += AssemblySize(candidate);
    }
  }
  found = false;
  return 0;
}

}  // namespace

DriveAssemblies::DriveAssemblies(DriveProfileRuntime& runtime) : runtime_(runtime) {}

base::Status DriveAssemblies::Register(AssemblyObject& assemblies) {
  for (std::uint16_t instance : kOutputInstances) {
    const base::Status status = assemblies.Register(instance, AssemblyDirection::kOutput, MemoryOf(instance), this);
    if (!status.ok()) return status;
  }
  for (std::uint16_t instance : kInputInstances) {
    const base::Status status = assemblies.RegisterInput(instance, MemoryOf(instance), *this);
    if (!status.ok()) return status;
  }
  // The input-only heartbeat: an O->T point without data. An explicit Set of its 0 bytes is accepted and
  // does nothing (OnExplicitWrite).
  for (std::uint16_t instance : kInputInstances) RefreshInput(instance, MemoryOf(instance));
  return assemblies.Register(kInputOnlyHeartbeat, AssemblyDirection::kOutput, std::span<std::uint8_t>(), this);
}

IoConnectionSpec DriveAssemblies::Describe(const IoPoints& points, const IoRequestedSizes& requested) const {
  IoConnectionSpec spec;
  if (points.configuration.has_value() && *points.configuration != kConfigurationInstance) {
    spec.extended = kNoSuchConfigurationPoint;
    return spec;
  }
  if (!IsCardPoint(points.consumed)) {
    spec.extended = kNoSuchConsumedPoint;
    return spec;
  }
  if (!IsCardPoint(points.produced)) {
    spec.extended = kNoSuchProducedPoint;
    return spec;
  }
  const bool consumed_role = IsOutputInstance(points.consumed) || IsHeartbeat(points.consumed);
  if (!consumed_role || !IsInputInstance(points.produced)) {
    spec.extended = kPointsDoNotConnect;
    return spec;
  }
  if (points.consumed == kInputOnlyHeartbeat) {
    spec.kind = IoConnectionKind::kInputOnly;
  } else if (points.consumed == kListenOnlyHeartbeat) {
    spec.kind = IoConnectionKind::kListenOnly;
  } else {
    spec.kind = IoConnectionKind::kExclusiveOwner;
    // One owner of the drive command: every command output writes FA06/FA07 (docs/drive-control.md).
    spec.owner_conflict = runtime_.DriveCommandOwnedBesides(points.consumed);
  }
  spec.consumed_size = IsHeartbeat(points.consumed) ? 0 : ConnectionSize(points.consumed, requested.consumed);
  spec.produced_size = ConnectionSize(points.produced, requested.produced);
  spec.configuration_size = 0;
  return spec;
}

void DriveAssemblies::Consume(std::uint32_t point, std::span<const std::uint8_t> data, bool run) {
  if (!run) return;
  if (!runtime_.ApplyOutput(point, data, CommandOrigin::kConnection)) return;
  const std::span<std::uint8_t> memory = MemoryOf(point);
  const std::size_t count = std::min(memory.size(), data.size());
  std::copy_n(data.begin(), count, memory.begin());
  std::fill(memory.begin() + static_cast<std::ptrdiff_t>(count), memory.end(), std::uint8_t{0});
}

void DriveAssemblies::Produce(std::uint32_t point, std::span<std::uint8_t> out) {
  runtime_.NoteProduced(point);
  runtime_.Refresh();
  if (!runtime_.FillInput(point, out)) {
    // Describe never lets a connection produce anything else; zeros rather than stale bytes.
    std::fill(out.begin(), out.end(), std::uint8_t{0});
    return;
  }
  const std::span<std::uint8_t> memory = MemoryOf(point);
  if (!memory.empty()) (void)runtime_.FillInput(point, memory);
}

ServiceStatus DriveAssemblies::OnExplicitWrite(std::uint32_t instance, std::span<const std::uint8_t> data) {
  if (!runtime_.ExplicitWriteAllowed(instance)) return Error(GeneralStatus::kDeviceStateConflict);
  if (instance == kInputOnlyHeartbeat) return Success();
  if (runtime_.ExplicitOutputHeldByLoss(instance, data)) return Error(GeneralStatus::kDeviceStateConflict);
  if (!runtime_.ApplyOutput(instance, data, CommandOrigin::kExplicit)) {
    return Error(GeneralStatus::kInvalidAttributeValue);  // not an output of this size: not registered so
  }
  return Success();
}

void DriveAssemblies::Poll(hal::Micros now) {
  runtime_.Poll(now);
}

void DriveAssemblies::RefreshInput(std::uint32_t instance, std::span<std::uint8_t> data) {
  (void)runtime_.FillInput(instance, data);
}

std::span<std::uint8_t> DriveAssemblies::MemoryOf(std::uint32_t instance) {
  bool found = false;
  const std::size_t offset = MemoryOffset(instance, found);
  if (!found) return {};
  return std::span<std::uint8_t>(memory_).subspan(offset, AssemblySize(instance));
}

std::span<const std::uint8_t> DriveAssemblies::Memory(std::uint32_t instance) const {
  bool found = false;
  const std::size_t offset = MemoryOffset(instance, found);
  if (!found) return {};
  return std::span<const std::uint8_t>(memory_).subspan(offset, AssemblySize(instance));
}

}  // namespace cip::drive
