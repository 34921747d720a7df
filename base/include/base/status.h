// Status and Result: error values instead of exceptions, for every layer.
//
// A Status is one byte. Codes follow the canonical meanings so that a caller can decide what to do
// without knowing the callee: kUnavailable = try again later (nothing wrong), kOutOfRange = input
// shorter/longer than its format allows, kResourceExhausted = a fixed pool or buffer is full,
// kDataLoss = stored or received data failed its integrity check.
#pragma once

#include <cstdint>
#include <utility>

namespace base {

enum class StatusCode : std::uint8_t {
  kOk = 0,
  kUnavailable,         // nothing to do now (no frame, no byte); try later
  kInvalidArgument,     // the caller passed something the callee cannot accept
  kOutOfRange,          // a length or index outside what the format or buffer allows
  kResourceExhausted,   // a fixed-size pool or buffer is full
  kNotFound,            // no such record, port, object
  kDataLoss,            // corrupt or truncated data (checksum, CRC, short read)
  kFailedPrecondition,  // the system is not in a state where this is allowed
  kPermissionDenied,    // the OS or a policy refused
  kInternal,            // an invariant broke; a bug or an OS failure
};

class [[nodiscard]] Status {
 public:
  constexpr Status() = default;
  constexpr explicit Status(StatusCode code) : code_(code) {}

  constexpr bool ok() const { return code_ == StatusCode::kOk; }
  constexpr StatusCode code() const { return code_; }
  constexpr bool operator==(const Status&) const = default;
  // Explicitly discard a status whose failure is not actionable at this call site.
  constexpr void IgnoreError() const {}

 private:
  StatusCode code_ = StatusCode::kOk;
};

constexpr Status OkStatus() { return Status(); }
constexpr Status Unavailable() { return Status(StatusCode::kUnavailable); }
constexpr Status InvalidArgument() { return Status(StatusCode::kInvalidArgument); }
constexpr Status OutOfRange() { return Status(StatusCode::kOutOfRange); }
constexpr Status ResourceExhausted() { return Status(StatusCode::kResourceExhausted); }
constexpr Status NotFound() { return Status(StatusCode::kNotFound); }
constexpr Status DataLoss() { return Status(StatusCode::kDataLoss); }
constexpr Status FailedPrecondition() { return Status(StatusCode::kFailedPrecondition); }
constexpr Status PermissionDenied() { return Status(StatusCode::kPermissionDenied); }
constexpr Status Internal() { return Status(StatusCode::kInternal); }

const char* StatusName(Status status);

// Value or error. T must be default-constructible (all our payloads are small PODs), which keeps this
// free of placement-new tricks.
//
// A Result is either a value or a failure, never "OK without a value": a Result built from an OK
// Status holds kInternal instead (a bug at the call site, e.g. `return status;` on a path that forgot
// to check it). It is turned into an error rather than refused at compile time because the status is
// usually a run-time value; this way the caller sees a failure and never a default-constructed T
// passing for a real one (DEVELOPERS.md: never a success answer for something that did not happen).
template <typename T>
class [[nodiscard]] Result {
 public:
  constexpr Result(T value) : value_(std::move(value)) {}  // NOLINT: implicit by design
  constexpr Result(Status status)                          // NOLINT: implicit by design
      : status_(status.ok() ? Status(StatusCode::kInternal) : status) {}

  constexpr bool ok() const { return status_.ok(); }
  constexpr Status status() const { return status_; }
  // Only meaningful when ok(); otherwise a default-constructed T.
  constexpr const T& value() const { return value_; }
  constexpr T& value() { return value_; }
  constexpr const T* operator->() const { return &value_; }
  constexpr const T& operator*() const { return value_; }

 private:
  T value_{};
  Status status_;
};

}  // namespace base
