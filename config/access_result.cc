// AccessErrorName: the names the card's reports and logs give the access errors.
#include "config/access_result.h"

namespace config {

const char* AccessErrorName(AccessError error) {
  switch (error) {
    case AccessError::kNone:
      return "none";
    case AccessError::kNoSuchRegister:
      return "no-such-register";
    case AccessError::kOutOfRange:
      return "out-of-range";
    case AccessError::kNotWritableWhileRunning:
      return "not-writable-while-running";
    case AccessError::kReadOnly:
      return "read-only";
    case AccessError::kReservedForScanner:
      return "reserved-for-scanner";
    case AccessError::kRefused:
      return "refused";
    case AccessError::kLinkDown:
      return "link-down";
    case AccessError::kTimeout:
      return "timeout";
    case AccessError::kNetworkLost:
      return "network-lost";
  }
  return "?";
}

}  // namespace config
