// A firmware::Service over any object with Poll(now) and NextDeadline(): lower layers (drive_link,
// modbus, cip) keep the same two functions without knowing the firmware's Service interface.
#pragma once

#include "event_loop.h"

namespace firmware {

template <typename Polled>
class PolledService final : public Service {
 public:
  explicit PolledService(Polled& polled) : polled_(polled) {}
  void Poll(hal::Micros now) override { polled_.Poll(now); }
  hal::Micros NextDeadline() const override { return polled_.NextDeadline(); }

 private:
  Polled& polled_;
};

}  // namespace firmware
