#include "cip_connection_supervisor.h"

#include <cstdint>

#include "cip/connection_manager.h"

namespace firmware {

bool CipConnectionSupervisor::Controls(const cip::ConnectionInfo& connection) {
  return connection.transport_class == 3 ||
         (connection.transport_class == 1 && connection.kind == cip::IoConnectionKind::kExclusiveOwner);
}

void CipConnectionSupervisor::OnConnectionTimedOut(const cip::ConnectionInfo& connection) {
  if (!Controls(connection)) return;
  ++counters_.timeouts;
  Lose();
}

void CipConnectionSupervisor::OnConnectionClosed(const cip::ConnectionInfo& connection, cip::CloseReason reason) {
  const bool owner = connection.transport_class == 1 && connection.kind == cip::IoConnectionKind::kExclusiveOwner;
  if (owner && reason == cip::CloseReason::kForwardClose) {
    ++counters_.owner_closes;
    Lose();
  }
}

void CipConnectionSupervisor::OnRunIdleChanged(const cip::ConnectionInfo& connection, bool run) {
  if (!run && Controls(connection)) {
    ++counters_.idle_transitions;
    Lose();
    return;
  }
  OnConnectionsChanged();
}

void CipConnectionSupervisor::OnConnectionsChanged() {
  if (lost_ && Healthy()) {
    lost_ = false;
    ++counters_.restores;
    loss_.NetworkRestored(clock_.NowMicros());
  }
  if (listener_ != nullptr) listener_->OnConnectionsChanged();
}

void CipConnectionSupervisor::Lose() {
  if (listener_ != nullptr) listener_->OnDriveControlLost();
  if (lost_) return;
  lost_ = true;
  ++counters_.losses;
  loss_.NetworkLost(drive_link::LossCause::kCipConnection, clock_.NowMicros());
}

bool CipConnectionSupervisor::Healthy() const {
  std::array<cip::ConnectionInfo, cip::kMaxCipConnections> open{};
  const std::size_t count = table_.ListConnections(open);
  bool owner_open = false;
  bool owner_running = false;
  bool explicit_open = false;
  for (std::size_t i = 0; i < count; ++i) {
    const cip::ConnectionInfo& connection = open[i];
    if (connection.transport_class == 3) explicit_open = true;
    if (connection.transport_class == 1 && connection.kind == cip::IoConnectionKind::kExclusiveOwner) {
      owner_open = true;
      owner_running = owner_running || connection.run;
    }
  }
  return owner_open ? owner_running : explicit_open;
}

}  // namespace firmware
