// Control Supervisor object 0x29 (seed 000 §4.6; docs/drive-objects.md "Control Supervisor"): the
// run/stop commands and the drive's state, over DriveProfileRuntime (the same path as assemblies
// 20/21/101, so explicit messaging can run the drive when no I/O connection commands it).
//
//   class      1 revision 1, 2 max instance 1, 3 instances 1, 6 max class attribute 7,
//              7 max instance attribute 15; service Get_Attribute_Single 0x0E
//   instance 1 (services Reset 0x05, Get_Attribute_Single 0x0E, Set_Attribute_Single 0x10)
//     1  NumAttr     UINT       13                                     Get
//     2  AttrList    USINT[13]  1 2 3 4 5 6 7 8 9 10 11 12 15           Get
//     3  Run1        BOOL       run forward, acts on 0 -> 1 (§4.6.1)   Get/Set
//     4  Run2        BOOL       run reverse, acts on 0 -> 1             Get/Set
//     5  NetCtrl     BOOL       FA06 bit 15 command priority            Get/Set
//     6  State       USINT      §4.6.2 (1 Startup ... 7 Faulted)        Get
//     7  Running1    BOOL       running forward (Enabled/Stopping/FaultStop)  Get
//     8  Running2    BOOL       running reverse                         Get
//     9  Ready       BOOL       Ready, Enabled or Stopping              Get
//     10 Faulted     BOOL       FaultStop or Faulted (latched)          Get
//     11 Warning     BOOL       FD01 bit 2 alarm                        Get
//     12 FaultRst    BOOL       0 -> 1: one fault reset while tripped   Get/Set
//     15 CtrlFromNet BOOL       FA06 bit 15 written, or cmod = 4        Get
//
// A Set of 3, 4, 5 or 12 and the Reset service are refused with 0x10 (device state conflict) while an
// exclusive-owner connection consumes 20, 21, 100 or 101 (DriveProfileRuntime::ExplicitControlAllowed):
// the connection's master commands the drive. A BOOL other than 0/1 is 0x09. Reset puts the state
// machine back to Startup and Run1/Run2/FaultRst to 0 (the drive stops when explicit messaging was
// running it); it does not reset the inverter (FaultRst does, when tripped).
#pragma once

#include <cstdint>
#include <span>

#include "cip/drive/drive_profile_runtime.h"
#include "cip/object_model.h"

namespace cip::drive {

inline constexpr std::uint16_t kClassControlSupervisor = 0x29;

class ControlSupervisorObject final : public AttributeHandler {
 public:
  explicit ControlSupervisorObject(DriveProfileRuntime& runtime);
  ControlSupervisorObject(const ControlSupervisorObject&) = delete;
  ControlSupervisorObject& operator=(const ControlSupervisorObject&) = delete;

  CipObject& object() { return object_; }

  std::uint32_t MaxInstance() const override { return 1; }
  std::span<const AttributeSpec> InstanceAttributes(std::uint32_t instance) const override;
  void GetInstanceAttribute(std::uint32_t instance, std::uint16_t id, base::ByteWriter& out) override;
  ServiceStatus SetInstanceAttribute(std::uint32_t instance, std::uint16_t id, base::ByteReader& value) override;
  ServiceStatus ExecuteOther(const ServiceRequest& request, base::ByteWriter& reply) override;

 private:
  DriveProfileRuntime& runtime_;
  AttributeObject object_;
};

// Decodes a BOOL attribute value (exactly one byte, 0 or 1): 0x13/0x15 for the size, 0x09 otherwise.
ServiceStatus ReadExactBool(base::ByteReader& in, bool& value);

}  // namespace cip::drive
