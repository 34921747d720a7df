// The drive profile at run time (drive_profile_runtime.h, docs/drive-profile.md "Runtime").
#include "cip/drive/drive_profile_runtime.h"

#include <algorithm>

#include "drive_link/drive_registers.h"
#include "drive_link/register_access.h"

namespace cip::drive {

namespace reg = drive_link::reg;

namespace {

// The assemblies whose packets carry FA06/FA07 (the others carry scanner words only).
constexpr std::array<std::uint16_t, 4> kCommandOutputs{kBasicSpeedOutput, kExtendedSpeedOutput, kNativeOutput,
                                                       kNativeParameterOutput};

constexpr bool NeedsDriveFeedback(std::uint32_t input_instance) {
  return input_instance == kBasicSpeedInput || input_instance == kExtendedSpeedInput ||
         input_instance == kNativeInput || input_instance == kNativeParameterInput;
}

// The parameter channel an output or input instance uses; 2 (none) for instances without one.
constexpr std::size_t ChannelIndex(std::uint32_t instance) {
  if (instance == kNativeParameterOutput || instance == kNativeParameterInput) return 0;
  if (instance == kToshibaOutput || instance == kToshibaInput) return 1;
  return 2;
}

std::size_t OutputIndex(std::uint32_t instance) {
  for (std::size_t i = 0; i < kOutputInstances.size(); ++i) {
    if (kOutputInstances[i] == instance) return i;
  }
  return kOutputInstances.size();
}

}  // namespace

DriveProfileRuntime::DriveProfileRuntime(const DriveProfileLinks& links, const DriveProfileOptions& options)
    : links_(links), options_(options) {}

DriveProfileRuntime::~DriveProfileRuntime() { links_.registers.Cancel(*this); }

void DriveProfileRuntime::SetCardConfig(const config::CardConfig& config) { config_ = config; }

// ---- Commands ------------------------------------------------------------------------------------------

bool DriveProfileRuntime::ApplyOutput(std::uint32_t instance, std::span<const std::uint8_t> data,
                                      CommandOrigin origin) {
  EndExplicitHoldAfterCardReset();
  DriveCommand command;
  if (!DecodeOutput(instance, data, command)) return false;
  OutputEdgeTracker* tracker = TrackerOf(instance);
  const OutputEvents events = tracker != nullptr ? tracker->Track(command) : OutputEvents{};
  switch (command.profile) {
    case CommandProfile::kCipSpeed:
      Take(origin, instance);
      ApplyCipSpeed(command, events);
      break;
    case CommandProfile::kNative:
      Take(origin, instance);
      ApplyNative(command, events);
      break;
    case CommandProfile::kScanner:
      // A connection's scanner words would be held off FA06/FA07 forever by an explicit command nobody
      // repeats: the connection wins (explicit control is refused while it is open, see
      // ExplicitControlAllowed).
      if (origin == CommandOrigin::kConnection && owner_ == Owner::kExplicit && ScannerTargetsDriveCommand()) {
        Release();
      }
      ApplyScanner(command);
      break;
    case CommandProfile::kNone:
      break;
  }
  if (origin == CommandOrigin::kExplicit) HoldStopDuringLoss();
  if (command.parameter.present) {
    if (ChannelSlot* slot = SlotOf(instance); slot != nullptr) {
      slot->channel.Offer(command.parameter);
      StartDueAccesses();
    }
  }
  ComputeFeedback();
  return true;
}

void DriveProfileRuntime::ApplyCipSpeed(const DriveCommand& command, const OutputEvents& events) {
  // 20/21/101 carry exactly the Control Supervisor's and the AC/DC Drive's command attributes.
  ApplyNetBits(command, net_ctrl_, net_ref_);
  run1_ = command.run_forward;
  run2_ = command.run_reverse;
  fault_reset_attribute_ = command.fault_reset;
  speed_reference_rpm_ = command.speed_reference_rpm;
  source_ = Source::kAttributes;
  fault_reset_bit_ = Step(events.fault_reset).send_fault_reset;
  WriteDriveCommand();
}

void DriveProfileRuntime::ApplyNative(const DriveCommand& command, const OutputEvents& events) {
  ApplyNetBits(command, net_ctrl_, net_ref_);
  source_ = Source::kNative;
  Step(events.fault_reset);  // the state only: 100 is FA06 itself, the run bits are the master's
  DriveContext context = Context();
  context.fault_reset = events.fault_reset;
  const CommandWrites writes = CommandRegisters(command, context);
  native_words_ = drive_link::DriveCommandWords{writes.fa06, writes.fa07};
  WriteDriveCommand();
  // A 100 of 2 words carries no scanner word, and words whose menu targets FA06/FA07 are left out:
  // an empty mask would stop the scanner words another connection (102/105) sends.
  SendScannerWords(writes);
}

void DriveProfileRuntime::ApplyScanner(const DriveCommand& command) {
  Step(false);
  WriteDriveCommand();  // an explicit hold just released is not written again
  SendScannerWords(CommandRegisters(command, Context()));
}

void DriveProfileRuntime::SendScannerWords(const CommandWrites& writes) {
  if (writes.scanner_mask == 0) return;
  links_.command.SetCommandWordsMasked(writes.scanner_words, writes.scanner_mask);
  scanner_words_sent_ = true;
}

bool DriveProfileRuntime::ScannerOutputOwned() const {
  return links_.ownership.IsOwned(kNativeOutput) || links_.ownership.IsOwned(kScannerOutput) ||
         links_.ownership.IsOwned(kToshibaOutput);
}

bool DriveProfileRuntime::ScannerTargetsDriveCommand() const {
  for (std::uint16_t menu : config_.command_menus) {
    const std::uint16_t target = config::CommandMenuTarget(menu);
    if (drive_link::IsDriveCommandRegister(target)) return true;
  }
  return false;
}

bool DriveProfileRuntime::CommandsDrive(std::uint32_t output) const {
  if (std::find(kCommandOutputs.begin(), kCommandOutputs.end(), output) != kCommandOutputs.end()) return true;
  // 102/105 write FA06/FA07 through a scanner word when a c00n menu targets them.
  return (output == kScannerOutput || output == kToshibaOutput) && ScannerTargetsDriveCommand();
}

bool DriveProfileRuntime::DriveCommandOwnedBesides(std::uint32_t output) const {
  if (!CommandsDrive(output)) return false;
  for (std::uint16_t point : kOutputInstances) {
    if (point != output && CommandsDrive(point) && links_.ownership.IsOwned(point)) return true;
  }
  return false;
}

bool DriveProfileRuntime::ExplicitControlAllowed() const {
  for (std::uint16_t point : kOutputInstances) {
    if (CommandsDrive(point) && links_.ownership.IsOwned(point)) return false;
  }
  return true;
}

bool DriveProfileRuntime::ExplicitWriteAllowed(std::uint32_t instance) const {
  if (std::find(kCommandOutputs.begin(), kCommandOutputs.end(), instance) != kCommandOutputs.end()) {
    return ExplicitControlAllowed();
  }
  if (instance == kScannerOutput || instance == kToshibaOutput) return !links_.ownership.IsOwned(instance);
  return true;
}

bool DriveProfileRuntime::ExplicitOutputHeldByLoss(std::uint32_t instance, std::span<const std::uint8_t> data) const {
  if (!links_.command.CommandsHeldByLoss()) return false;
  DriveCommand command;
  if (!DecodeOutput(instance, data, command)) return false;  // answered as an invalid size
  switch (command.profile) {
    case CommandProfile::kCipSpeed:
      return command.run_forward || command.run_reverse;
    case CommandProfile::kNative:
      return !reg::IsStopCommand(command.native_command);
    case CommandProfile::kScanner:
      return true;  // scanner words are not written while the action is in force
    case CommandProfile::kNone:
      break;
  }
  return false;
}

// An explicit stop taken while a loss holds the drive: the loss action writes it from now on instead of
// its own FA06 (c101 = 5 must not run the drive again after a user stopped it).
void DriveProfileRuntime::HoldStopDuringLoss() {
  if (owner_ == Owner::kExplicit && written_valid_ && links_.command.CommandsHeldByLoss()) {
    links_.command.HoldStopDuringLoss(written_.fa06);
  }
}

ServiceStatus DriveProfileRuntime::SetControl(ControlAttribute attribute, bool value) {
  EndExplicitHoldAfterCardReset();
  if (!ExplicitControlAllowed()) return Error(GeneralStatus::kDeviceStateConflict);
  // While a network loss holds the drive only a stop is taken: a run, a change of the control source
  // or a fault reset would be dropped or undone by the loss action (docs/drive-control.md).
  const bool stop = (attribute == ControlAttribute::kRun1 || attribute == ControlAttribute::kRun2) && !value;
  if (!stop && links_.command.CommandsHeldByLoss()) return Error(GeneralStatus::kDeviceStateConflict);
  // A run edge while the drive is tripped would be stored and dropped: Faulted needs FaultRst first
  // (seed 000 §4.6.3), so the answer says so instead of a success without a running drive.
  const bool run = (attribute == ControlAttribute::kRun1 || attribute == ControlAttribute::kRun2) && value;
  Step(false);
  const SupervisorState state = supervisor_.state();
  if (run && (state == SupervisorState::kFaulted || state == SupervisorState::kFaultStop)) {
    return Error(GeneralStatus::kDeviceStateConflict);
  }
  bool fault_reset_event = false;
  switch (attribute) {
    case ControlAttribute::kRun1:
      run1_ = value;
      break;
    case ControlAttribute::kRun2:
      run2_ = value;
      break;
    case ControlAttribute::kNetCtrl:
      net_ctrl_ = value;
      break;
    case ControlAttribute::kNetRef:
      net_ref_ = value;
      break;
    case ControlAttribute::kFaultReset:
      fault_reset_event = value && !fault_reset_attribute_;
      fault_reset_attribute_ = value;
      break;
  }
  Take(CommandOrigin::kExplicit, 0);
  source_ = Source::kAttributes;
  fault_reset_bit_ = Step(fault_reset_event).send_fault_reset;
  WriteDriveCommand();
  HoldStopDuringLoss();
  ComputeFeedback();
  return Success();
}

ServiceStatus DriveProfileRuntime::SetSpeedReference(std::int16_t rpm) {
  EndExplicitHoldAfterCardReset();
  if (!ExplicitControlAllowed() || links_.command.CommandsHeldByLoss()) {
    return Error(GeneralStatus::kDeviceStateConflict);
  }
  speed_reference_rpm_ = rpm;
  Take(CommandOrigin::kExplicit, 0);
  source_ = Source::kAttributes;
  fault_reset_bit_ = Step(false).send_fault_reset;
  WriteDriveCommand();
  ComputeFeedback();
  return Success();
}

ServiceStatus DriveProfileRuntime::ResetSupervisor() {
  EndExplicitHoldAfterCardReset();
  if (!ExplicitControlAllowed()) return Error(GeneralStatus::kDeviceStateConflict);
  supervisor_.Reset();
  run1_ = false;
  run2_ = false;
  fault_reset_attribute_ = false;
  fault_reset_bit_ = false;
  if (owner_ == Owner::kExplicit) source_ = Source::kAttributes;
  WriteDriveCommand();  // the run type is gone: FA06 without its run bits
  HoldStopDuringLoss();
  ComputeFeedback();
  return Success();
}

void DriveProfileRuntime::Take(CommandOrigin origin, std::uint32_t instance) {
  owner_ = origin == CommandOrigin::kConnection ? Owner::kConnection : Owner::kExplicit;
  owner_point_ = origin == CommandOrigin::kConnection ? instance : 0;
}

// A card reset (f899 = 1) gives the drive command back by itself (RegisterProxy::BeginLoad): the card
// starts afresh. An explicit command is nobody's to repeat, so its hold ends there (as a connection's
// does at its close) instead of being taken over again by the next refresh, which would keep FA06/FA07
// reserved for a master that is gone. A connection's next packet takes the command over again
// (WriteDriveCommand). Checked before anything else acts, so that a new command after the reset is taken
// afresh and not dropped.
void DriveProfileRuntime::EndExplicitHoldAfterCardReset() {
  if (owner_ == Owner::kExplicit && written_valid_ && !links_.command.drive_command_taken()) Release();
}

void DriveProfileRuntime::Release() {
  if (owner_ != Owner::kNone) links_.command.ReleaseDriveCommand();
  owner_ = Owner::kNone;
  owner_point_ = 0;
  source_ = Source::kAttributes;
  written_valid_ = false;
  // The master that set these is gone: the next command needs a new Run edge (a level left at 1 must
  // not start the drive when someone else takes over).
  run1_ = false;
  run2_ = false;
  fault_reset_attribute_ = false;
  fault_reset_bit_ = false;
}

DriveContext DriveProfileRuntime::Context() const {
  DriveContext context;
  context.pole_pairs = config_.pole_pairs;
  context.net_ctrl_attribute = net_ctrl_;
  context.net_ref_attribute = net_ref_;
  context.command_menus = config_.command_menus;
  return context;
}

SupervisorOutputs DriveProfileRuntime::Step(bool fault_reset_event) {
  SupervisorInputs inputs;
  inputs.run1 = run1_;
  inputs.run2 = run2_;
  inputs.fault_reset = fault_reset_event;
  inputs.drive = links_.status.CurrentDriveStatus();
  return supervisor_.Step(inputs);
}

void DriveProfileRuntime::WriteDriveCommand() {
  if (owner_ == Owner::kNone) return;
  drive_link::DriveCommandWords words = native_words_;
  if (source_ == Source::kAttributes) {
    DriveCommand command;
    command.profile = CommandProfile::kCipSpeed;
    command.speed_reference_rpm = speed_reference_rpm_;
    DriveContext context = Context();
    context.run = supervisor_.run_type();
    context.fault_reset = fault_reset_bit_;
    const CommandWrites writes = CommandRegisters(command, context);
    words = drive_link::DriveCommandWords{writes.fa06, writes.fa07};
  }
  // The drive link writes on change and refreshes by itself: hand over changes only, and again when it
  // gave the drive command back by itself (a card reset, f899 = 1: nothing is written until the next
  // SetDriveCommand takes it over afresh).
  if (written_valid_ && words == written_ && links_.command.drive_command_taken()) return;
  links_.command.SetDriveCommand(words);
  written_ = words;
  written_valid_ = true;
}

OutputEdgeTracker* DriveProfileRuntime::TrackerOf(std::uint32_t instance) {
  const std::size_t index = OutputIndex(instance);
  return index < trackers_.size() ? &trackers_[index] : nullptr;
}

DriveProfileRuntime::ChannelSlot* DriveProfileRuntime::SlotOf(std::uint32_t instance) {
  const std::size_t index = ChannelIndex(instance);
  return index < channels_.size() ? &channels_[index] : nullptr;
}

const DriveProfileRuntime::ChannelSlot* DriveProfileRuntime::SlotOf(std::uint32_t instance) const {
  const std::size_t index = ChannelIndex(instance);
  return index < channels_.size() ? &channels_[index] : nullptr;
}

// ---- Parameter channel -----------------------------------------------------------------------------------

void DriveProfileRuntime::ResetChannel(ChannelSlot& slot) {
  // The access on its way runs to its end in the proxy; its completion no longer matches the slot.
  slot.channel.Reset();
  slot.token = drive_link::kNoAccess;
  slot.waiting_retry = false;
}

void DriveProfileRuntime::StartDueAccesses() {
  for (ChannelSlot& slot : channels_) {
    if (slot.token != drive_link::kNoAccess) continue;
    if (slot.waiting_retry && now_ < slot.retry_at) continue;
    ParameterRequest request;
    if (!slot.channel.TakeDue(request)) continue;
    slot.waiting_retry = false;
    const base::Result<drive_link::AccessToken> token =
        request.write ? links_.registers.Write(request.number, request.data, kParameterWriteMode, *this)
                      : links_.registers.Read(request.number, *this);
    if (token.ok()) {
      slot.token = token.value();
    } else if (token.status().code() == base::StatusCode::kResourceExhausted) {
      slot.channel.Retry();
      slot.waiting_retry = true;
      slot.retry_at = now_ + options_.parameter_retry;
    } else {
      // kFailedPrecondition: the link is down (e-23), nothing was sent.
      drive_link::AccessResult result;
      result.error = drive_link::AccessError::kLinkDown;
      result.number = request.number;
      slot.channel.Complete(result);
    }
  }
}

void DriveProfileRuntime::OnAccessDone(drive_link::AccessToken token, const drive_link::AccessResult& result) {
  for (ChannelSlot& slot : channels_) {
    if (token == drive_link::kNoAccess || slot.token != token) continue;
    slot.token = drive_link::kNoAccess;
    slot.channel.Complete(result);
  }
  StartDueAccesses();  // a newer request may have been offered meanwhile
}

// ---- Status ----------------------------------------------------------------------------------------------

void DriveProfileRuntime::Refresh() {
  EndExplicitHoldAfterCardReset();
  Step(false);
  WriteDriveCommand();
  ComputeFeedback();
}

ControlSources DriveProfileRuntime::control_sources() const {
  const std::uint16_t fa06 = owner_ != Owner::kNone && written_valid_ ? written_.fa06 : 0;
  return ControlSourcesOf(fa06, config_.cmod, config_.fmod);
}

void DriveProfileRuntime::ComputeFeedback() {
  const DriveStatus status = links_.status.CurrentDriveStatus();
  const drive_link::DriveFeedbackWords words = links_.command.DriveFeedback();
  DriveMonitors monitors;
  monitors.fd01 = status.known ? status.fd01 : 0;
  monitors.fd00 = words.known ? words.fd00 : 0;
  monitors.fe02 = words.known ? words.fe02 : 0;
  FeedbackOptions options;
  options.pole_pairs = config_.pole_pairs;
  feedback_ = MakeFeedback(monitors, supervisor_.state(), control_sources(), options);
  // Until FD00/FE02 are read both are 0, which would look like "at reference"; and the three words
  // come from one exchange cycle, whose FD01 must show the drive running too (the supervisor follows the
  // newest FD01, which may be a cycle ahead of them).
  if (!words.known || (words.fd01 & drive_link::reg::status_bit::kRunning) == 0) feedback_.at_reference = false;
}

bool DriveProfileRuntime::FillInput(std::uint32_t instance, std::span<std::uint8_t> out) const {
  DriveFeedback feedback = feedback_;
  feedback.monitor_words = links_.scanner.MonitorWords();
  if (const ChannelSlot* slot = SlotOf(instance); slot != nullptr) feedback.parameter = slot->channel.response();
  return EncodeInput(instance, feedback, out);
}

void DriveProfileRuntime::NoteProduced(std::uint32_t instance) {
  if (!NeedsDriveFeedback(instance)) return;
  produced_since_poll_ = true;
  if (feedback_wanted_) return;
  feedback_wanted_ = true;
  last_production_ = now_;
  links_.command.SetFeedbackWanted(true);
}

// ---- Connections and time --------------------------------------------------------------------------------

void DriveProfileRuntime::OnConnectionsChanged() {
  for (std::size_t i = 0; i < kOutputInstances.size(); ++i) {
    const bool owned = links_.ownership.IsOwned(kOutputInstances[i]);
    if (owned == owned_[i]) continue;
    // Opened or closed: the new master's first packet counts from zero levels, and its parameter
    // channel starts empty (151/155 show zeros until it asks).
    owned_[i] = owned;
    trackers_[i].Reset();
    if (ChannelSlot* slot = SlotOf(kOutputInstances[i]); slot != nullptr) ResetChannel(*slot);
  }
  // The scanner words' master is gone (closed or timed out): its words must neither keep FA06/FA07
  // reserved nor be written again later (a ReleaseDriveCommand writes scanner words on FA06/FA07 at once):
  // an empty mask takes them out, writing nothing; the next master's words come back in at once.
  if (scanner_words_sent_ && !ScannerOutputOwned()) {
    links_.command.SetCommandWordsMasked(drive_link::ScannerWords{}, 0);
    scanner_words_sent_ = false;
  }
  if (owner_ == Owner::kConnection && !links_.ownership.IsOwned(owner_point_)) Release();
  ComputeFeedback();
}

void DriveProfileRuntime::Poll(hal::Micros now) {
  now_ = now;
  if (produced_since_poll_) {
    last_production_ = now;
    produced_since_poll_ = false;
  }
  if (feedback_wanted_ && now - last_production_ >= options_.feedback_hold) {
    feedback_wanted_ = false;
    links_.command.SetFeedbackWanted(false);
  }
  StartDueAccesses();
  Refresh();
}

hal::Micros DriveProfileRuntime::NextDeadline() const {
  hal::Micros deadline = hal::kNever;
  if (feedback_wanted_) deadline = last_production_ + options_.feedback_hold;
  for (const ChannelSlot& slot : channels_) {
    if (slot.waiting_retry && slot.token == drive_link::kNoAccess) deadline = std::min(deadline, slot.retry_at);
  }
  return deadline;
}

}  // namespace cip::drive
