// Control Supervisor run/stop logic: §4.6.1 event matrix, §4.6.2 states (control_supervisor.h).
#include "cip/drive/control_supervisor.h"

#include "drive_link/drive_registers.h"

namespace cip::drive {

namespace status_bit = drive_link::reg::status_bit;

const char* SupervisorStateName(SupervisorState state) {
  switch (state) {
    case SupervisorState::kNonExistent:
      return "NonExistent";
    case SupervisorState::kStartup:
      return "Startup";
    case SupervisorState::kNotReady:
      return "NotReady";
    case SupervisorState::kReady:
      return "Ready";
    case SupervisorState::kEnabled:
      return "Enabled";
    case SupervisorState::kStopping:
      return "Stopping";
    case SupervisorState::kFaultStop:
      return "FaultStop";
    case SupervisorState::kFaulted:
      return "Faulted";
  }
  return "?";
}

RunType RunStopMatrix::Update(bool run1, bool run2) {
  const bool rise1 = run1 && !run1_;
  const bool rise2 = run2 && !run2_;
  const bool fall1 = !run1 && run1_;
  const bool fall2 = !run2 && run2_;
  if (!run1 && !run2) {
    type_ = RunType::kStop;  // "0 0: Stop"
  } else if (run1 && run2) {
    // "0->1 0->1" and "1 1": no action. Also a rising edge while the other level is held at 1.
  } else if (run1) {  // run1 = 1, run2 = 0
    // "0->1 0: Run1" and "1 1->0: Run1". Held 1/0 without an edge keeps the run type.
    if (rise1 || fall2) type_ = RunType::kRun1;
  } else {  // run1 = 0, run2 = 1
    if (rise2 || fall1) type_ = RunType::kRun2;
  }
  run1_ = run1;
  run2_ = run2;
  return type_;
}

void RunStopMatrix::Clear() { *this = RunStopMatrix{}; }

SupervisorState ControlSupervisor::Settle(const DriveStatus& drive) const {
  SupervisorState state = state_;
  if (state == SupervisorState::kNonExistent) return state;
  if (!drive.known) {
    // Start-up: initialization is not complete until the drive is known. Later: the drive link is lost
    // (option fault e-23): a fault detected.
    return state == SupervisorState::kStartup ? state : SupervisorState::kFaulted;
  }
  const bool tripped = (drive.fd01 & status_bit::kTripped) != 0;
  const bool standby = (drive.fd01 & status_bit::kReady) != 0;
  const bool running = (drive.fd01 & status_bit::kRunning) != 0;
  const bool run_on = (drive.fd01 & status_bit::kReadyStRun) != 0;
  if (state == SupervisorState::kStartup) state = SupervisorState::kNotReady;  // initialization complete
  if (tripped) {
    const bool was_moving = state == SupervisorState::kEnabled || state == SupervisorState::kStopping ||
                            state == SupervisorState::kFaultStop;
    return was_moving && running ? SupervisorState::kFaultStop : SupervisorState::kFaulted;
  }
  // Not tripped: a fault state has been reset (Faulted/FaultStop -> NotReady).
  if (!standby) return SupervisorState::kNotReady;  // main power off / not initialised
  if (!running) return SupervisorState::kReady;     // main power on, stop complete
  if (run_on) return SupervisorState::kEnabled;     // run
  return SupervisorState::kStopping;                // stop: decelerating with RUN off
}

SupervisorOutputs ControlSupervisor::Step(const SupervisorInputs& inputs) {
  state_ = Settle(inputs.drive);
  if (inputs.drive.known) fd01_ = inputs.drive.fd01;
  matrix_.Update(inputs.run1, inputs.run2);
  // A run is carried out only where the state machine has a Run transition; elsewhere (fault, not
  // ready, start-up) it is dropped and a held level needs a new edge.
  if (!AcceptsRun(state_)) matrix_.StopKeepingLevels();
  SupervisorOutputs out;
  out.state = state_;
  out.run = matrix_.run_type();
  out.send_fault_reset =
      inputs.fault_reset && (state_ == SupervisorState::kFaulted || state_ == SupervisorState::kFaultStop) &&
      inputs.drive.known;
  return out;
}

void ControlSupervisor::Reset() {
  state_ = SupervisorState::kStartup;
  matrix_.Clear();
  fd01_ = 0;
}

void ControlSupervisor::SwitchOff() {
  Reset();
  state_ = SupervisorState::kNonExistent;
}

void ControlSupervisor::SwitchOn() { Reset(); }

bool ControlSupervisor::running1() const {
  const bool moving = state_ == SupervisorState::kEnabled || state_ == SupervisorState::kStopping ||
                      state_ == SupervisorState::kFaultStop;
  return moving && (fd01_ & status_bit::kRunning) != 0 && (fd01_ & kFd01Reverse) == 0;
}

bool ControlSupervisor::running2() const {
  const bool moving = state_ == SupervisorState::kEnabled || state_ == SupervisorState::kStopping ||
                      state_ == SupervisorState::kFaultStop;
  return moving && (fd01_ & status_bit::kRunning) != 0 && (fd01_ & kFd01Reverse) != 0;
}

bool ControlSupervisor::ready() const { return AcceptsRun(state_); }

bool ControlSupervisor::faulted() const {
  return state_ == SupervisorState::kFaultStop || state_ == SupervisorState::kFaulted;
}

bool ControlSupervisor::warning() const {
  return state_ != SupervisorState::kStartup && state_ != SupervisorState::kNonExistent &&
         (fd01_ & status_bit::kAlarm) != 0;
}

}  // namespace cip::drive
