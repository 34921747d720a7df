// drive_link::ConfigLoader (drive_link/include/drive_link/config_loader.h): the reads of a configuration
// load in their order, what a failed read leaves, F875-F879 validated, FD01 kept, an abandoned load.
#include "drive_link/config_loader.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <map>
#include <vector>

#include "drive_link_part_fakes.h"

namespace drive_link::test {
namespace {

TEST(DriveLinkConfigLoader, ReadsTheConfigNumbersThenF875ToF879ThenFd01) {
  ConfigLoader loader;
  EXPECT_FALSE(loader.loading());
  const std::vector<std::uint16_t> numbers = RunLoad(loader, FactoryReads());
  ASSERT_EQ(numbers.size(), 63U);
  EXPECT_EQ(numbers[0], 0xC001);
  EXPECT_EQ(numbers[56], 0x0856);  // f856, the last of config::kConfigNumbers
  EXPECT_EQ(numbers[57], 0x0875);
  EXPECT_EQ(numbers[61], 0x0879);
  EXPECT_EQ(numbers[62], 0xFD01);
  EXPECT_TRUE(loader.loaded());
  EXPECT_FALSE(loader.loading());
  EXPECT_EQ(loader.parsed().problems_total, 0U);
}

TEST(DriveLinkConfigLoader, TheLoadedValuesAreInForceOnlyWhenTheLoadEnds) {
  ConfigLoader loader;
  loader.Begin();
  OwnJob job;
  ASSERT_TRUE(loader.NextRead(job));
  EXPECT_EQ(job.kind, OwnJobKind::kConfigRead);
  EXPECT_EQ(job.index, 0);
  EXPECT_EQ(job.transaction.kind, TransactionKind::kRead);
  EXPECT_FALSE(loader.OnRead(0, OkCompletion(5)));  // c001 = 5 (FA50)
  EXPECT_EQ(loader.config().command_menus[0], 1);   // the factory default until the end
  RunLoad(loader, FactoryReads({{0xC001, 5}, {0xC100, 30}, {0x0875, 2}, {0xFD01, 0x6400}}));
  EXPECT_EQ(loader.config().command_menus[0], 5);
  EXPECT_EQ(loader.config().loss_delay_tenths, 30);
  EXPECT_EQ(loader.block_selections()[0], 2);
  EXPECT_TRUE(loader.drive_status_read().ok());
  EXPECT_EQ(loader.drive_status_read().number, 0xFD01);
  EXPECT_EQ(loader.drive_status_read().value, 0x6400);
}

TEST(DriveLinkConfigLoader, BlockSelectionAboveTenIsReportedAndNotUsed) {
  ConfigLoader loader;
  RunLoad(loader, FactoryReads({{0x0876, 11}}));
  EXPECT_EQ(loader.block_selections()[1], 0);
  ASSERT_EQ(loader.parsed().problem_count, 1U);
  EXPECT_EQ(loader.parsed().problems[0].number, 0x0876);
  EXPECT_EQ(loader.parsed().problems[0].value, 11);
  EXPECT_EQ(loader.parsed().problems[0].kind, config::ConfigProblem::Kind::kOutOfRange);
}

TEST(DriveLinkConfigLoader, FailedReadsBecomeProblemsWithTheirAccessError) {
  ConfigLoader loader;
  const std::map<std::uint16_t, std::uint16_t> factory = FactoryReads();
  loader.Begin();
  OwnJob job;
  std::uint8_t index = 0;
  while (loader.NextRead(job)) {
    index = job.index;
    const auto found = factory.find(job.transaction.comm_number);
    Completion completion = OkCompletion(found == factory.end() ? 0 : found->second);
    if (job.transaction.comm_number == 0xC101) completion = ErrorCompletion(wire::ErrorCode::kCommunicationNumberError);
    if (job.transaction.comm_number == 0x0877) completion = OutcomeCompletion(Outcome::kTimeout);
    if (job.transaction.comm_number == 0xC001) completion = ErrorCompletion(wire::ErrorCode::kChecksumError);
    if (loader.OnRead(job.index, completion)) break;
  }
  EXPECT_EQ(index, 62);
  EXPECT_EQ(loader.config().loss_action, 4);  // c101's factory default
  ASSERT_EQ(loader.parsed().problem_count, 3U);
  EXPECT_EQ(loader.parsed().problems[0].number, 0xC001);
  EXPECT_EQ(loader.parsed().problems[0].error, AccessError::kTimeout);
  EXPECT_EQ(loader.parsed().problems[1].number, 0xC101);
  EXPECT_EQ(loader.parsed().problems[1].error, AccessError::kNoSuchRegister);
  EXPECT_EQ(loader.parsed().problems[2].number, 0x0877);
  EXPECT_EQ(loader.parsed().problems[2].kind, config::ConfigProblem::Kind::kUnreadable);
  EXPECT_EQ(loader.parsed().problems[2].error, AccessError::kTimeout);
}

TEST(DriveLinkConfigLoader, LinkDownAndStaleCompletionsAreIgnored) {
  ConfigLoader loader;
  loader.Begin();
  EXPECT_FALSE(loader.OnRead(0, OutcomeCompletion(Outcome::kLinkDown)));
  OwnJob job;
  ASSERT_TRUE(loader.NextRead(job));
  EXPECT_EQ(job.index, 0);  // the read is asked again
  EXPECT_FALSE(loader.OnRead(1, OkCompletion(0)));  // not the read asked for
  ASSERT_TRUE(loader.NextRead(job));
  EXPECT_EQ(job.index, 0);
  loader.Abandon();  // e-23
  EXPECT_FALSE(loader.NextRead(job));
  EXPECT_FALSE(loader.OnRead(0, OkCompletion(1)));
  EXPECT_FALSE(loader.loaded());
}

}  // namespace
}  // namespace drive_link::test
