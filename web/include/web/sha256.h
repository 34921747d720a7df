// SHA-256 (FIPS 180-4), HMAC-SHA256 (RFC 2104) and PBKDF2-HMAC-SHA256 (RFC 8018 §5.2) for the web
// server's passwords (docs/web.md "Passwords and sessions (implementation)"). Written from the standards;
// no allocation, every input a span. Not a general crypto library: no other hashes, no MAC truncation.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "base/status.h"

namespace web {

inline constexpr std::size_t kSha256Bytes = 32;
inline constexpr std::size_t kSha256BlockBytes = 64;

using Sha256Digest = std::array<std::uint8_t, kSha256Bytes>;

// A message fed in pieces of any size. The length is counted in bytes in 64 bits: messages up to
// 2^61 - 1 bytes, far beyond anything the card hashes.
class Sha256 {
 public:
  Sha256() { Reset(); }

  void Reset();
  void Update(std::span<const std::uint8_t> data);
  // The digest of everything given since the last Reset; the object starts a new message afterwards.
  Sha256Digest Finish();

 private:
  void Compress(std::span<const std::uint8_t, kSha256BlockBytes> block);

  std::array<std::uint32_t, 8> state_{};
  std::array<std::uint8_t, kSha256BlockBytes> pending_{};
  std::size_t pending_bytes_ = 0;
  std::uint64_t length_ = 0;
};

// HMAC with a key of any length. The hash states after the two padded keys are kept, so each further
// message under the same key costs the message's blocks plus one for the outer hash: PBKDF2 relies on
// this (two compressions per iteration instead of four).
class HmacSha256 {
 public:
  explicit HmacSha256(std::span<const std::uint8_t> key);

  void Update(std::span<const std::uint8_t> data) { inner_.Update(data); }
  // The MAC of everything given since construction or the last Finish; ready for a new message.
  Sha256Digest Finish();

 private:
  Sha256 inner_start_;  // after K0 ^ ipad
  Sha256 outer_start_;  // after K0 ^ opad
  Sha256 inner_;
};

// PBKDF2 that can be run in slices: the firmware has one thread, and thousands of iterations in one go
// would hold up every other service for a noticeable time (docs/web.md). Run(n) does at most n
// iterations and says whether the key is complete. `salt` and `derived` must stay valid until then.
class Pbkdf2Sha256 {
 public:
  // kInvalidArgument from status(): no iterations, or nothing to derive (RFC 8018 requires c >= 1 and
  // dkLen >= 1; dkLen is far below its (2^32 - 1) * hLen ceiling for any span on the card).
  Pbkdf2Sha256(std::span<const std::uint8_t> password, std::span<const std::uint8_t> salt, std::uint32_t iterations,
               std::span<std::uint8_t> derived);

  base::Status status() const { return status_; }
  bool done() const { return !status_.ok() || offset_ >= derived_.size(); }
  // Up to `max_iterations` iterations (0 means none); true once finished: `derived` holds the whole
  // key, or status() refused the parameters (and `derived` is untouched).
  bool Run(std::uint32_t max_iterations);

 private:
  void StartBlock();

  HmacSha256 prf_;
  std::span<const std::uint8_t> salt_;
  std::span<std::uint8_t> derived_;
  std::uint32_t iterations_;
  base::Status status_;
  std::size_t offset_ = 0;     // bytes of `derived_` complete
  std::uint32_t block_ = 0;    // the index i of T_i being computed (1-based once started)
  std::uint32_t done_in_block_ = 0;  // iterations of T_i done
  Sha256Digest u_{};           // U_j
  Sha256Digest t_{};           // U_1 ^ ... ^ U_j
};

Sha256Digest Sha256Of(std::span<const std::uint8_t> data);
Sha256Digest HmacSha256Of(std::span<const std::uint8_t> key, std::span<const std::uint8_t> message);
// All iterations in one call; kInvalidArgument as Pbkdf2Sha256.
base::Status Pbkdf2HmacSha256(std::span<const std::uint8_t> password, std::span<const std::uint8_t> salt,
                              std::uint32_t iterations, std::span<std::uint8_t> derived);

// Equality whose time depends only on the lengths (which are public: digest sizes, token formats), not
// on where the first difference is: a secret compared this way cannot be found byte by byte by timing.
bool ConstantTimeEqual(std::span<const std::uint8_t> a, std::span<const std::uint8_t> b);
inline bool DigestsEqual(const Sha256Digest& a, const Sha256Digest& b) { return ConstantTimeEqual(a, b); }

}  // namespace web
