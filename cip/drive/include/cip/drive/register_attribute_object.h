// CIP objects whose attributes live in the inverter: the Parameter objects 0x64/0x65 and Motor Data
// 0x28 (docs/drive-objects.md). The attribute tables, class attributes and the checks before a value
// is touched (0x14, 0x15, 0x0E, 0x13) are cip::AttributeObject's; what this adds is the register access
// behind a getter or setter, through the DriveAccessJournal, and its outcome as a CIP status.
//
// AttributeHandler's getters cannot fail, yet a register read can pend or fail. So a handler derives
// from RegisterAttributeHandler and reads with ReadRegister, which records the outcome of the service;
// RegisterAttributeObject wraps the AttributeObject and answers that outcome instead of the success
// AttributeObject reports after a getter. A getter that got no value writes nothing: an error reply
// carries no data, and a pending request's reply is never sent.
#pragma once

#include <cstdint>
#include <optional>

#include "cip/cip_status.h"
#include "cip/drive/drive_access_journal.h"
#include "cip/object_model.h"
#include "drive_link/register_access.h"

namespace cip::drive {

// CIP Vol. 1 Appendix B 0x1F: the journal saw a handler repeat a request differently (a bug).
inline constexpr GeneralStatus kVendorSpecificError = static_cast<GeneralStatus>(0x1F);

// What a register the inverter does not have (AccessError::kNoSuchRegister) is to the requester.
enum class MissingRegister : std::uint8_t {
  kNoSuchInstance,   // 0x64/0x65: the instance IS the register -> 0x16 object does not exist
  kNoSuchAttribute,  // 0x28: the instance exists, the attribute's register does not -> 0x14
};

enum class AccessKind : std::uint8_t { kGet, kSet };

// The CIP status of a completed access (docs/drive-objects.md "Access errors"). No extended status:
// the general codes already separate what an originator can act on.
constexpr ServiceStatus AccessErrorStatus(drive_link::AccessError error, AccessKind kind, MissingRegister missing) {
  using drive_link::AccessError;
  switch (error) {
    case AccessError::kNone:
      return Success();
    case AccessError::kNoSuchRegister:
      return Error(missing == MissingRegister::kNoSuchInstance ? GeneralStatus::kObjectDoesNotExist
                                                               : GeneralStatus::kAttributeNotSupported);
    case AccessError::kOutOfRange:
      return Error(GeneralStatus::kInvalidAttributeValue);
    case AccessError::kNotWritableWhileRunning:  // the drive's state forbids it now: stop, then retry
    case AccessError::kReservedForScanner:       // owned by the cyclic exchange, as an assembly owned
                                                 // by an I/O connection is
    case AccessError::kLinkDown:                 // nothing reaches the inverter until the link is back
    case AccessError::kNetworkLost:              // the loss action owns FA06 until the network is back
      return Error(GeneralStatus::kDeviceStateConflict);
    case AccessError::kReadOnly:
      return Error(GeneralStatus::kAttributeNotSettable);
    case AccessError::kRefused:
      // The inverter's 0000/0003: for a Set, the drive did not store the value; a Get it refused is
      // a conflict with the object's (the parameter's) state.
      return Error(kind == AccessKind::kSet ? GeneralStatus::kStoreOperationFailure
                                            : GeneralStatus::kObjectStateConflict);
    case AccessError::kTimeout:  // the inverter did not answer this time: worth trying again
      return Error(GeneralStatus::kResourceUnavailable);
  }
  return Error(kVendorSpecificError);
}

// The CIP status of an access the journal refused (JournalAnswer::refusal).
constexpr ServiceStatus RefusalStatus(base::StatusCode refusal) {
  switch (refusal) {
    case base::StatusCode::kResourceExhausted:  // proxy pool or journal full: try again
      return Error(GeneralStatus::kResourceUnavailable);
    case base::StatusCode::kFailedPrecondition:  // link down: as AccessError::kLinkDown
      return AccessErrorStatus(drive_link::AccessError::kLinkDown, AccessKind::kGet,
                               MissingRegister::kNoSuchInstance);
    default:
      return Error(kVendorSpecificError);
  }
}

// What a service returns while its access is on the way. The server never sends it (context.pending
// makes it keep the request); were it sent (a server without a lifecycle), "resource unavailable" is
// the truthful answer.
inline constexpr ServiceStatus kPendingStatus = Error(GeneralStatus::kResourceUnavailable);

class RegisterAttributeHandler : public AttributeHandler {
 public:
  RegisterAttributeHandler(DriveAccessJournal& journal, MissingRegister missing)
      : journal_(journal), missing_(missing) {}

  // Called by RegisterAttributeObject around each service.
  void BeginService(RequestContext* context) {
    context_ = context;
    outcome_ = Success();
    pending_ = false;
  }
  const ServiceStatus& outcome() const { return outcome_; }

 protected:
  // The register's value, or nothing when the service cannot answer now: outcome() then says why
  // (pending, refused, or the access's error). After an outcome other than pending, no further access
  // is started in this service (its answer is decided).
  std::optional<std::uint16_t> ReadRegister(std::uint16_t number);
  // Writes and returns the outcome so far (Success once the inverter took the value).
  ServiceStatus WriteRegister(std::uint16_t number, std::uint16_t value, drive_link::WriteMode mode);

 private:
  bool Decided() const { return !outcome_.ok() && !pending_; }
  void Record(const JournalAnswer& answer, AccessKind kind);

  DriveAccessJournal& journal_;
  MissingRegister missing_;
  RequestContext* context_ = nullptr;
  ServiceStatus outcome_;
  bool pending_ = false;
};

// The CipObject of a RegisterAttributeHandler.
class RegisterAttributeObject final : public CipObject {
 public:
  RegisterAttributeObject(const ClassSpec& spec, RegisterAttributeHandler& handler)
      : handler_(handler), attributes_(spec, handler) {}

  std::uint16_t class_id() const override { return attributes_.class_id(); }
  bool HasInstance(std::uint32_t instance) const override { return attributes_.HasInstance(instance); }
  bool SupportsService(std::uint32_t instance, std::uint8_t service) const override {
    return attributes_.SupportsService(instance, service);
  }
  ServiceStatus Execute(const ServiceRequest& request, base::ByteWriter& reply) override;

 private:
  RegisterAttributeHandler& handler_;
  AttributeObject attributes_;
};

}  // namespace cip::drive
