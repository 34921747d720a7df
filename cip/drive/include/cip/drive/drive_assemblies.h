// The Assembly instances of the drive profile and the connection points the Connection Manager opens
// (seed 000 §4.3, §5; docs/drive-profile.md "Connection points" and "Runtime"; docs/connections.md
// "For the assemblies"). The data goes to and comes from DriveProfileRuntime.
//
//   output (consumed, O->T)  20 (4 B), 21 (4 B), 100 (4-16 B), 101 (8 B), 102 (12 B), 105 (18 B)
//   input (produced, T->O)   70 (4 B), 71 (4 B), 150 (4-16 B), 151 (8 B), 152 (12 B), 155 (18 B)
//   heartbeats (size 0)      199 input only (an Assembly instance: the class reads 199 / 13),
//                            198 listen only (a connection point only)
//   configuration point      1, size 0 (a connection point only; no Assembly instance)
//
// Describe, per docs/connections.md (extended status of the refusal):
//   0x0129  a configuration point other than 1 (none at all is accepted too)
//   0x012A  a consumed point that is not one of the card's points
//   0x012B  a produced point that is not one of the card's points
//   0x012F  both are points of the card but not in these roles (an input consumed, an output or a
//           heartbeat produced, the configuration point as data)
// Kinds: consumed 199 -> input only, 198 -> listen only, an output -> exclusive owner. Any output may be
// paired with any input (the codecs are independent; §5's pairs are PairedInput). Sizes: 100 and 150
// take the requested size when IsValidSize accepts it, else 16 (the Forward_Open is then refused with
// 0x0127/0x0128 naming the connection size for 16); every other point has its one size.
//
// Memory: the card's own fixed arrays. An output instance holds the last data applied (a connection's
// packet in run mode, or an explicit Set); an input instance is refreshed by Poll and by every
// production, so an explicit Get of attribute 3 reads the current status. 100/150 hold 16 bytes (their
// explicit size); a shorter connection fills the beginning.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "base/status.h"
#include "cip/assembly_object.h"
#include "cip/connection_manager.h"
#include "cip/drive/drive_profile_runtime.h"
#include "cip/io_connection.h"

namespace cip::drive {

// The Connection Manager as the runtime's OwnershipQuery.
class ConnectionManagerOwnership final : public OwnershipQuery {
 public:
  explicit ConnectionManagerOwnership(const ConnectionManager& connections) : connections_(connections) {}
  bool IsOwned(std::uint32_t consumed_point) const override { return connections_.IsOwned(consumed_point); }

 private:
  const ConnectionManager& connections_;
};

// Input + output bytes of the 12 data assemblies (4 + 4 + 16 + 8 + 12 + 18 each way).
inline constexpr std::size_t kAssemblyMemorySize = 2 * (4 + 4 + 16 + 8 + 12 + 18);

class DriveAssemblies final : public IoApplication, public AssemblyWriteHandler, public AssemblyInputSource {
 public:
  explicit DriveAssemblies(DriveProfileRuntime& runtime);
  DriveAssemblies(const DriveAssemblies&) = delete;
  DriveAssemblies& operator=(const DriveAssemblies&) = delete;

  // Registers the 12 data assemblies and heartbeat 199 (13 instances, the highest 199). Fails as
  // AssemblyObject::Register does (an instance already there, the object full).
  base::Status Register(AssemblyObject& assemblies);

  // IoApplication
  IoConnectionSpec Describe(const IoPoints& points, const IoRequestedSizes& requested) const override;
  // Run mode: the data is applied (DriveProfileRuntime::ApplyOutput). Idle (run = false): nothing is
  // applied, not even a fault reset or a parameter request; the firmware treats idle as a loss of the
  // master (LossSupervision), the data of a PLC in Program mode is no command.
  void Consume(std::uint32_t point, std::span<const std::uint8_t> data, bool run) override;
  void Produce(std::uint32_t point, std::span<std::uint8_t> out) override;

  // AssemblyWriteHandler: 0x10 device state conflict when DriveProfileRuntime::ExplicitWriteAllowed
  // says no (an exclusive owner holds it), else applied as a packet in run mode.
  ServiceStatus OnExplicitWrite(std::uint32_t instance, std::span<const std::uint8_t> data) override;

  // AssemblyInputSource: an explicit read of an input instance sees the drive as it is now.
  void RefreshInput(std::uint32_t instance, std::span<std::uint8_t> data) override;

  // The firmware's Service: drives the runtime (parameter accesses, supervisor, feedback hold). The
  // input instances' memory is filled when read or produced, not here (a pass is not a change).
  void Poll(hal::Micros now);
  hal::Micros NextDeadline() const { return runtime_.NextDeadline(); }
  // Forwarded to DriveProfileRuntime::OnConnectionsChanged (call from ConnectionEvents).
  void OnConnectionsChanged() { runtime_.OnConnectionsChanged(); }

  // The memory of a data instance (empty for others), for tests and the web page.
  std::span<const std::uint8_t> Memory(std::uint32_t instance) const;

 private:
  std::span<std::uint8_t> MemoryOf(std::uint32_t instance);

  DriveProfileRuntime& runtime_;
  std::array<std::uint8_t, kAssemblyMemorySize> memory_{};
};

}  // namespace cip::drive
