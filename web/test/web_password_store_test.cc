// The web passwords: text limits, exact PBKDF2 records, the NV layout byte by byte, refusal of every
// truncation and of bad versions, flags and iteration counts, and the store's load / set / fall-back
// behaviour on a memory NV store (docs/web.md "Passwords and sessions (implementation)").
#include "web/password_store.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "web_fakes.h"

namespace web {
namespace {

constexpr hal::NvRecordId kId = 0x0020;

std::string Hex(std::span<const std::uint8_t> bytes) {
  static constexpr char kDigits[] = "0123456789abcdef";
  std::string text;
  for (std::uint8_t byte : bytes) {
    text += kDigits[byte >> 4];
    text += kDigits[byte & 0x0F];
  }
  return text;
}

std::array<std::uint8_t, kPasswordSaltBytes> CountingSalt(std::uint8_t first) {
  std::array<std::uint8_t, kPasswordSaltBytes> salt{};
  for (std::size_t i = 0; i < salt.size(); ++i) salt[i] = static_cast<std::uint8_t>(first + i);
  return salt;
}

// PBKDF2-HMAC-SHA256("USER", 00..0f, 4096) and ("USER", 10..1f, 4096), computed independently.
constexpr std::string_view kUserHashSalt00 = "342f5946add9e1a5511b3abe4a51642fa27c8a9ac70771746a215967d965f24f";
constexpr std::string_view kUserHashSalt10 = "ca4790f2a856ad84b0cb66ea89fd49784e4690b2f6b69e877bd6bd8fbcf17c9c";

TEST(PasswordTextTest, Limits) {
  EXPECT_EQ(CheckPasswordText(""), base::OutOfRange());
  EXPECT_TRUE(CheckPasswordText("x").ok());
  EXPECT_TRUE(CheckPasswordText(std::string(32, 'x')).ok());
  EXPECT_EQ(CheckPasswordText(std::string(33, 'x')), base::OutOfRange());
  for (int c = 0x20; c <= 0x7E; ++c) EXPECT_TRUE(CheckPasswordText(std::string(1, static_cast<char>(c))).ok()) << c;
  for (int c : {0x00, 0x09, 0x0A, 0x1F, 0x7F, 0x80, 0xC3, 0xFF}) {
    EXPECT_EQ(CheckPasswordText("ab" + std::string(1, static_cast<char>(c))), base::InvalidArgument()) << c;
  }
}

TEST(PasswordRecordTest, HashOfTheDefaultIsExact) {
  const base::Result<PasswordRecord> record = HashPassword("USER", CountingSalt(0x00));
  ASSERT_TRUE(record.ok());
  EXPECT_EQ(record->iterations, 4096U);
  EXPECT_TRUE(record->is_default);
  EXPECT_EQ(record->salt, CountingSalt(0x00));
  EXPECT_EQ(Hex(record->hash), kUserHashSalt00);
  const base::Result<PasswordRecord> one = HashPassword("USER", CountingSalt(0x00), 1);
  ASSERT_TRUE(one.ok());
  EXPECT_EQ(Hex(one->hash), "7118f3a7a50b3a708e61a11572cd621a26f7794828480a96901e093003886a9f");
}

TEST(PasswordRecordTest, OnlyUserExactlyIsTheDefault) {
  EXPECT_FALSE(HashPassword("user", CountingSalt(0), 1)->is_default);
  EXPECT_FALSE(HashPassword("USER ", CountingSalt(0), 1)->is_default);
  EXPECT_FALSE(HashPassword("USERS", CountingSalt(0), 1)->is_default);
}

TEST(PasswordRecordTest, RefusedTextAndIterations) {
  EXPECT_EQ(HashPassword("", CountingSalt(0)).status(), base::OutOfRange());
  EXPECT_EQ(HashPassword("a\nb", CountingSalt(0)).status(), base::InvalidArgument());
  EXPECT_EQ(HashPassword("abc", CountingSalt(0), 0).status(), base::InvalidArgument());
  EXPECT_EQ(HashPassword("abc", CountingSalt(0), kMaxPasswordIterations + 1).status(), base::InvalidArgument());
  EXPECT_TRUE(HashPassword("abc", CountingSalt(0), kMaxPasswordIterations).ok());
}

TEST(PasswordRecordTest, VerifyMatchesOnlyTheSamePassword) {
  const PasswordRecord record = *HashPassword("Secret 1~", CountingSalt(7), 16);
  EXPECT_TRUE(VerifyPassword(record, "Secret 1~"));
  EXPECT_FALSE(VerifyPassword(record, "Secret 1"));
  EXPECT_FALSE(VerifyPassword(record, "secret 1~"));
  EXPECT_FALSE(VerifyPassword(record, "Secret 1~ "));
  EXPECT_FALSE(VerifyPassword(record, ""));
  PasswordRecord other_salt = record;
  other_salt.salt[0] ^= 1;
  EXPECT_FALSE(VerifyPassword(other_salt, "Secret 1~"));
  PasswordRecord other_count = record;
  other_count.iterations = 17;
  EXPECT_FALSE(VerifyPassword(other_count, "Secret 1~"));
  EXPECT_FALSE(VerifyPassword(PasswordRecord{}, "Secret 1~"));  // never set
}

PasswordRecords TwoRecords() {
  PasswordRecords records{};
  records[0] = *HashPassword("USER", CountingSalt(0x00), 4096);
  records[1] = *HashPassword("writer", CountingSalt(0x10), 0x2345);
  return records;
}

TEST(PasswordNvTest, LayoutIsExact) {
  const PasswordRecords records = TwoRecords();
  std::array<std::uint8_t, kPasswordNvBytes> bytes{};
  EncodePasswordRecords(records, bytes);
  ASSERT_EQ(bytes.size(), 107U);
  EXPECT_EQ(bytes[0], 0x01);
  // Read password: flags, iterations 4096 little-endian, salt, hash.
  EXPECT_EQ(bytes[1], 0x01);
  EXPECT_EQ(Hex(std::span(bytes).subspan(2, 4)), "00100000");
  EXPECT_EQ(Hex(std::span(bytes).subspan(6, 16)), "000102030405060708090a0b0c0d0e0f");
  EXPECT_EQ(Hex(std::span(bytes).subspan(22, 32)), kUserHashSalt00);
  // Write password: not the default, 0x2345 iterations.
  EXPECT_EQ(bytes[54], 0x00);
  EXPECT_EQ(Hex(std::span(bytes).subspan(55, 4)), "45230000");
  EXPECT_EQ(Hex(std::span(bytes).subspan(59, 16)), "101112131415161718191a1b1c1d1e1f");
  EXPECT_EQ(Hex(std::span(bytes).subspan(75, 32)), Hex(records[1].hash));
}

TEST(PasswordNvTest, RoundTrip) {
  const PasswordRecords records = TwoRecords();
  std::array<std::uint8_t, kPasswordNvBytes> bytes{};
  EncodePasswordRecords(records, bytes);
  const base::Result<PasswordRecords> parsed = ParsePasswordRecords(bytes);
  ASSERT_TRUE(parsed.ok());
  EXPECT_EQ(*parsed, records);
}

TEST(PasswordNvTest, EveryOtherLengthIsRefused) {
  std::array<std::uint8_t, kPasswordNvBytes + 2> bytes{};
  EncodePasswordRecords(TwoRecords(), std::span(bytes).first<kPasswordNvBytes>());
  for (std::size_t length = 0; length < kPasswordNvBytes; ++length) {
    EXPECT_EQ(ParsePasswordRecords(std::span(bytes).first(length)).status(), base::OutOfRange()) << length;
  }
  EXPECT_TRUE(ParsePasswordRecords(std::span(bytes).first(kPasswordNvBytes)).ok());
  EXPECT_EQ(ParsePasswordRecords(std::span(bytes).first(kPasswordNvBytes + 1)).status(), base::OutOfRange());
  EXPECT_EQ(ParsePasswordRecords(bytes).status(), base::OutOfRange());
}

TEST(PasswordNvTest, BadVersionFlagsAndIterationsAreRefused) {
  std::array<std::uint8_t, kPasswordNvBytes> good{};
  EncodePasswordRecords(TwoRecords(), good);
  auto refused = [&good](std::size_t offset, std::uint8_t value) {
    std::array<std::uint8_t, kPasswordNvBytes> bytes = good;
    bytes[offset] = value;
    return ParsePasswordRecords(bytes).status();
  };
  EXPECT_EQ(refused(0, 0x00), base::DataLoss());
  EXPECT_EQ(refused(0, 0x02), base::DataLoss());
  for (std::size_t flags : {std::size_t{1}, std::size_t{54}}) {
    EXPECT_EQ(refused(flags, 0x02), base::DataLoss()) << flags;
    EXPECT_EQ(refused(flags, 0x81), base::DataLoss()) << flags;
    EXPECT_TRUE(refused(flags, 0x00).ok()) << flags;
    EXPECT_TRUE(refused(flags, 0x01).ok()) << flags;
  }
  auto with_iterations = [&good](std::size_t offset, std::uint32_t iterations) {
    std::array<std::uint8_t, kPasswordNvBytes> bytes = good;
    for (std::size_t i = 0; i < 4; ++i) bytes[offset + i] = static_cast<std::uint8_t>(iterations >> (8 * i));
    return ParsePasswordRecords(bytes).status();
  };
  for (std::size_t offset : {std::size_t{2}, std::size_t{55}}) {
    EXPECT_EQ(with_iterations(offset, 0), base::DataLoss()) << offset;
    EXPECT_TRUE(with_iterations(offset, 1).ok()) << offset;
    EXPECT_TRUE(with_iterations(offset, 65536).ok()) << offset;
    EXPECT_EQ(with_iterations(offset, 65537), base::DataLoss()) << offset;
    EXPECT_EQ(with_iterations(offset, 0x80000000), base::DataLoss()) << offset;
  }
}

class PasswordStoreTest : public ::testing::Test {
 protected:
  PasswordRecords StoredRecords() {
    const base::Result<PasswordRecords> parsed = ParsePasswordRecords(nv_.records[kId]);
    EXPECT_TRUE(parsed.ok());
    return *parsed;
  }

