// File object 0x37 (docs/file-object.md) and ByteSpanFile, through the message router of a CipDevice on
// fakes: every attribute with exact bytes, uploads of a 600-byte file in several transfers (the last with
// the checksum), a resend, out-of-sequence and unsolicited transfers, sessions and the idle limit.
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <vector>

#include "cip/byte_span_file.h"
#include "cip/file_object.h"
#include "cip_fakes.h"

namespace cip {
namespace {

using test::Bytes;
using test::Concat;
using test::Hex;

// 600 bytes of a known pattern: byte i is (7 i + 3) mod 256. Their sum is 0x26B4, the checksum 0xD94C.
std::vector<std::uint8_t> Pattern(std::size_t size) {
  std::vector<std::uint8_t> bytes(size);
  for (std::size_t i = 0; i < size; ++i) bytes[i] = static_cast<std::uint8_t>(i * 7 + 3);
  return bytes;
}
const std::vector<std::uint8_t> kFileBytes = Pattern(600);

Bytes Slice(std::size_t from, std::size_t count) {
  return Bytes(kFileBytes.begin() + static_cast<std::ptrdiff_t>(from),
               kFileBytes.begin() + static_cast<std::ptrdiff_t>(from + count));
}

const Bytes kInstancePath = Hex("20 37 24 C8");
Bytes Initiate(std::string_view data) { return Concat(Concat(Hex("4B 02"), kInstancePath), Hex(data)); }
Bytes Transfer(std::string_view data) { return Concat(Concat(Hex("4F 02"), kInstancePath), Hex(data)); }
Bytes GetAttribute(std::uint8_t id) { return Concat(Concat(Hex("0E 03"), kInstancePath), Bytes{0x30, id}); }

class CipFileObjectTest : public ::testing::Test {
 protected:
  CipFileObjectTest() { EXPECT_TRUE(card_.cip.objects().Register(file_object_.object()).ok()); }

  // A request on encapsulation session `session` at time `now`.
  Bytes Ask(const Bytes& request, std::uint32_t session = 1, hal::Micros now = 0) {
    std::vector<std::uint8_t> reply(kMaxEncapsulationData);
    RequestContext context;
    context.session_handle = session;
    context.now = now;
    reply.resize(card_.cip.router().HandleUnconnected(request, context, reply));
    return reply;
  }

