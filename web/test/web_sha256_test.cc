// SHA-256, HMAC-SHA256 and PBKDF2-HMAC-SHA256 against published vectors: FIPS 180-2 appendix B (and the
// NIST example messages), RFC 4231 §4 and the PBKDF2-HMAC-SHA256 vectors of RFC 7914 §11 / the
// widely used extension of RFC 6070 to SHA-256. Also: pieces of every size give the same digest, the
// padding boundaries, PBKDF2 run in slices, and the constant-time comparison.
#include "web/sha256.h"

#include <gtest/gtest.h>

#include <string>
#include <string_view>
#include <vector>

namespace web {
namespace {

std::span<const std::uint8_t> Bytes(std::string_view text) {
  return {reinterpret_cast<const std::uint8_t*>(text.data()), text.size()};
}

std::string Hex(std::span<const std::uint8_t> bytes) {
  static constexpr char kDigits[] = "0123456789abcdef";
  std::string text;
  for (std::uint8_t byte : bytes) {
    text += kDigits[byte >> 4];
    text += kDigits[byte & 0x0F];
  }
  return text;
}

std::string HashHex(std::string_view text) { return Hex(Sha256Of(Bytes(text))); }

TEST(Sha256Test, FipsAbc) {
  EXPECT_EQ(HashHex("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
}

TEST(Sha256Test, Fips448BitMessage) {
  EXPECT_EQ(HashHex("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq"),
            "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
}

TEST(Sha256Test, Nist896BitMessage) {
  EXPECT_EQ(HashHex("abcdefghbcdefghicdefghijdefghijkefghijklfghijklmghijklmnhijklmnoijklmnopjklmnopqklmnopqrlmnopqrs"
                    "mnopqrstnopqrstu"),
            "cf5b16a778af8380036ce59e7b0492370b249b11e8f07a51afac45037afee9d1");
}

TEST(Sha256Test, EmptyMessage) {
  EXPECT_EQ(HashHex(""), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
}

TEST(Sha256Test, OneMillionAInThousandByteUpdates) {
  const std::string thousand(1000, 'a');
  Sha256 hash;
  for (int i = 0; i < 1000; ++i) hash.Update(Bytes(thousand));
  EXPECT_EQ(Hex(hash.Finish()), "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
}

// 55 bytes leave exactly room for the 0x80 and the length; 56..63 need a second padding block.
TEST(Sha256Test, PaddingBoundaries) {
  EXPECT_EQ(HashHex(std::string(55, 'a')), "9f4390f8d30c2dd92ec9f095b65e2b9ae9b0a925a5258e241c9f1e910f734318");
  EXPECT_EQ(HashHex(std::string(56, 'a')), "b35439a4ac6f0948b6d6f9e3c6af0f5f590ce20f1bde7090ef7970686ec6738a");
  EXPECT_EQ(HashHex(std::string(63, 'a')), "7d3e74a05d7db15bce4ad9ec0658ea98e3f06eeecf16b4c6fff2da457ddc2f34");
  EXPECT_EQ(HashHex(std::string(64, 'a')), "ffe054fe7ae0cb6dc65c3af9b61d5209f439851db43d0ba5997337df154668eb");
  EXPECT_EQ(HashHex(std::string(65, 'a')), "635361c48bb9eab14198e76ea8ab7f1a41685d6ad62aa9146d301d4f17eb0ae0");
  EXPECT_EQ(HashHex(std::string(119, 'a')), "31eba51c313a5c08226adf18d4a359cfdfd8d2e816b13f4af952f7ea6584dcfb");
  EXPECT_EQ(HashHex(std::string(120, 'a')), "2f3d335432c70b580af0e8e1b3674a7c020d683aa5f73aaaedfdc55af904c21c");
}

TEST(Sha256Test, AnySplitIntoTwoOrThreePiecesGivesTheSameDigest) {
  std::vector<std::uint8_t> message(200);
  for (std::size_t i = 0; i < message.size(); ++i) message[i] = static_cast<std::uint8_t>(i * 7 + 3);
  const Sha256Digest whole = Sha256Of(message);
  const std::span<const std::uint8_t> all(message);
  for (std::size_t cut = 0; cut <= message.size(); ++cut) {
    Sha256 hash;
    hash.Update(all.first(cut));
    hash.Update(all.subspan(cut));
    EXPECT_EQ(hash.Finish(), whole) << cut;
  }
  Sha256 bytewise;
  for (std::uint8_t byte : message) bytewise.Update(std::span(&byte, 1));
  EXPECT_EQ(bytewise.Finish(), whole);
}

TEST(Sha256Test, FinishStartsANewMessage) {
  Sha256 hash;
  hash.Update(Bytes("something else"));
  hash.Finish();
  hash.Update(Bytes("abc"));
  EXPECT_EQ(Hex(hash.Finish()), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
}

std::string HmacHex(std::span<const std::uint8_t> key, std::span<const std::uint8_t> data) {
  return Hex(HmacSha256Of(key, data));
}

TEST(HmacSha256Test, Rfc4231Case1) {
  const std::vector<std::uint8_t> key(20, 0x0b);
  EXPECT_EQ(HmacHex(key, Bytes("Hi There")), "b0344c61d8db38535ca8afceaf0bf12b881dc200c9833da726e9376c2e32cff7");
}

TEST(HmacSha256Test, Rfc4231Case2ShortKey) {
  EXPECT_EQ(HmacHex(Bytes("Jefe"), Bytes("what do ya want for nothing?")),
            "5bdcc146bf60754e6a042426089575c75a003f089d2739839dec58b964ec3843");
}

TEST(HmacSha256Test, Rfc4231Case3) {
  const std::vector<std::uint8_t> key(20, 0xaa);
  const std::vector<std::uint8_t> data(50, 0xdd);
  EXPECT_EQ(HmacHex(key, data), "773ea91e36800e46854db8ebd09181a72959098b3ef8c122d9635514ced565fe");
}

TEST(HmacSha256Test, Rfc4231Case4) {
  std::vector<std::uint8_t> key;
  for (std::uint8_t i = 1; i <= 25; ++i) key.push_back(i);
  const std::vector<std::uint8_t> data(50, 0xcd);
  EXPECT_EQ(HmacHex(key, data), "82558a389a443c0ea4cc819899f2083a85f0faa3e578f8077a2e3ff46729665b");
}

TEST(HmacSha256Test, Rfc4231Case6KeyLongerThanABlock) {
  const std::vector<std::uint8_t> key(131, 0xaa);
  EXPECT_EQ(HmacHex(key, Bytes("Test Using Larger Than Block-Size Key - Hash Key First")),
            "60e431591ee0b67f0d8a26aacbf5b77f8e0bc6213728c5140546040f0ee37f54");
}

TEST(HmacSha256Test, Rfc4231Case7KeyAndDataLongerThanABlock) {
  const std::vector<std::uint8_t> key(131, 0xaa);
  EXPECT_EQ(HmacHex(key, Bytes("This is a test using a larger than block-size key and a larger than block-size data. "
                               "The key needs to be hashed before being used by the HMAC algorithm.")),
            "9b09ffa71b942fcb27635fbcd5b0e944bfdc63644f0713938a7f51535c3a35e2");
}

TEST(HmacSha256Test, OneKeyManyMessages) {
  HmacSha256 mac(Bytes("Jefe"));
  mac.Update(Bytes("what do ya "));
  mac.Update(Bytes("want for nothing?"));
  EXPECT_EQ(Hex(mac.Finish()), "5bdcc146bf60754e6a042426089575c75a003f089d2739839dec58b964ec3843");
  mac.Update(Bytes("what do ya want for nothing?"));
  EXPECT_EQ(Hex(mac.Finish()), "5bdcc146bf60754e6a042426089575c75a003f089d2739839dec58b964ec3843");
}

std::string Pbkdf2Hex(std::string_view password, std::string_view salt, std::uint32_t iterations, std::size_t length) {
  std::vector<std::uint8_t> derived(length);
  EXPECT_TRUE(Pbkdf2HmacSha256(Bytes(password), Bytes(salt), iterations, derived).ok());
  return Hex(derived);
}

TEST(Pbkdf2Sha256Test, PasswordSaltOneIteration) {
  EXPECT_EQ(Pbkdf2Hex("password", "salt", 1, 32), "120fb6cffcf8b32c43e7225256c4f837a86548c92ccc35480805987cb70be17b");
}

TEST(Pbkdf2Sha256Test, PasswordSaltTwoIterations) {
  EXPECT_EQ(Pbkdf2Hex("password", "salt", 2, 32), "ae4d0c95af6b46d32d0adff928f06dd02a303f8ef3c251dfd6e2d85a95474c43");
}

TEST(Pbkdf2Sha256Test, PasswordSalt4096Iterations) {
  EXPECT_EQ(Pbkdf2Hex("password", "salt", 4096, 32),
            "c5e478d59288c841aa530db6845c4c8d962893a001ce4e11a4963873aa98134a");
}

// 40 bytes: two blocks, the second cut to 8 bytes.
TEST(Pbkdf2Sha256Test, LongPasswordAndSaltTwoBlocks) {
  EXPECT_EQ(Pbkdf2Hex("passwordPASSWORDpassword", "saltSALTsaltSALTsaltSALTsaltSALTsalt", 4096, 40),
            "348c89dbcbd32b2f32d814b8116e84cf2b17347ebc1800181c4e2a1fb8dd53e1c635518c7dac47e9");
}

TEST(Pbkdf2Sha256Test, SlicesOfOneIterationGiveTheSameKey) {
  std::vector<std::uint8_t> derived(40);
  Pbkdf2Sha256 kdf(Bytes("passwordPASSWORDpassword"), Bytes("saltSALTsaltSALTsaltSALTsaltSALTsalt"), 4096, derived);
  ASSERT_TRUE(kdf.status().ok());
  int calls = 0;
  while (!kdf.Run(1)) ++calls;
  EXPECT_EQ(calls + 1, 2 * 4096);  // one PRF call per iteration, per block
  EXPECT_EQ(Hex(derived), "348c89dbcbd32b2f32d814b8116e84cf2b17347ebc1800181c4e2a1fb8dd53e1c635518c7dac47e9");
  EXPECT_TRUE(kdf.done());
  EXPECT_TRUE(kdf.Run(100));
}

TEST(Pbkdf2Sha256Test, UnevenSlicesAcrossTheBlockBoundary) {
  std::vector<std::uint8_t> derived(40);
  Pbkdf2Sha256 kdf(Bytes("passwordPASSWORDpassword"), Bytes("saltSALTsaltSALTsaltSALTsaltSALTsalt"), 4096, derived);
  EXPECT_FALSE(kdf.Run(0));
  EXPECT_FALSE(kdf.Run(4095));
  EXPECT_FALSE(kdf.Run(2));  // the first block's last iteration, then the second block's first
  EXPECT_FALSE(kdf.Run(4094));
  EXPECT_TRUE(kdf.Run(1));
  EXPECT_EQ(Hex(derived), "348c89dbcbd32b2f32d814b8116e84cf2b17347ebc1800181c4e2a1fb8dd53e1c635518c7dac47e9");
}

TEST(Pbkdf2Sha256Test, ZeroIterationsOrNoOutputRefusedAndNothingWritten) {
  std::vector<std::uint8_t> derived(32, 0x5a);
  EXPECT_EQ(Pbkdf2HmacSha256(Bytes("password"), Bytes("salt"), 0, derived), base::InvalidArgument());
  EXPECT_EQ(derived, std::vector<std::uint8_t>(32, 0x5a));
  EXPECT_EQ(Pbkdf2HmacSha256(Bytes("password"), Bytes("salt"), 1, std::span<std::uint8_t>()), base::InvalidArgument());
}

TEST(ConstantTimeEqualTest, EqualDifferentAndLengthMismatch) {
  Sha256Digest a = Sha256Of(Bytes("abc"));
  Sha256Digest b = a;
  EXPECT_TRUE(DigestsEqual(a, b));
  for (std::size_t i = 0; i < b.size(); ++i) {
    b = a;
    b[i] ^= 0x01;
    EXPECT_FALSE(DigestsEqual(a, b)) << i;
    b[i] ^= 0x81;
    EXPECT_FALSE(DigestsEqual(a, b)) << i;
  }
  EXPECT_FALSE(ConstantTimeEqual(Bytes("abc"), Bytes("abcd")));
  EXPECT_TRUE(ConstantTimeEqual(Bytes(""), Bytes("")));
}

}  // namespace
}  // namespace web
