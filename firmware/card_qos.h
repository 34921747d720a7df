// The card's QoS values (cip::QosProvider for the QoS object 0x48): stored in the card's NV record
// kNvQos, in force from the next start (docs/network.md "QoS (DSCP)").
//
// The values read at construction, once per start of the firmware, are the active ones: the I/O service
// marks class 1 productions with them, the encapsulation service its TCP and UDP 44818 traffic, and the
// netif tags frames by them. A Set_Attribute_Single changes only the stored values, which Get reads back;
// an Identity Reset (or a power cycle) brings them into force, as it does for the TCP/IP settings.
//
// Record: version 1, then attributes 1-8 (one byte each). A record of another version or length, with
// a value out of range, or damaged (the store's check) leaves the specification's defaults.
#pragma once

#include "base/status.h"
#include "cip/providers.h"
#include "hal/nv_store.h"

namespace firmware {

inline constexpr hal::NvRecordId kNvQos = 0x0011;

class CardQos final : public cip::QosProvider {
 public:
  explicit CardQos(hal::NvStore& store);

  cip::QosSettings StoredQos() const override { return stored_; }
  base::Status StoreQos(const cip::QosSettings& settings) override;

  // The values in force since the start.
  const cip::QosSettings& active() const { return active_; }

 private:
  hal::NvStore& store_;
  cip::QosSettings stored_;
  cip::QosSettings active_;
};

}  // namespace firmware
