#include "web/sha256.h"

#include <algorithm>
#include <bit>

#include "base/byte_reader.h"
#include "base/byte_writer.h"

namespace web {
namespace {

// FIPS 180-4 §4.2.2: the first 32 bits of the fractional parts of the cube roots of the first 64 primes.
constexpr std::array<std::uint32_t, 64> kRoundConstants = {
    0x428a2f98, 0x71374491, 0xb5c0fbcf, 0xe9b5dba5, 0x3956c25b, 0x59f111f1, 0x923f82a4, 0xab1c5ed5,
    0xd807aa98, 0x12835b01, 0x243185be, 0x550c7dc3, 0x72be5d74, 0x80deb1fe, 0x9bdc06a7, 0xc19bf174,
    0xe49b69c1, 0xefbe4786, 0x0fc19dc6, 0x240ca1cc, 0x2de92c6f, 0x4a7484aa, 0x5cb0a9dc, 0x76f988da,
    0x983e5152, 0xa831c66d, 0xb00327c8, 0xbf597fc7, 0xc6e00bf3, 0xd5a79147, 0x06ca6351, 0x14292967,
    0x27b70a85, 0x2e1b2138, 0x4d2c6dfc, 0x53380d13, 0x650a7354, 0x766a0abb, 0x81c2c92e, 0x92722c85,
    0xa2bfe8a1, 0xa81a664b, 0xc24b8b70, 0xc76c51a3, 0xd192e819, 0xd6990624, 0xf40e3585, 0x106aa070,
    0x19a4c116, 0x1e376c08, 0x2748774c, 0x34b0bcb5, 0x391c0cb3, 0x4ed8aa4a, 0x5b9cca4f, 0x682e6ff3,
    0x748f82ee, 0x78a5636f, 0x84c87814, 0x8cc70208, 0x90befffa, 0xa4506ceb, 0xbef9a3f7, 0xc67178f2,
};

// FIPS 180-4 §5.3.3: the first 32 bits of the fractional parts of the square roots of the first 8 primes.
constexpr std::array<std::uint32_t, 8> kInitialState = {
    0x6a09e667, 0xbb67ae85, 0x3c6ef372, 0xa54ff53a, 0x510e527f, 0x9b05688c, 0x1f83d9ab, 0x5be0cd19,
};

constexpr std::uint8_t kInnerPad = 0x36;
constexpr std::uint8_t kOuterPad = 0x5c;

std::uint32_t Ch(std::uint32_t x, std::uint32_t y, std::uint32_t z) { return (x & y) ^ (~x & z); }
std::uint32_t Maj(std::uint32_t x, std::uint32_t y, std::uint32_t z) { return (x & y) ^ (x & z) ^ (y & z); }
std::uint32_t BigSigma0(std::uint32_t x) { return std::rotr(x, 2) ^ std::rotr(x, 13) ^ std::rotr(x, 22); }
std::uint32_t BigSigma1(std::uint32_t x) { return std::rotr(x, 6) ^ std::rotr(x, 11) ^ std::rotr(x, 25); }
std::uint32_t SmallSigma0(std::uint32_t x) { return std::rotr(x, 7) ^ std::rotr(x, 18) ^ (x >> 3); }
std::uint32_t SmallSigma1(std::uint32_t x) { return std::rotr(x, 17) ^ std::rotr(x, 19) ^ (x >> 10); }

}  // namespace

void Sha256::Reset() {
  state_ = kInitialState;
  pending_bytes_ = 0;
  length_ = 0;
}

// FIPS 180-4 §6.2.2. The schedule is kept as a ring of 16 words instead of all 64 (W_t only ever
// needs W_{t-16} .. W_{t-1}): 192 bytes less stack on the card.
void Sha256::Compress(std::span<const std::uint8_t, kSha256BlockBytes> block) {
  std::array<std::uint32_t, 16> w{};
  base::ByteReader words(block);  // 64 bytes, 16 words: cannot fail
  for (std::uint32_t& word : w) word = words.U32Be();
  std::uint32_t a = state_[0], b = state_[1], c = state_[2], d = state_[3];
  std::uint32_t e = state_[4], f = state_[5], g = state_[6], h = state_[7];
  for (std::size_t t = 0; t < 64; ++t) {
    if (t >= 16) {
      w[t % 16] += SmallSigma1(w[(t - 2) % 16]) + w[(t - 7) % 16] + SmallSigma0(w[(t - 15) % 16]);
    }
    const std::uint32_t t1 = h + BigSigma1(e) + Ch(e, f, g) + kRoundConstants[t] + w[t % 16];
    const std::uint32_t t2 = BigSigma0(a) + Maj(a, b, c);
    h = g;
    g = f;
    f = e;
    e = d + t1;
    d = c;
    c = b;
    b = a;
    a = t1 + t2;
  }
  state_[0] += a;
  state_[1] += b;
  state_[2] += c;
  state_[3] += d;
  state_[4] += e;
  state_[5] += f;
  state_[6] += g;
  state_[7] += h;
}

void Sha256::Update(std::span<const std::uint8_t> data) {
  length_ += data.size();
  if (pending_bytes_ > 0) {
    const std::size_t take = std::min(data.size(), kSha256BlockBytes - pending_bytes_);
    std::copy_n(data.begin(), take, pending_.begin() + static_cast<std::ptrdiff_t>(pending_bytes_));
    pending_bytes_ += take;
    data = data.subspan(take);
    if (pending_bytes_ < kSha256BlockBytes) return;
    Compress(pending_);
    pending_bytes_ = 0;
  }
  while (data.size() >= kSha256BlockBytes) {
    Compress(data.first<kSha256BlockBytes>());
    data = data.subspan(kSha256BlockBytes);
  }
  std::copy(data.begin(), data.end(), pending_.begin());
  pending_bytes_ = data.size();
}

// §5.1.1: a 1 bit, zeros up to 56 bytes into the last block, then the length in bits (big-endian).
Sha256Digest Sha256::Finish() {
  const std::uint64_t bits = length_ * 8;
  pending_[pending_bytes_++] = 0x80;
  if (pending_bytes_ > kSha256BlockBytes - 8) {
    std::fill(pending_.begin() + static_cast<std::ptrdiff_t>(pending_bytes_), pending_.end(), std::uint8_t{0});
    Compress(pending_);
    pending_bytes_ = 0;
  }
  std::fill(pending_.begin() + static_cast<std::ptrdiff_t>(pending_bytes_), pending_.end() - 8, std::uint8_t{0});
  base::ByteWriter length{std::span(pending_).last<8>()};
  length.U64Be(bits);
  Compress(pending_);
  Sha256Digest digest{};
  base::ByteWriter out(digest);  // 8 words into 32 bytes: cannot fail
  for (std::uint32_t word : state_) out.U32Be(word);
  Reset();
  return digest;
}

// RFC 2104 §2: K0 is the key, or its hash when longer than a block, padded with zeros to a block.
HmacSha256::HmacSha256(std::span<const std::uint8_t> key) {
  std::array<std::uint8_t, kSha256BlockBytes> padded{};
  if (key.size() > kSha256BlockBytes) {
    const Sha256Digest hashed = Sha256Of(key);
    std::copy(hashed.begin(), hashed.end(), padded.begin());
  } else {
    std::copy(key.begin(), key.end(), padded.begin());
  }
  for (std::uint8_t& byte : padded) byte ^= kInnerPad;
  inner_start_.Update(padded);
  for (std::uint8_t& byte : padded) byte ^= kInnerPad ^ kOuterPad;
  outer_start_.Update(padded);
  padded.fill(0);  // the key does not stay on the stack
  inner_ = inner_start_;
}

Sha256Digest HmacSha256::Finish() {
  const Sha256Digest inner = inner_.Finish();
  Sha256 outer = outer_start_;
  outer.Update(inner);
  inner_ = inner_start_;
  return outer.Finish();
}

Pbkdf2Sha256::Pbkdf2Sha256(std::span<const std::uint8_t> password, std::span<const std::uint8_t> salt,
                           std::uint32_t iterations, std::span<std::uint8_t> derived)
    : prf_(password),
      salt_(salt),
      derived_(derived),
      iterations_(iterations),
      status_(iterations == 0 || derived.empty() ? base::InvalidArgument() : base::OkStatus()) {}

// RFC 8018 §5.2 step 3: U_1 = PRF(P, S || INT(i)), INT(i) the block index as 4 bytes big-endian.
void Pbkdf2Sha256::StartBlock() {
  ++block_;
  std::array<std::uint8_t, 4> index{};
  base::ByteWriter index_writer(index);
  index_writer.U32Be(block_);
  prf_.Update(salt_);
  prf_.Update(index);
  u_ = prf_.Finish();
  t_ = u_;
  done_in_block_ = 1;
}

bool Pbkdf2Sha256::Run(std::uint32_t max_iterations) {
  for (; max_iterations > 0 && !done(); --max_iterations) {
    if (done_in_block_ == 0) {
      StartBlock();
    } else {
      prf_.Update(u_);
      u_ = prf_.Finish();
      for (std::size_t i = 0; i < t_.size(); ++i) t_[i] ^= u_[i];
      ++done_in_block_;
    }
    if (done_in_block_ == iterations_) {
      const std::size_t take = std::min(t_.size(), derived_.size() - offset_);
      std::copy_n(t_.begin(), take, derived_.begin() + static_cast<std::ptrdiff_t>(offset_));
      offset_ += take;
      done_in_block_ = 0;
    }
  }
  return done();
}

Sha256Digest Sha256Of(std::span<const std::uint8_t> data) {
  Sha256 hash;
  hash.Update(data);
  return hash.Finish();
}

Sha256Digest HmacSha256Of(std::span<const std::uint8_t> key, std::span<const std::uint8_t> message) {
  HmacSha256 mac(key);
  mac.Update(message);
  return mac.Finish();
}

base::Status Pbkdf2HmacSha256(std::span<const std::uint8_t> password, std::span<const std::uint8_t> salt,
                              std::uint32_t iterations, std::span<std::uint8_t> derived) {
  Pbkdf2Sha256 kdf(password, salt, iterations, derived);
  while (!kdf.Run(UINT32_MAX)) {
  }
  return kdf.status();
}

// No early exit: the loop runs over every byte whatever it finds, so its time says nothing about where
// the inputs differ.
bool ConstantTimeEqual(std::span<const std::uint8_t> a, std::span<const std::uint8_t> b) {
  if (a.size() != b.size()) return false;
  std::uint8_t difference = 0;
  for (std::size_t i = 0; i < a.size(); ++i) difference = static_cast<std::uint8_t>(difference | (a[i] ^ b[i]));
  return difference == 0;
}

}  // namespace web
