// base::PoolWatermark: the high-water mark and refusal count kept beside a fixed pool.
#include "base/pool_stats.h"

#include <gtest/gtest.h>

namespace base {
namespace {

TEST(PoolWatermarkTest, FreshPoolReportsOnlyWhatIsUsed) {
  const PoolWatermark marks;
  EXPECT_EQ(marks.Stats(0, 8), (PoolStats{0, 8, 0, 0}));
  // A pool whose slots were filled without NoteTaken (none of ours) still never reports a high-water
  // mark below its use.
  EXPECT_EQ(marks.Stats(3, 8), (PoolStats{3, 8, 3, 0}));
}

TEST(PoolWatermarkTest, HighWaterKeepsTheMostAndRefusalsCount) {
  PoolWatermark marks;
  marks.NoteTaken(1);
  marks.NoteTaken(2);
  marks.NoteTaken(1);  // one was given back meanwhile
  marks.NoteRefused();
  marks.NoteRefused();
  EXPECT_EQ(marks.Stats(1, 2), (PoolStats{1, 2, 2, 2}));
  EXPECT_EQ(marks.Stats(0, 2), (PoolStats{0, 2, 2, 2}));
}

}  // namespace
}  // namespace base
