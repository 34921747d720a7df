// CardQos: the QoS values in the card's NV record 0x0011; stored at once, in force from the next start.
#include "card_qos.h"

#include <gtest/gtest.h>

#include <vector>

#include "memory_nv_store.h"

namespace firmware {
namespace {

using hal::test::MemoryNvStore;

cip::QosSettings Explicit10Scheduled20() {
  cip::QosSettings settings;
  settings.values = {1, 59, 47, 55, 20, 43, 31, 10};
  return settings;
}

TEST(CardQos, NoRecord_TheSpecificationsDefaults) {
  MemoryNvStore store;
  const CardQos qos(store);
  EXPECT_EQ(qos.StoredQos(), cip::QosSettings{});
  EXPECT_EQ(qos.active(), cip::QosSettings{});
  EXPECT_EQ(qos.active().values, (std::array<std::uint8_t, 8>{0, 59, 47, 55, 47, 43, 31, 27}));
}

TEST(CardQos, StoredAtOnceInForceFromTheNextStart) {
  MemoryNvStore store;
  CardQos qos(store);
  ASSERT_TRUE(qos.StoreQos(Explicit10Scheduled20()).ok());
  EXPECT_EQ(store.records.at(kNvQos), (std::vector<std::uint8_t>{1, 1, 59, 47, 55, 20, 43, 31, 10}));
  EXPECT_EQ(qos.StoredQos(), Explicit10Scheduled20());
  EXPECT_EQ(qos.active(), cip::QosSettings{});  // until the reset
  const CardQos restarted(store);
  EXPECT_EQ(restarted.StoredQos(), Explicit10Scheduled20());
  EXPECT_EQ(restarted.active(), Explicit10Scheduled20());
}

TEST(CardQos, UnchangedValuesAreNotWrittenAgain) {
  MemoryNvStore store;
  CardQos qos(store);
  ASSERT_TRUE(qos.StoreQos(cip::QosSettings{}).ok());
  EXPECT_EQ(store.records.count(kNvQos), 0U);
}

TEST(CardQos, OutOfRangeRefusedAsInvalidArgument) {
  MemoryNvStore store;
  CardQos qos(store);
  cip::QosSettings settings;
  settings.values[7] = 64;
  EXPECT_EQ(qos.StoreQos(settings).code(), base::StatusCode::kInvalidArgument);
  settings = {};
  settings.values[0] = 2;
  EXPECT_EQ(qos.StoreQos(settings).code(), base::StatusCode::kInvalidArgument);
  EXPECT_TRUE(store.records.empty());
}

TEST(CardQos, StoreFailure_ReturnedAndTheOldValuesKept) {
  MemoryNvStore store;
  CardQos qos(store);
  store.write_status = base::Internal();
  EXPECT_EQ(qos.StoreQos(Explicit10Scheduled20()).code(), base::StatusCode::kInternal);
  EXPECT_EQ(qos.StoredQos(), cip::QosSettings{});
}

TEST(CardQos, RecordOfAnotherVersionLengthOrRange_Defaults) {
  for (const std::vector<std::uint8_t>& record : std::vector<std::vector<std::uint8_t>>{
           {2, 1, 59, 47, 55, 20, 43, 31, 10},      // version 2
           {1, 1, 59, 47, 55, 20, 43, 31},          // cut short
           {1, 1, 59, 47, 55, 20, 43, 31, 10, 0},   // too long
           {1, 1, 59, 47, 55, 20, 43, 31, 64},      // DSCP 64
           {1, 2, 59, 47, 55, 20, 43, 31, 10}}) {   // tag enable 2
    MemoryNvStore store;
    store.records[kNvQos] = record;
    EXPECT_EQ(CardQos(store).active(), cip::QosSettings{});
  }
}

}  // namespace
}  // namespace firmware
