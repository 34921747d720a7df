// The ChaCha20 block function (RFC 8439 §2.3) and a random generator built on it.
//
// ChaChaGenerator is the card's deterministic random bit generator on a board without a TRNG
// (docs/board.md "Random numbers"): its 256-bit key absorbs seed material (Mix) and produces output
// blocks under a fresh key each time (Fill): after every request the key is replaced by output of the
// old key ("fast key erasure"), so a later look at the state does not give earlier output away. It is
// exactly as unpredictable as the seed material mixed into it, no more.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

namespace hal::mps2 {

inline constexpr std::size_t kChaChaKeyBytes = 32;
inline constexpr std::size_t kChaChaNonceBytes = 12;
inline constexpr std::size_t kChaChaBlockBytes = 64;

// One 64-byte block of key stream for (key, counter, nonce), serialized little-endian (RFC 8439 §2.3.2).
void ChaCha20Block(std::span<const std::uint8_t, kChaChaKeyBytes> key, std::uint32_t counter,
                   std::span<const std::uint8_t, kChaChaNonceBytes> nonce,
                   std::span<std::uint8_t, kChaChaBlockBytes> out);

class ChaChaGenerator {
 public:
  // Absorbs `input` into the key, 32 bytes at a time: each chunk is XORed into the key and the key is
  // replaced by a block of ChaCha20 under the result (the chunk's number and the input's length in the
  // nonce, so inputs that differ only in their split or padding do not end alike).
  void Mix(std::span<const std::uint8_t> input);
  // Output under the current key (blocks 1, 2, ...), then a new key from block 0.
  void Fill(std::span<std::uint8_t> out);

 private:
  void Rekey(std::uint32_t domain, std::uint32_t word1, std::uint32_t word2);

  std::array<std::uint8_t, kChaChaKeyBytes> key_{};
};

}  // namespace hal::mps2
