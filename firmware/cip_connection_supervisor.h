// What the card does when its CIP connections come and go (docs/ethernetip.md "Connection loss"):
// the bridge from cip::ConnectionEvents to the drive link's LossSupervision (c100 delay, c103
// condition, c101 action) and to whoever else must know (the drive assemblies, the LEDs).
//
// A connection *controls the drive* when it is a class 1 exclusive owner (it consumes an output
// assembly) or a class 3 connection (explicit messages may write commands). The network counts as
// lost (NetworkLost, LossCause::kCipConnection) when
//   - a controlling connection's watchdog runs out (seed 000 §3.2.3: RPI x 4 x 2^multiplier, then c100),
//   - an exclusive owner is closed by Forward_Close (the PLC stopped controlling: the drive must not
//     keep running on the last command unless c101 = 1 says so), or
//   - an exclusive owner's O->T data turns idle (PLC in program mode).
// Closing a class 3 connection normally is not a loss (a PLC opens and closes them for messages).
// The network is restored (NetworkRestored) once the connections are healthy again: an exclusive owner
// in run mode, or, when no exclusive owner is open, an open class 3 connection.
// Unconnected messages never count (§3.2.3: "time-out is not operating").
#pragma once

#include <array>
#include <cstddef>

#include "cip/io_connection.h"
#include "drive_link/register_access.h"
#include "hal/clock.h"

namespace firmware {

// Told when the drive stops being controlled over a connection (timeout, close, idle), so the
// assemblies forget edge and parameter-channel state; and when connections change at all.
class DriveControlListener {
 public:
  virtual ~DriveControlListener() = default;
  virtual void OnDriveControlLost() = 0;
  virtual void OnConnectionsChanged() = 0;
};

struct CipLossCounters {
  std::uint32_t timeouts = 0;         // controlling connections whose watchdog ran out
  std::uint32_t owner_closes = 0;     // exclusive owners closed by Forward_Close
  std::uint32_t idle_transitions = 0; // exclusive owners turning idle
  std::uint32_t losses = 0;           // NetworkLost reports
  std::uint32_t restores = 0;         // NetworkRestored reports
};

class CipConnectionSupervisor final : public cip::ConnectionEvents {
 public:
  CipConnectionSupervisor(const cip::ConnectionTable& table, drive_link::LossSupervision& loss,
                          const hal::Clock& clock)
      : table_(table), loss_(loss), clock_(clock) {}

  void set_listener(DriveControlListener* listener) { listener_ = listener; }

  void OnConnectionTimedOut(const cip::ConnectionInfo& connection) override;
  void OnRunIdleChanged(const cip::ConnectionInfo& connection, bool run) override;
  void OnConnectionsChanged() override;
  void OnConnectionClosed(const cip::ConnectionInfo& connection, cip::CloseReason reason) override;

  bool lost() const { return lost_; }
  const CipLossCounters& counters() const { return counters_; }

 private:
  static bool Controls(const cip::ConnectionInfo& connection);
  void Lose();
  bool Healthy() const;

  const cip::ConnectionTable& table_;
  drive_link::LossSupervision& loss_;
  const hal::Clock& clock_;
  DriveControlListener* listener_ = nullptr;
  bool lost_ = false;
  CipLossCounters counters_;
};

}  // namespace firmware
