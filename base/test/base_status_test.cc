// base::Status and base::Result: a Result holds a value or a failure, never "OK without a value".
#include "base/status.h"

#include <gtest/gtest.h>

#include <cstdint>

namespace base {
namespace {

TEST(Result, FromAValue_IsOkAndHoldsIt) {
  const Result<std::uint16_t> result(std::uint16_t{0x1234});
  ASSERT_TRUE(result.ok());
  EXPECT_EQ(result.status(), OkStatus());
  EXPECT_EQ(*result, 0x1234);
}

TEST(Result, FromAnError_KeepsThatError) {
  const Result<std::uint16_t> result(OutOfRange());
  EXPECT_FALSE(result.ok());
  EXPECT_EQ(result.status(), OutOfRange());
}

TEST(Result, FromAnOkStatus_IsAnInternalError) {
  const Result<std::uint16_t> result(OkStatus());
  EXPECT_FALSE(result.ok());
  EXPECT_EQ(result.status(), Internal());
  EXPECT_STREQ(StatusName(result.status()), "INTERNAL");

  // The same at compile time, and through the implicit conversion a `return status;` uses.
  static_assert(!Result<int>(OkStatus()).ok());
  static_assert(Result<int>(OkStatus()).status().code() == StatusCode::kInternal);
  const auto forwarded = [](Status status) -> Result<int> { return status; };
  EXPECT_EQ(forwarded(OkStatus()).status(), Internal());
  EXPECT_EQ(forwarded(DataLoss()).status(), DataLoss());
}

}  // namespace
}  // namespace base
