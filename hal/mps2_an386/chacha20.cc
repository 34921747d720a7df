#include "chacha20.h"

#include <algorithm>

namespace hal::mps2 {
namespace {

constexpr std::uint32_t Rotl(std::uint32_t value, int bits) { return (value << bits) | (value >> (32 - bits)); }

void QuarterRound(std::array<std::uint32_t, 16>& x, int a, int b, int c, int d) {
  const auto i = [](int n) { return static_cast<std::size_t>(n); };
  x[i(a)] += x[i(b)];
  x[i(d)] = Rotl(x[i(d)] ^ x[i(a)], 16);
  x[i(c)] += x[i(d)];
  x[i(b)] = Rotl(x[i(b)] ^ x[i(c)], 12);
  x[i(a)] += x[i(b)];
  x[i(d)] = Rotl(x[i(d)] ^ x[i(a)], 8);
  x[i(c)] += x[i(d)];
  x[i(b)] = Rotl(x[i(b)] ^ x[i(c)], 7);
}

std::uint32_t LoadLittle(const std::uint8_t* bytes) {
  return static_cast<std::uint32_t>(bytes[0]) | static_cast<std::uint32_t>(bytes[1]) << 8 |
         static_cast<std::uint32_t>(bytes[2]) << 16 | static_cast<std::uint32_t>(bytes[3]) << 24;
}

void StoreLittle(std::uint32_t value, std::uint8_t* bytes) {
  for (int i = 0; i < 4; ++i) bytes[i] = static_cast<std::uint8_t>(value >> (8 * i));
}

// Nonce words of the generator's uses of the block function, so they never share a key stream.
constexpr std::uint32_t kOutputDomain = 0;
constexpr std::uint32_t kMixDomain = 0x0078696D;    // "mix"
constexpr std::uint32_t kRekeyDomain = 0x0079656B;  // "key"

std::array<std::uint8_t, kChaChaNonceBytes> Nonce(std::uint32_t domain, std::uint32_t word1, std::uint32_t word2) {
  std::array<std::uint8_t, kChaChaNonceBytes> nonce{};
  StoreLittle(domain, &nonce[0]);
  StoreLittle(word1, &nonce[4]);
  StoreLittle(word2, &nonce[8]);
  return nonce;
}

}  // namespace

void ChaCha20Block(std::span<const std::uint8_t, kChaChaKeyBytes> key, std::uint32_t counter,
                   std::span<const std::uint8_t, kChaChaNonceBytes> nonce,
                   std::span<std::uint8_t, kChaChaBlockBytes> out) {
  std::array<std::uint32_t, 16> state{0x61707865, 0x3320646e, 0x79622d32, 0x6b206574};  // "expand 32-byte k"
  for (std::size_t i = 0; i < 8; ++i) state[4 + i] = LoadLittle(&key[4 * i]);
  state[12] = counter;
  for (std::size_t i = 0; i < 3; ++i) state[13 + i] = LoadLittle(&nonce[4 * i]);

  std::array<std::uint32_t, 16> working = state;
  for (int round = 0; round < 10; ++round) {  // 20 rounds: 10 column + 10 diagonal
    QuarterRound(working, 0, 4, 8, 12);
    QuarterRound(working, 1, 5, 9, 13);
    QuarterRound(working, 2, 6, 10, 14);
    QuarterRound(working, 3, 7, 11, 15);
    QuarterRound(working, 0, 5, 10, 15);
    QuarterRound(working, 1, 6, 11, 12);
    QuarterRound(working, 2, 7, 8, 13);
    QuarterRound(working, 3, 4, 9, 14);
  }
  for (std::size_t i = 0; i < 16; ++i) StoreLittle(working[i] + state[i], &out[4 * i]);
}

void ChaChaGenerator::Rekey(std::uint32_t domain, std::uint32_t word1, std::uint32_t word2) {
  std::array<std::uint8_t, kChaChaBlockBytes> block;
  ChaCha20Block(key_, 0, Nonce(domain, word1, word2), block);
  std::copy_n(block.begin(), key_.size(), key_.begin());
  block.fill(0);
}

void ChaChaGenerator::Mix(std::span<const std::uint8_t> input) {
  const auto length = static_cast<std::uint32_t>(input.size());
  std::uint32_t chunk = 0;
  std::size_t offset = 0;
  do {
    const std::size_t take = std::min(key_.size(), input.size() - offset);
    for (std::size_t i = 0; i < take; ++i) key_[i] ^= input[offset + i];
    Rekey(kMixDomain, chunk++, length);
    offset += take;
  } while (offset < input.size());
}

void ChaChaGenerator::Fill(std::span<std::uint8_t> out) {
  std::array<std::uint8_t, kChaChaBlockBytes> block;
  const auto nonce = Nonce(kOutputDomain, 0, 0);
  std::uint32_t counter = 1;
  for (std::size_t offset = 0; offset < out.size(); offset += block.size()) {
    ChaCha20Block(key_, counter++, nonce, block);
    std::copy_n(block.begin(), std::min(block.size(), out.size() - offset), out.begin() + static_cast<std::ptrdiff_t>(offset));
  }
  block.fill(0);
  Rekey(kRekeyDomain, 0, 0);
}

}  // namespace hal::mps2
