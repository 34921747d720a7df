// The Control Supervisor's run/stop logic (object 0x29, seed 000 §4.6; docs/drive-profile.md "Control
// Supervisor"): the Run/Stop event matrix of §4.6.1 and the states of §4.6.2, as pure classes.
//
// - RunStopMatrix turns the levels Run1/Run2 (attributes 3/4, or Run Fwd/Run Rev of assemblies 20/21/101)
//   into the run type the drive must carry out: Stop, Run1 (forward) or Run2 (reverse). Run acts on an
//   edge: a level held through a fault or a "not ready" phase does not start the drive again.
// - ControlSupervisor follows the drive: its state comes from FD01 (tripped, standby, running, ST/RUN on)
//   and the drive link; the run type is only in force in Ready/Enabled/Stopping; a FaultRst edge asks for
//   one fault reset (FA06 bit 13) while the drive is tripped.
#pragma once

#include <cstdint>

namespace cip::drive {

// FD01 bits drive_registers.h's status_bit does not name (seed 000 §3.2.4.7).
inline constexpr std::uint16_t kFd01Undervoltage = 1u << 3;  // moff; "-" in 150
inline constexpr std::uint16_t kFd01Reverse = 1u << 9;       // 0 forward, 1 reverse
inline constexpr std::uint16_t kFd01Reserved = 1u << 15;     // undefined (reads 1 on a real S15: E404H)

// §4.6.2; attribute 6 and the "Drive Status" byte of 71/151. 0 (NonExistent) is never reported by a
// card that answers.
enum class SupervisorState : std::uint8_t {
  kNonExistent = 0,
  kStartup = 1,
  kNotReady = 2,
  kReady = 3,
  kEnabled = 4,
  kStopping = 5,
  kFaultStop = 6,
  kFaulted = 7,
};

const char* SupervisorStateName(SupervisorState state);

enum class RunType : std::uint8_t { kStop, kRun1, kRun2 };

// §4.6.1:
//   Run1    Run2    Trigger    Run type
//   0       0       Stop       -
//   0->1    0       Run        Run1
//   0       0->1    Run        Run2
//   0->1    0->1    none       (unchanged)
//   1       1       none       (unchanged)
//   1->0    1       Run        Run2
//   1       1->0    Run        Run1
// Levels without an edge (1/0 held, 0/1 held) keep the run type. A rising edge while the other level is
// held at 1 is the "1 1" row: no action.
class RunStopMatrix {
 public:
  RunType Update(bool run1, bool run2);
  // Forgets the run type (back to Stop) but keeps the levels: a held level needs a new edge.
  void StopKeepingLevels() { type_ = RunType::kStop; }
  // Levels and run type back to 0 / Stop (Reset service, connection opened): the next 1 is an edge.
  void Clear();
  RunType run_type() const { return type_; }

 private:
  bool run1_ = false;
  bool run2_ = false;
  RunType type_ = RunType::kStop;
};

// What the supervisor knows of the drive each step.
struct DriveStatus {
  // The drive link is up and FD01 below is fresh (configuration loaded, status read). False during the
  // card's start-up (state stays Startup) and after an option fault e-23 (state goes Faulted).
  bool known = false;
  std::uint16_t fd01 = 0;  // status word 1 (drive_registers.h status_bit)
};

struct SupervisorInputs {
  bool run1 = false;         // level: attribute 3, or Run Fwd of 20/21/101
  bool run2 = false;         // level: attribute 4, or Run Rev of 21/101
  bool fault_reset = false;  // one-shot: a 0->1 of FaultRst (attribute 12, or the assembly's bit) now
  DriveStatus drive;
};

struct SupervisorOutputs {
  SupervisorState state = SupervisorState::kStartup;
  RunType run = RunType::kStop;    // what FA06 must carry: bit 10 (Run1), bits 10 + 9 (Run2)
  bool send_fault_reset = false;   // write FA06 bit 13 once now
};

// The transitions, evaluated from the newest drive status (docs/drive-profile.md has the table):
//   Startup      -> NotReady   initialization complete (drive status known)
//   any          -> Faulted    drive link lost after start-up (option fault e-23)
//   Enabled/Stopping/FaultStop -> FaultStop   tripped while the output still runs (FD01 bits 1 + 10)
//   FaultStop    -> Faulted    fault stop complete (bit 10 clear)
//   other        -> Faulted    tripped (bit 1)
//   Faulted/FaultStop -> NotReady   fault reset (the trip is gone: bit 1 clear)
//   any          -> NotReady   main power off / not initialised (bit 14 clear)
//   NotReady     -> Ready      main power on (bit 14)
//   Ready/Stopping -> Enabled  run (bits 10 + 13: running with RUN on)
//   Enabled      -> Stopping   stop (bit 10 with bit 13 clear: decelerating)
//   Stopping     -> Ready      stop complete (bit 10 clear)
// Several transitions may follow each other in one step (Faulted -> NotReady -> Ready when the drive
// reports "standby" again after a reset); the result is the state the status settles in.
class ControlSupervisor {
 public:
  SupervisorOutputs Step(const SupervisorInputs& inputs);
  // The Reset service (0x05): back to Startup; the run type and the levels are forgotten.
  void Reset();
  void SwitchOff();  // NonExistent (power off); SwitchOn() or Reset() brings it back to Startup
  void SwitchOn();

  SupervisorState state() const { return state_; }
  RunType run_type() const { return matrix_.run_type(); }
  // Attributes 7-11 (§4.6): Running1/Running2 from the drive's direction while it runs (Enabled,
  // Stopping, FaultStop); Ready = Ready/Enabled/Stopping; Faulted = FaultStop/Faulted; Warning = FD01
  // bit 2 (alarm, not latched).
  bool running1() const;
  bool running2() const;
  bool ready() const;
  bool faulted() const;
  bool warning() const;

 private:
  SupervisorState Settle(const DriveStatus& drive) const;

  SupervisorState state_ = SupervisorState::kStartup;
  RunStopMatrix matrix_;
  std::uint16_t fd01_ = 0;
};

// Ready/Enabled/Stopping: the states in which a run command is carried out.
constexpr bool AcceptsRun(SupervisorState state) {
  return state == SupervisorState::kReady || state == SupervisorState::kEnabled ||
         state == SupervisorState::kStopping;
}

}  // namespace cip::drive
