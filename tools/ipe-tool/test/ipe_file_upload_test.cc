// tools/ipe eds: the whole File object upload against a fake card that answers per CIP Vol. 1 §5A-42.
#include <gtest/gtest.h>

#include "eip_codec.h"
#include "failure.h"
#include "file_transfer.h"

namespace ipe {
namespace {

using B = std::vector<std::uint8_t>;

// Serves `file` in packets of at most `chunk` bytes; the packet with the last byte is a last packet.
struct FakeFileInstance {
  FakeFileInstance(B bytes, std::uint8_t packet) : file(std::move(bytes)), chunk(packet) {}

  B file;
  std::uint8_t chunk = 0;
  std::size_t sent = 0;
  std::vector<std::uint8_t> numbers_asked;
  // Damage, for the refusal tests.
  bool corrupt_checksum = false;
  bool abort_second = false;
  bool wrong_number = false;
  bool never_last = false;
  std::uint8_t refuse_initiate = 0;

  CipReply operator()(std::uint8_t service, std::span<const std::uint8_t> data) {
    CipReply reply;
    reply.service = static_cast<std::uint8_t>(service | 0x80);
    if (service == kServiceInitiateUpload) {
      if (refuse_initiate != 0) {
        reply.general = refuse_initiate;
        return reply;
      }
      chunk = std::min<std::uint8_t>(chunk, data[0]);
      const auto size = static_cast<std::uint32_t>(file.size());
      reply.data = {static_cast<std::uint8_t>(size), static_cast<std::uint8_t>(size >> 8),
                    static_cast<std::uint8_t>(size >> 16), static_cast<std::uint8_t>(size >> 24), chunk};
      return reply;
    }
    const std::uint8_t number = data[0];
    numbers_asked.push_back(number);
    const std::size_t count = std::min<std::size_t>(chunk, file.size() - sent);
    const bool first = sent == 0;
    const bool last = !never_last && sent + count == file.size();
    std::uint8_t type = first ? (last ? 4 : 0) : (last ? 2 : 1);
    if (abort_second && !first) type = 3;
    reply.data = {static_cast<std::uint8_t>(wrong_number && !first ? number + 1 : number), type};
    reply.data.insert(reply.data.end(), file.begin() + static_cast<std::ptrdiff_t>(sent),
                      file.begin() + static_cast<std::ptrdiff_t>(sent + count));
    sent += count;
    if (last) {
      const std::uint16_t sum = static_cast<std::uint16_t>(FileChecksum(file) + (corrupt_checksum ? 1 : 0));
      reply.data.push_back(static_cast<std::uint8_t>(sum));
      reply.data.push_back(static_cast<std::uint8_t>(sum >> 8));
    }
    return reply;
  }
};

B Text(std::size_t size) {
  B bytes(size);
  for (std::size_t i = 0; i < size; ++i) bytes[i] = static_cast<std::uint8_t>('A' + i % 26);
  return bytes;
}

UploadResult Upload(FakeFileInstance& card, std::uint8_t max = 255) {
  return UploadFile([&card](std::uint8_t s, std::span<const std::uint8_t> d) { return card(s, d); }, max);
}

TEST(IpeFileUpload, ManyPacketsInOrder) {
  FakeFileInstance card(Text(600), 200);
  const UploadResult result = Upload(card);
  EXPECT_EQ(result.exit_code, kExitOk) << result.error;
  EXPECT_EQ(result.content, Text(600));
  EXPECT_EQ(card.numbers_asked, (std::vector<std::uint8_t>{0, 1, 2}));
}

TEST(IpeFileUpload, OnePacketFirstAndLast) {
  FakeFileInstance card(Text(20), 200);
  const UploadResult result = Upload(card);
  EXPECT_EQ(result.exit_code, kExitOk) << result.error;
  EXPECT_EQ(result.content, Text(20));
}

TEST(IpeFileUpload, TransferNumbersWrapAt256AndTheMaximumIsAsked) {
  FakeFileInstance card(Text(300), 200);
  const UploadResult result = Upload(card, 1);  // the card takes the smaller size: 1 byte a packet
  EXPECT_EQ(result.exit_code, kExitOk) << result.error;
  EXPECT_EQ(result.content, Text(300));
  ASSERT_EQ(card.numbers_asked.size(), 300u);
  EXPECT_EQ(card.numbers_asked[255], 255);
  EXPECT_EQ(card.numbers_asked[256], 0);
  EXPECT_EQ(card.numbers_asked[299], 43);
}

TEST(IpeFileUpload, Refusals) {
  FakeFileInstance missing(Text(10), 200);
  missing.refuse_initiate = 0x05;
  UploadResult result = Upload(missing);
  EXPECT_EQ(result.exit_code, kExitRefused);
  EXPECT_EQ(result.error, "Initiate_Upload refused by the card: general status 0x05 (path destination unknown)");

  FakeFileInstance checksum(Text(600), 200);
  checksum.corrupt_checksum = true;
  result = Upload(checksum);
  EXPECT_EQ(result.exit_code, kExitUnreachable);
  EXPECT_EQ(result.error, "checksum mismatch");
  EXPECT_TRUE(result.content.empty());

  FakeFileInstance aborted(Text(600), 200);
  aborted.abort_second = true;
  result = Upload(aborted);
  EXPECT_EQ(result.exit_code, kExitRefused);
  EXPECT_EQ(result.error, "the card aborted the transfer");

  FakeFileInstance skipped(Text(600), 200);
  skipped.wrong_number = true;
  result = Upload(skipped);
  EXPECT_EQ(result.exit_code, kExitUnreachable);
  EXPECT_EQ(result.error, "Upload_Transfer 1 answered as 2");

  FakeFileInstance endless(Text(400), 200);
  endless.never_last = true;  // then empty middle packets forever: bounded by the announced size
  result = Upload(endless);
  EXPECT_EQ(result.exit_code, kExitUnreachable);
  EXPECT_EQ(result.error, "more packets than the announced file size allows");
  EXPECT_EQ(endless.numbers_asked.size(), 3u);
}

}  // namespace
}  // namespace ipe
