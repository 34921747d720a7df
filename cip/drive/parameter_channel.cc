// The parameter channel of 101/151 and 105/155: one access per distinct request (parameter_channel.h).
#include "cip/drive/parameter_channel.h"

namespace cip::drive {

void ParameterChannel::Offer(const ParameterRequest& request) {
  if (!request.present) return;
  if (seen_ && request == last_) return;
  last_ = request;
  seen_ = true;
  if (in_flight_) superseded_ = true;
  if (!request.valid) {
    // Answered at once: no access can make sense of an unknown function code.
    due_ = false;
    response_ = ParameterResponse{};
    response_.present = true;
    response_.write = request.write;
    response_.error = true;
    response_.cause = drive_link::AccessError::kRefused;
    response_.number = request.number;
    return;
  }
  due_ = true;
}

bool ParameterChannel::TakeDue(ParameterRequest& request) {
  if (!due_ || in_flight_) return false;
  due_ = false;
  in_flight_ = true;
  superseded_ = false;
  started_ = last_;
  request = started_;
  return true;
}

void ParameterChannel::Complete(const drive_link::AccessResult& result) {
  if (!in_flight_) return;
  in_flight_ = false;
  if (superseded_) return;  // the newer request (due, or already answered) owns the response
  response_ = ParameterResponse{};
  response_.present = true;
  response_.write = started_.write;
  response_.number = started_.number;
  if (result.ok()) {
    response_.value = result.value;
  } else {
    response_.error = true;
    response_.cause = result.error;
  }
}

void ParameterChannel::Retry() {
  if (!in_flight_) return;
  in_flight_ = false;
  if (!superseded_) due_ = true;
}

void ParameterChannel::Reset() { *this = ParameterChannel{}; }

}  // namespace cip::drive
