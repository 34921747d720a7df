// The drive profile at run time (docs/drive-profile.md "Runtime"): the one place where the CIP side's
// commands become FA06/FA07 and scanner words, and where the inverter's status becomes the Control
// Supervisor state and the input assemblies' content. It glues the pure pieces of cip/drive
// (DecodeOutput, OutputEdgeTracker, ControlSupervisor, CommandRegisters, ParameterChannel, MakeFeedback)
// to the drive link's facades.
//
// Three front doors share it, so that they can never disagree about who drives the motor:
//   - DriveAssemblies (I/O connections and explicit access to the assemblies),
//   - ControlSupervisorObject 0x29 (Run1, Run2, NetCtrl, FaultRst, Reset),
//   - AcDcDriveObject 0x2A (NetRef, SpeedRef).
//
// Who owns FA06/FA07 (DriveCommandChannel::SetDriveCommand):
//   - an exclusive-owner connection whose output is 20/21/100/101, from its first packet in run mode
//     until it closes or times out (OnConnectionsChanged then gives them back: ReleaseDriveCommand);
//   - explicit messaging (a Set of a command attribute of 0x29/0x2A, or of assembly 20/21/100/101's
//     data), but only while no exclusive owner consumes 20/21/100/101 (0x10 device state conflict
//     otherwise: two masters writing one FA06 would fight every cycle; the same while 102/105 are owned
//     and a c00n menu targets FA06/FA07). A connection's 102/105 packet takes FA06/FA07 back from
//     explicit messaging when a c00n menu targets them, so its scanner words reach them again.
// Nothing is written to the drive when a connection goes away: the drive link's loss supervision
// (c100/c101), started by the firmware from the connection events, decides what the drive does.
//
// Device-path code: no exceptions, RTTI, heap or threads; everything is fixed-size members.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "cip/cip_status.h"
#include "cip/drive/assembly_codec.h"
#include "cip/drive/control_supervisor.h"
#include "cip/drive/drive_profile.h"
#include "cip/drive/parameter_channel.h"
#include "config/card_config.h"
#include "drive_link/register_access.h"
#include "hal/clock.h"

namespace cip::drive {

// Whether an exclusive-owner connection consumes an output point. The firmware passes the Connection
// Manager (ConnectionManagerOwnership in drive_assemblies.h adapts cip::ConnectionManager::IsOwned).
class OwnershipQuery {
 public:
  virtual ~OwnershipQuery() = default;
  virtual bool IsOwned(std::uint32_t consumed_point) const = 0;
};

// The drive status the Control Supervisor follows. FD01 is read in every exchange cycle whatever else
// is wanted, so this is always fresh; `known` must be false while the link is in e-23 or before the
// first FD01 of a configuration load (RegisterProxy: drive_status_known() and the link not in fault).
class DriveStatusSource {
 public:
  virtual ~DriveStatusSource() = default;
  virtual DriveStatus CurrentDriveStatus() const = 0;
};

// The facades the runtime works through; all must outlive it.
struct DriveProfileLinks {
  drive_link::DriveCommandChannel& command;
  drive_link::ScannerImage& scanner;
  drive_link::DriveRegisters& registers;  // the parameter channel of 101/105
  const DriveStatusSource& status;
  const OwnershipQuery& ownership;
};

struct DriveProfileOptions {
  // FD00/FE02 are read (SetFeedbackWanted) from the first production of 70/71/150/151 until none has
  // been produced for this long. A production comes at least every RPI, and the Connection Manager
  // accepts RPIs up to 10 s (ConnectionManagerOptions::max_rpi): keep this above max_rpi.
  hal::Micros feedback_hold = 11 * hal::kMicrosPerSecond;
  // A parameter access refused because the proxy's pool is full is tried again this much later.
  hal::Micros parameter_retry = hal::kMicrosPerMilli;
};

// Where an output assembly's data comes from.
enum class CommandOrigin : std::uint8_t {
  kConnection,  // Consume of an exclusive owner in run mode
  kExplicit,    // Set_Attribute_Single of attribute 3 (no exclusive owner)
};

// The command attributes explicit messaging may set (§4.6 attributes 3, 4, 5, 12; §4.7 attribute 4).
enum class ControlAttribute : std::uint8_t { kRun1, kRun2, kNetCtrl, kFaultReset, kNetRef };

class DriveProfileRuntime final : private drive_link::AccessListener {
 public:
  explicit DriveProfileRuntime(const DriveProfileLinks& links, const DriveProfileOptions& options = {});
  ~DriveProfileRuntime() override;
  DriveProfileRuntime(const DriveProfileRuntime&) = delete;
  DriveProfileRuntime& operator=(const DriveProfileRuntime&) = delete;