  ByteSpanFile content_{kFileBytes};
  test::FakeCard card_;
  FileObject file_object_{ServedFile{&content_, "ipe002z.eds", 1, 2}};
};

TEST(ByteSpanFileTest, SizeChecksumAndReads) {
  constexpr std::array<std::uint8_t, 5> kBytes = {0x01, 0x02, 0x03, 0xFF, 0x10};
  const ByteSpanFile file(kBytes);
  EXPECT_EQ(file.Size(), 5u);
  // 1 + 2 + 3 + 255 + 16 = 0x0115; 0x10000 - 0x0115 = 0xFEEB.
  EXPECT_EQ(file.Checksum(), 0xFEEB);
  std::array<std::uint8_t, 3> out{};
  EXPECT_EQ(file.ReadAt(1, out), 3u);
  EXPECT_EQ(Bytes(out.begin(), out.end()), Hex("02 03 FF"));
  out = {};
  EXPECT_EQ(file.ReadAt(3, out), 2u);
  EXPECT_EQ(Bytes(out.begin(), out.end()), Hex("FF 10 00"));
  EXPECT_EQ(file.ReadAt(5, out), 0u);
  EXPECT_EQ(file.ReadAt(0xFFFFFFFF, out), 0u);
  EXPECT_EQ(file.ReadAt(0, std::span<std::uint8_t>()), 0u);
  EXPECT_EQ(ByteSpanFile(std::span<const std::uint8_t>()).Checksum(), 0x0000);
  EXPECT_EQ(ByteSpanFile(kFileBytes).Checksum(), 0xD94C);
}

TEST_F(CipFileObjectTest, InstanceAttributes) {
  EXPECT_EQ(Ask(GetAttribute(1)), Hex("8E 00 00 00 02"));
  EXPECT_EQ(Ask(GetAttribute(2)), Hex("8E 00 00 00 01 65 6E 67 DA 04 00 12"
                                      "45 44 53 20 61 6E 64 20 49 63 6F 6E 20 46 69 6C 65 73"));
  EXPECT_EQ(Ask(GetAttribute(3)), Hex("8E 00 00 00 01 00"));
  EXPECT_EQ(Ask(GetAttribute(4)), Hex("8E 00 00 00 01 65 6E 67 DA 04 00 0B 69 70 65 30 30 32 7A 2E 65 64 73"));
  EXPECT_EQ(Ask(GetAttribute(5)), Hex("8E 00 00 00 01 02"));
  EXPECT_EQ(Ask(GetAttribute(6)), Hex("8E 00 00 00 58 02 00 00"));
  EXPECT_EQ(Ask(GetAttribute(7)), Hex("8E 00 00 00 4C D9"));
  EXPECT_EQ(Ask(GetAttribute(8)), Hex("8E 00 00 00 FF"));
  EXPECT_EQ(Ask(GetAttribute(9)), Hex("8E 00 00 00 00"));
  EXPECT_EQ(Ask(GetAttribute(10)), Hex("8E 00 00 00 01"));
  EXPECT_EQ(Ask(GetAttribute(11)), Hex("8E 00 00 00 00"));
  EXPECT_EQ(Ask(GetAttribute(12)), Hex("8E 00 14 00"));
  EXPECT_EQ(Ask(Concat(GetAttribute(6), Hex("00"))), Hex("8E 00 15 00"));
  EXPECT_EQ(Ask(Concat(Hex("01 02"), kInstancePath)),
            Hex("81 00 00 00 | 02 | 01 65 6E 67 DA 04 00 12 45 44 53 20 61 6E 64 20 49 63 6F 6E 20 46 69 6C 65 73"
                "| 01 00 | 01 65 6E 67 DA 04 00 0B 69 70 65 30 30 32 7A 2E 65 64 73 | 01 02 | 58 02 00 00 | 4C D9"
                "| FF | 00 | 01 | 00"));
}

TEST_F(CipFileObjectTest, ClassAttributesAndDirectory) {
  EXPECT_EQ(Ask(Hex("0E 03 20 37 24 00 30 01")), Hex("8E 00 00 00 03 00"));
  EXPECT_EQ(Ask(Hex("0E 03 20 37 24 00 30 02")), Hex("8E 00 00 00 C8 00"));
  EXPECT_EQ(Ask(Hex("0E 03 20 37 24 00 30 03")), Hex("8E 00 00 00 01 00"));
  EXPECT_EQ(Ask(Hex("0E 03 20 37 24 00 30 06")), Hex("8E 00 00 00 20 00"));
  EXPECT_EQ(Ask(Hex("0E 03 20 37 24 00 30 07")), Hex("8E 00 00 00 0B 00"));
  EXPECT_EQ(Ask(Hex("0E 03 20 37 24 00 30 20")),
            Hex("8E 00 00 00 | C8 00 | 01 65 6E 67 DA 04 00 12 45 44 53 20 61 6E 64 20 49 63 6F 6E 20 46 69 6C 65 73"
                "| 01 65 6E 67 DA 04 00 0B 69 70 65 30 30 32 7A 2E 65 64 73"));
  EXPECT_EQ(Ask(Hex("0E 03 20 37 24 00 30 04")), Hex("8E 00 14 00"));
  // Only instance 0xC8 exists; the upload services are instance services.
  EXPECT_EQ(Ask(Hex("0E 03 20 37 24 01 30 01")), Hex("8E 00 16 00"));
  EXPECT_EQ(Ask(Hex("4B 02 20 37 24 00 64")), Hex("CB 00 08 00"));
  EXPECT_EQ(Ask(Concat(Concat(Hex("10 03"), kInstancePath), Hex("30 01 02"))), Hex("90 00 08 00"));
}

TEST_F(CipFileObjectTest, UploadInThreeTransfersEndsWithTheChecksum) {
  EXPECT_EQ(Ask(Initiate("FA")), Hex("CB 00 00 00 | 58 02 00 00 | FA"));
  EXPECT_EQ(Ask(GetAttribute(1)), Hex("8E 00 00 00 03"));
  EXPECT_EQ(Ask(Transfer("00")), Concat(Hex("CF 00 00 00 | 00 | 00"), Slice(0, 250)));
  EXPECT_EQ(Ask(GetAttribute(1)), Hex("8E 00 00 00 05"));
  EXPECT_EQ(Ask(Transfer("01")), Concat(Hex("CF 00 00 00 | 01 | 01"), Slice(250, 250)));
  EXPECT_EQ(Ask(Transfer("02")), Concat(Concat(Hex("CF 00 00 00 | 02 | 02"), Slice(500, 100)), Hex("4C D9")));
  EXPECT_EQ(Ask(GetAttribute(1)), Hex("8E 00 00 00 02"));
  // The upload is over: the last packet can be asked for again, nothing after it.
  EXPECT_EQ(Ask(Transfer("02")), Concat(Concat(Hex("CF 00 00 00 | 02 | 02"), Slice(500, 100)), Hex("4C D9")));
  EXPECT_EQ(Ask(Transfer("03")), Hex("CF 00 0C 00"));
  // The bytes and the checksum add up to 0 modulo 2^16.
  std::uint32_t sum = 0xD94C;
  for (std::uint8_t byte : kFileBytes) sum += byte;
  EXPECT_EQ(sum & 0xFFFF, 0u);
}

TEST_F(CipFileObjectTest, AFileOfWholeTransfersEndsWithoutAnEmptyPacket) {
  EXPECT_EQ(Ask(Initiate("C8")), Hex("CB 00 00 00 | 58 02 00 00 | C8"));
  EXPECT_EQ(Ask(Transfer("00")), Concat(Hex("CF 00 00 00 00 00"), Slice(0, 200)));
  EXPECT_EQ(Ask(Transfer("01")), Concat(Hex("CF 00 00 00 01 01"), Slice(200, 200)));
  EXPECT_EQ(Ask(Transfer("02")), Concat(Concat(Hex("CF 00 00 00 02 02"), Slice(400, 200)), Hex("4C D9")));
}

TEST_F(CipFileObjectTest, AResendRepeatsThePacketAndTheUploadGoesOn) {
  EXPECT_EQ(Ask(Initiate("FA")), Hex("CB 00 00 00 58 02 00 00 FA"));
  EXPECT_EQ(Ask(Transfer("00")), Concat(Hex("CF 00 00 00 00 00"), Slice(0, 250)));
  EXPECT_EQ(Ask(Transfer("00")), Concat(Hex("CF 00 00 00 00 00"), Slice(0, 250)));
  EXPECT_EQ(Ask(Transfer("01")), Concat(Hex("CF 00 00 00 01 01"), Slice(250, 250)));
  EXPECT_EQ(Ask(Transfer("01")), Concat(Hex("CF 00 00 00 01 01"), Slice(250, 250)));
  EXPECT_EQ(Ask(Transfer("02")), Concat(Concat(Hex("CF 00 00 00 02 02"), Slice(500, 100)), Hex("4C D9")));
}

TEST_F(CipFileObjectTest, OutOfSequenceTransfersAreRefusedWithoutLosingThePlace) {
  EXPECT_EQ(Ask(Initiate("FA")), Hex("CB 00 00 00 58 02 00 00 FA"));
  // Before the first packet only 0 is in sequence (255 is not "the packet sent last").
  EXPECT_EQ(Ask(Transfer("01")), Hex("CF 00 20 01 06 00"));
  EXPECT_EQ(Ask(Transfer("FF")), Hex("CF 00 20 01 06 00"));
  EXPECT_EQ(Ask(Transfer("00")), Concat(Hex("CF 00 00 00 00 00"), Slice(0, 250)));
  EXPECT_EQ(Ask(Transfer("02")), Hex("CF 00 20 01 06 00"));
  EXPECT_EQ(Ask(Transfer("05")), Hex("CF 00 20 01 06 00"));
  EXPECT_EQ(Ask(Transfer("01")), Concat(Hex("CF 00 00 00 01 01"), Slice(250, 250)));
}

TEST_F(CipFileObjectTest, RequestDataAndTransferSizeChecks) {
  EXPECT_EQ(Ask(Transfer("00")), Hex("CF 00 0C 00"));  // no Initiate_Upload
  EXPECT_EQ(Ask(Initiate("")), Hex("CB 00 13 00"));
  EXPECT_EQ(Ask(Initiate("64 00")), Hex("CB 00 15 00"));
  EXPECT_EQ(Ask(Initiate("00")), Hex("CB 00 20 01 08 00"));
  EXPECT_EQ(Ask(Transfer("00")), Hex("CF 00 0C 00"));  // none of those started an upload
  EXPECT_EQ(Ask(Initiate("64")), Hex("CB 00 00 00 58 02 00 00 64"));
  EXPECT_EQ(Ask(Transfer("")), Hex("CF 00 13 00"));
  EXPECT_EQ(Ask(Transfer("00 00")), Hex("CF 00 15 00"));
  EXPECT_EQ(Ask(Transfer("00")), Concat(Hex("CF 00 00 00 00 00"), Slice(0, 100)));
}

TEST_F(CipFileObjectTest, OneUploadAtATimeOwnedByItsSession) {
  EXPECT_EQ(Ask(Initiate("FA"), 1, 0), Hex("CB 00 00 00 58 02 00 00 FA"));
  EXPECT_EQ(Ask(Transfer("00"), 1, 1000), Concat(Hex("CF 00 00 00 00 00"), Slice(0, 250)));
  // Another session can neither transfer nor start its own while this one is live.
  EXPECT_EQ(Ask(Transfer("01"), 2, 2000), Hex("CF 00 0C 00"));
  EXPECT_EQ(Ask(Initiate("FA"), 2, 2000), Hex("CB 00 0C 00"));
  EXPECT_EQ(Ask(Transfer("01"), 1, 3000), Concat(Hex("CF 00 00 00 01 01"), Slice(250, 250)));
  // Idle for just under the limit: still owned; at the limit it is dropped and another session may start.
  const hal::Micros idle_end = 3000 + kFileUploadIdleLimit;
  EXPECT_EQ(Ask(Initiate("FA"), 2, idle_end - 1), Hex("CB 00 0C 00"));
  EXPECT_EQ(Ask(GetAttribute(1), 2, idle_end - 1), Hex("8E 00 00 00 05"));
  EXPECT_EQ(Ask(GetAttribute(1), 2, idle_end), Hex("8E 00 00 00 02"));
  EXPECT_EQ(Ask(Initiate("64"), 2, idle_end), Hex("CB 00 00 00 58 02 00 00 64"));
  EXPECT_EQ(Ask(Transfer("02"), 1, idle_end), Hex("CF 00 0C 00"));
  EXPECT_EQ(Ask(Transfer("00"), 2, idle_end), Concat(Hex("CF 00 00 00 00 00"), Slice(0, 100)));
  // The owner may start over at any time.
  EXPECT_EQ(Ask(Initiate("FA"), 2, idle_end), Hex("CB 00 00 00 58 02 00 00 FA"));
  EXPECT_EQ(Ask(Transfer("00"), 2, idle_end), Concat(Hex("CF 00 00 00 00 00"), Slice(0, 250)));
}

TEST_F(CipFileObjectTest, TransferNumbersWrapAround) {
  EXPECT_EQ(Ask(Initiate("01")), Hex("CB 00 00 00 58 02 00 00 01"));
  Bytes uploaded;
  for (std::size_t i = 0; i < 600; ++i) {
    const auto number = static_cast<std::uint8_t>(i);
    const Bytes reply = Ask(Concat(Concat(Hex("4F 02"), kInstancePath), Bytes{number}));
    const std::uint8_t type = i == 0 ? 0 : (i == 599 ? 2 : 1);
    ASSERT_EQ(reply.size(), i == 599 ? 9u : 7u) << i;
    ASSERT_EQ(Bytes(reply.begin(), reply.begin() + 6), (Bytes{0xCF, 0x00, 0x00, 0x00, number, type})) << i;
    uploaded.push_back(reply[6]);
    if (i == 599) {
      EXPECT_EQ(Bytes(reply.begin() + 7, reply.end()), Hex("4C D9"));
    }
  }
  EXPECT_EQ(uploaded, kFileBytes);
}

TEST_F(CipFileObjectTest, ASmallFileIsOneFirstAndLastPacket) {
  constexpr std::array<std::uint8_t, 3> kSmall = {'a', 'b', 'c'};
  const ByteSpanFile small(kSmall);
  test::FakeCard card;
  FileObject object(ServedFile{&small, "x.eds", 1, 0});
  ASSERT_TRUE(card.cip.objects().Register(object.object()).ok());
  EXPECT_EQ(card.Ask(Initiate("FF")), Hex("CB 00 00 00 03 00 00 00 FF"));
  // 'a' + 'b' + 'c' = 0x126; checksum 0xFEDA.
  EXPECT_EQ(card.Ask(Transfer("00")), Hex("CF 00 00 00 00 04 61 62 63 DA FE"));
}

TEST(CipFileObjectWithoutFileTest, NoInstanceAndAnEmptyDirectory) {
  test::FakeCard card;
  FileObject object(ServedFile{});
  ASSERT_TRUE(card.cip.objects().Register(object.object()).ok());
  EXPECT_EQ(card.Ask(Hex("0E 03 20 37 24 00 30 03")), Hex("8E 00 00 00 00 00"));
  EXPECT_EQ(card.Ask(Hex("0E 03 20 37 24 00 30 20")), Hex("8E 00 00 00"));
  EXPECT_EQ(card.Ask(GetAttribute(6)), Hex("8E 00 16 00"));
  EXPECT_EQ(card.Ask(Initiate("64")), Hex("CB 00 16 00"));
}

TEST(CipFileObjectEmptyFileTest, AnEmptyFileCannotBeUploaded) {
  const ByteSpanFile empty{std::span<const std::uint8_t>()};
  test::FakeCard card;
  FileObject object(ServedFile{&empty, "empty.eds", 1, 0});
  ASSERT_TRUE(card.cip.objects().Register(object.object()).ok());
  EXPECT_EQ(card.Ask(GetAttribute(1)), Hex("8E 00 00 00 01"));
  EXPECT_EQ(card.Ask(GetAttribute(6)), Hex("8E 00 00 00 00 00 00 00"));
  EXPECT_EQ(card.Ask(Initiate("64")), Hex("CB 00 0C 00"));
}

}  // namespace
}  // namespace cip
