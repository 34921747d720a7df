// Reset of the card (Identity object Reset service, web "restart", power-cycle on the host).
//
// Contract: RequestReset() only records the request and returns. The event loop performs it after the
// current pass, so that a reply already queued (for example the Identity Reset response) is sent first.
#pragma once

#include <cstdint>

namespace hal {

enum class ResetKind : std::uint8_t {
  kRestart = 0,          // like a power cycle of the card (Identity Reset type 0)
  kFactoryDefaults = 1,  // erase the card's own store, then restart (Identity Reset type 1)
};

class ResetControl {
 public:
  virtual ~ResetControl() = default;
  virtual void RequestReset(ResetKind kind) = 0;
};

}  // namespace hal