  // The configuration in force (f856, cmod, fmod, c001-c006): at start-up and from every
  // ConfigListener::OnConfigLoaded. Factory values until then.
  void SetCardConfig(const config::CardConfig& config);

  // ---- Commands ----
  // Acts on one output assembly's data: decoded, edges tracked, Control Supervisor stepped, FA06/FA07
  // and scanner words handed to the drive link, the parameter request offered. False (nothing done)
  // for an instance that is not an output or a size it cannot have.
  bool ApplyOutput(std::uint32_t instance, std::span<const std::uint8_t> data, CommandOrigin origin);
  // Whether explicit messaging may write output `instance` (assembly attribute 3): 20/21/100/101 when
  // no exclusive owner consumes any of them, 102/105 when none consumes that one, heartbeats always.
  bool ExplicitWriteAllowed(std::uint32_t instance) const;
  // Whether an explicit write of output `instance` would run the drive, change its speed or write
  // scanner words while a network loss holds the drive (DriveCommandChannel::CommandsHeldByLoss): such a
  // write is refused with 0x10, a stop passes (docs/drive-control.md).
  bool ExplicitOutputHeldByLoss(std::uint32_t instance, std::span<const std::uint8_t> data) const;
  // Whether explicit messaging may command the drive (0x29/0x2A Sets, Reset): no exclusive owner
  // consumes a command output (CommandsDrive).
  bool ExplicitControlAllowed() const;
  // Whether output `output` commands the drive (writes FA06/FA07): 20, 21, 100, 101, and 102/105 while a
  // c00n menu targets FA06 or FA07.
  bool CommandsDrive(std::uint32_t output) const;
  // Whether an exclusive owner of `output` would be a second master of the drive command: `output`
  // commands the drive and an exclusive owner of another command output is open (Forward_Open 0x0106,
  // DriveAssemblies::Describe).
  bool DriveCommandOwnedBesides(std::uint32_t output) const;
  // 0x29 attributes 3, 4, 5, 12 and 0x2A attribute 4. 0x10 when ExplicitControlAllowed() is false, and
  // while a network loss holds the drive for everything but Run1/Run2 = 0 (a stop is never refused).
  // FaultRst acts on 0 -> 1 only (one fault reset while the drive is tripped).
  ServiceStatus SetControl(ControlAttribute attribute, bool value);
  // 0x2A attribute 8 (rpm; negative: 0 Hz). 0x10 when ExplicitControlAllowed() is false or a network
  // loss holds the drive.
  ServiceStatus SetSpeedReference(std::int16_t rpm);
  // 0x29 Reset service: the supervisor back to Startup, Run1/Run2/FaultRst back to 0 (FA06 loses its
  // run bits when explicit messaging holds it). 0x10 when ExplicitControlAllowed() is false.
  ServiceStatus ResetSupervisor();

  // ---- Status ----
  // Steps the Control Supervisor with the newest drive status and rewrites FA06/FA07 when the run type
  // in force changed (a fault or a "not ready" drops a run: a held level needs a new edge).
  void Refresh();
  // Fills input assembly `instance` (70/71/150/151/152/155; `out` of a size IsValidSize accepts) from
  // the state of the last Refresh. False for anything else.
  bool FillInput(std::uint32_t instance, std::span<std::uint8_t> out) const;
  // A connection produced `instance` just now: FD00/FE02 are wanted while 70/71/150/151 are produced.
  void NoteProduced(std::uint32_t instance);

  const ControlSupervisor& supervisor() const { return supervisor_; }
  bool run1() const { return run1_; }
  bool run2() const { return run2_; }
  bool net_ctrl() const { return net_ctrl_; }
  bool net_ref() const { return net_ref_; }
  bool fault_reset_attribute() const { return fault_reset_attribute_; }
  std::int16_t speed_reference_rpm() const { return speed_reference_rpm_; }
  // 0x29 attribute 15 / 0x2A attribute 29 (and 71/151 bits 5/6).
  ControlSources control_sources() const;
  std::uint16_t pole_pairs() const { return config_.pole_pairs; }
  bool feedback_wanted() const { return feedback_wanted_; }
  bool drive_command_held() const { return owner_ != Owner::kNone; }