  test::CountingRandom random_;
  test::MemoryNvStore nv_;
  PasswordStore store_{nv_, kId, random_};
};

TEST_F(PasswordStoreTest, NothingMatchesBeforeLoad) {
  EXPECT_FALSE(store_.Verify(PasswordKind::kRead, "USER"));
  EXPECT_FALSE(store_.defaults());
}

TEST_F(PasswordStoreTest, FirstStartWritesTheDefaultsWithFreshSalts) {
  const base::Result<PasswordSource> loaded = store_.Load();
  ASSERT_TRUE(loaded.ok());
  EXPECT_EQ(*loaded, PasswordSource::kDefaults);
  EXPECT_EQ(nv_.writes, 1);
  ASSERT_EQ(nv_.records[kId].size(), kPasswordNvBytes);
  const PasswordRecords stored = StoredRecords();
  EXPECT_EQ(stored[0].salt, CountingSalt(0x00));
  EXPECT_EQ(Hex(stored[0].hash), kUserHashSalt00);
  EXPECT_EQ(stored[1].salt, CountingSalt(0x10));
  EXPECT_EQ(Hex(stored[1].hash), kUserHashSalt10);
  EXPECT_TRUE(stored[0].is_default && stored[1].is_default);
  EXPECT_EQ(stored[0].iterations, kPasswordIterations);
  EXPECT_TRUE(store_.Verify(PasswordKind::kRead, "USER"));
  EXPECT_TRUE(store_.Verify(PasswordKind::kWrite, "USER"));
  EXPECT_FALSE(store_.Verify(PasswordKind::kRead, "user"));
  EXPECT_TRUE(store_.defaults());
}

TEST_F(PasswordStoreTest, StoredRecordIsUsedAndNotRewritten) {
  PasswordRecords records{};
  records[0] = *HashPassword("reader", CountingSalt(0x40), 8);
  records[1] = *HashPassword("writer", CountingSalt(0x50), 9);
  std::array<std::uint8_t, kPasswordNvBytes> bytes{};
  EncodePasswordRecords(records, bytes);
  nv_.records[kId].assign(bytes.begin(), bytes.end());
  const base::Result<PasswordSource> loaded = store_.Load();
  ASSERT_TRUE(loaded.ok());
  EXPECT_EQ(*loaded, PasswordSource::kStored);
  EXPECT_EQ(nv_.writes, 0);
  EXPECT_TRUE(store_.Verify(PasswordKind::kRead, "reader"));
  EXPECT_FALSE(store_.Verify(PasswordKind::kRead, "writer"));
  EXPECT_TRUE(store_.Verify(PasswordKind::kWrite, "writer"));
  EXPECT_FALSE(store_.Verify(PasswordKind::kWrite, "USER"));
  EXPECT_FALSE(store_.defaults());
}

TEST_F(PasswordStoreTest, UnusableRecordsFallBackToTheDefaults) {
  std::array<std::uint8_t, kPasswordNvBytes> good{};
  EncodePasswordRecords(TwoRecords(), good);
  const std::vector<std::vector<std::uint8_t>> damaged = {
      std::vector<std::uint8_t>(good.begin(), good.end() - 1),
      [&good] {
        std::vector<std::uint8_t> longer(good.begin(), good.end());
        longer.push_back(0);
        return longer;
      }(),
      std::vector<std::uint8_t>(kPasswordNvBytes + 40, 0x01),
      {},
  };
  for (const std::vector<std::uint8_t>& record : damaged) {
    test::CountingRandom random;
    test::MemoryNvStore nv;
    nv.records[kId] = record;
    PasswordStore store(nv, kId, random);
    const base::Result<PasswordSource> loaded = store.Load();
    ASSERT_TRUE(loaded.ok()) << record.size();
    EXPECT_EQ(*loaded, PasswordSource::kDefaults) << record.size();
    EXPECT_EQ(nv.records[kId].size(), kPasswordNvBytes);
    EXPECT_TRUE(store.Verify(PasswordKind::kWrite, "USER"));
  }
}

TEST_F(PasswordStoreTest, ReadErrorFallsBackToTheDefaults) {
  nv_.read_status = base::DataLoss();
  const base::Result<PasswordSource> loaded = store_.Load();
  ASSERT_TRUE(loaded.ok());
  EXPECT_EQ(*loaded, PasswordSource::kDefaults);
  EXPECT_TRUE(store_.Verify(PasswordKind::kRead, "USER"));
}

TEST_F(PasswordStoreTest, FailedWriteOfTheDefaultsIsReportedButTheyApply) {
  nv_.write_status = base::Internal();
  EXPECT_EQ(store_.Load().status(), base::Internal());
  EXPECT_TRUE(store_.Verify(PasswordKind::kRead, "USER"));
  EXPECT_TRUE(store_.defaults());
}

TEST_F(PasswordStoreTest, SetChangesOnePasswordAndPersistsIt) {
  ASSERT_TRUE(store_.Load().ok());
  ASSERT_TRUE(store_.Set(PasswordKind::kRead, "viewer!").ok());
  EXPECT_EQ(nv_.writes, 2);
  EXPECT_TRUE(store_.Verify(PasswordKind::kRead, "viewer!"));
  EXPECT_FALSE(store_.Verify(PasswordKind::kRead, "USER"));
  EXPECT_TRUE(store_.Verify(PasswordKind::kWrite, "USER"));
  EXPECT_TRUE(store_.defaults());  // the write password is still "USER"
  const PasswordRecords stored = StoredRecords();
  EXPECT_EQ(stored[0].salt, CountingSalt(0x20));  // a fresh salt
  EXPECT_FALSE(stored[0].is_default);
  EXPECT_EQ(Hex(stored[1].hash), kUserHashSalt10);  // untouched
  ASSERT_TRUE(store_.Set(PasswordKind::kWrite, "changer").ok());
  EXPECT_FALSE(store_.defaults());

  test::CountingRandom random;
  PasswordStore again(nv_, kId, random);
  ASSERT_EQ(*again.Load(), PasswordSource::kStored);
  EXPECT_TRUE(again.Verify(PasswordKind::kRead, "viewer!"));
  EXPECT_TRUE(again.Verify(PasswordKind::kWrite, "changer"));
  EXPECT_FALSE(again.defaults());
  ASSERT_TRUE(again.Set(PasswordKind::kWrite, "USER").ok());  // back to the factory password
  EXPECT_TRUE(again.defaults());
}

TEST_F(PasswordStoreTest, RefusedPasswordChangesNothing) {
  ASSERT_TRUE(store_.Load().ok());
  EXPECT_EQ(store_.Set(PasswordKind::kRead, ""), base::OutOfRange());
  EXPECT_EQ(store_.Set(PasswordKind::kRead, std::string(33, 'a')), base::OutOfRange());
  EXPECT_EQ(store_.Set(PasswordKind::kWrite, "tab\there"), base::InvalidArgument());
  EXPECT_EQ(store_.Set(PasswordKind::kWrite, "caf\xC3\xA9"), base::InvalidArgument());
  EXPECT_EQ(nv_.writes, 1);
  EXPECT_TRUE(store_.Verify(PasswordKind::kRead, "USER"));
  EXPECT_TRUE(store_.Verify(PasswordKind::kWrite, "USER"));
}

TEST_F(PasswordStoreTest, FailedWriteKeepsTheOldPassword) {
  ASSERT_TRUE(store_.Load().ok());
  nv_.write_status = base::Unavailable();
  EXPECT_EQ(store_.Set(PasswordKind::kRead, "newone"), base::Unavailable());
  EXPECT_TRUE(store_.Verify(PasswordKind::kRead, "USER"));
  EXPECT_FALSE(store_.Verify(PasswordKind::kRead, "newone"));
  EXPECT_EQ(Hex(StoredRecords()[0].hash), kUserHashSalt00);
}

}  // namespace
}  // namespace web
