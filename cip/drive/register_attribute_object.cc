#include "cip/drive/register_attribute_object.h"

namespace cip::drive {

std::optional<std::uint16_t> RegisterAttributeHandler::ReadRegister(std::uint16_t number) {
  if (Decided()) return std::nullopt;
  if (context_ == nullptr) {
    // Only the message router calls objects, always with a context; without one nothing could be
    // deferred, so nothing is started.
    outcome_ = Error(GeneralStatus::kResourceUnavailable);
    return std::nullopt;
  }
  const JournalAnswer answer = journal_.Read(*context_, number);
  if (answer.state == JournalState::kDone && answer.result.ok()) return answer.result.value;
  Record(answer, AccessKind::kGet);
  return std::nullopt;
}

ServiceStatus RegisterAttributeHandler::WriteRegister(std::uint16_t number, std::uint16_t value,
                                                      drive_link::WriteMode mode) {
  if (Decided()) return outcome_;
  if (context_ == nullptr) {
    outcome_ = Error(GeneralStatus::kResourceUnavailable);
    return outcome_;
  }
  const JournalAnswer answer = journal_.Write(*context_, number, value, mode);
  if (!(answer.state == JournalState::kDone && answer.result.ok())) Record(answer, AccessKind::kSet);
  return outcome_;
}

void RegisterAttributeHandler::Record(const JournalAnswer& answer, AccessKind kind) {
  // While an access pends the request is executed again anyway, and the first failure in call order
  // is what that execution will answer; so pending outranks everything recorded in this pass.
  if (pending_) return;
  switch (answer.state) {
    case JournalState::kPending:
      pending_ = true;
      outcome_ = kPendingStatus;
      return;
    case JournalState::kRefused:
      if (outcome_.ok()) outcome_ = RefusalStatus(answer.refusal);
      return;
    case JournalState::kDone:
      if (outcome_.ok()) outcome_ = AccessErrorStatus(answer.result.error, kind, missing_);
      return;
  }
}

ServiceStatus RegisterAttributeObject::Execute(const ServiceRequest& request, base::ByteWriter& reply) {
  handler_.BeginService(request.context);
  const ServiceStatus status = attributes_.Execute(request, reply);
  // AttributeObject reports success after a getter; the getter's access may have said otherwise.
  if (status.ok() && !handler_.outcome().ok()) return handler_.outcome();
  return status;
}

}  // namespace cip::drive