  // ---- Connections and time ----
  // Call from cip::ConnectionEvents::OnConnectionsChanged (every open and close, timeouts included):
  // an output point that changed hands starts again from zero levels (edge tracker) and an empty
  // parameter channel; FA06/FA07 held by a connection that is gone are given back and Run1/Run2 drop
  // to 0, so that a later command needs a new Run edge. Nothing is written to the drive.
  void OnConnectionsChanged();
  // Starts due parameter accesses, ends the feedback hold, refreshes the supervisor.
  void Poll(hal::Micros now);
  // A parameter access to retry, or the end of the feedback hold; hal::kNever otherwise.
  hal::Micros NextDeadline() const;

 private:
  enum class Owner : std::uint8_t { kNone, kConnection, kExplicit };
  enum class Source : std::uint8_t { kAttributes, kNative };

  // The parameter channel of one output instance (101 answers in 151, 105 in 155).
  struct ChannelSlot {
    ParameterChannel channel;
    drive_link::AccessToken token = drive_link::kNoAccess;  // the access on its way, if any
    hal::Micros retry_at = 0;                               // pool was full: not before this
    bool waiting_retry = false;
  };

  DriveContext Context() const;
  OutputEdgeTracker* TrackerOf(std::uint32_t instance);
  ChannelSlot* SlotOf(std::uint32_t instance);
  const ChannelSlot* SlotOf(std::uint32_t instance) const;
  bool ScannerTargetsDriveCommand() const;
  void Take(CommandOrigin origin, std::uint32_t instance);
  void Release();
  void EndExplicitHoldAfterCardReset();
  void HoldStopDuringLoss();
  SupervisorOutputs Step(bool fault_reset_event);
  void WriteDriveCommand();
  void ApplyCipSpeed(const DriveCommand& command, const OutputEvents& events);
  void ApplyNative(const DriveCommand& command, const OutputEvents& events);
  void ApplyScanner(const DriveCommand& command);
  void SendScannerWords(const CommandWrites& writes);
  bool ScannerOutputOwned() const;
  void ResetChannel(ChannelSlot& slot);
  void StartDueAccesses();
  void ComputeFeedback();
  void OnAccessDone(drive_link::AccessToken token, const drive_link::AccessResult& result) override;

  DriveProfileLinks links_;
  DriveProfileOptions options_;
  config::CardConfig config_;
  hal::Micros now_ = 0;  // of the last Poll

  ControlSupervisor supervisor_;
  // The command attributes (§4.6 3/4/5/12, §4.7 4/8); 20/21/101 packets set them too.
  bool run1_ = false;
  bool run2_ = false;
  bool net_ctrl_ = false;
  bool net_ref_ = false;
  bool fault_reset_attribute_ = false;
  std::int16_t speed_reference_rpm_ = 0;

  // FA06/FA07: who holds them, what they are made from, what was handed to the drive link.
  Owner owner_ = Owner::kNone;
  std::uint32_t owner_point_ = 0;
  Source source_ = Source::kAttributes;
  bool fault_reset_bit_ = false;                 // kAttributes: FA06 bit 13 of the last command event
  drive_link::DriveCommandWords native_words_;   // kNative: FA06/FA07 of the last 100 packet
  drive_link::DriveCommandWords written_;
  bool written_valid_ = false;
  // A connection's scanner words (100 of more than 2 words, 102, 105) are in the drive link: given back
  // when no such connection is open any more (OnConnectionsChanged).
  bool scanner_words_sent_ = false;

  // Per output instance (kOutputInstances order): edges, and whether a connection owned it last time.
  std::array<OutputEdgeTracker, kOutputInstances.size()> trackers_{};
  std::array<bool, kOutputInstances.size()> owned_{};
  // [0]: 101 (answered in 151), [1]: 105 (answered in 155).
  std::array<ChannelSlot, 2> channels_{};

  // Feedback.
  bool feedback_wanted_ = false;
  bool produced_since_poll_ = false;
  hal::Micros last_production_ = 0;
  DriveFeedback feedback_;
};

}  // namespace cip::drive
