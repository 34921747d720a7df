// The card's two web passwords (docs/web.md "Access"): the read password opens a session, the write
// password raises it to write level. Each is kept only as a salted PBKDF2-HMAC-SHA256 hash in one NV
// record; the text of a password is never stored, and no hash ever leaves this class (nothing here logs,
// and nothing answers with a record).
//
// Layout of the NV record (docs/web.md "Passwords and sessions (implementation)"), kPasswordNvBytes long:
//   [0]       version (kPasswordNvVersion)
//   [1..53]   the read password's record, [54..106] the write password's, each:
//             flags (bit 0: still the default "USER"; other bits 0), iterations (u32 little-endian),
//             salt (16 bytes), hash (32 bytes)
// A record of another length or version, with unknown flags or an iteration count outside
// 1..kMaxPasswordIterations, is refused as a whole: the card then starts from the defaults.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>

#include "base/status.h"
#include "hal/nv_store.h"
#include "hal/random.h"
#include "web/sha256.h"

namespace web {

enum class PasswordKind : std::uint8_t { kRead = 0, kWrite = 1 };
inline constexpr std::size_t kPasswordKinds = 2;

// Out of the box (seed 000 §13.1), both passwords.
inline constexpr std::string_view kDefaultPassword = "USER";
// 1..32 bytes of printable ASCII (0x20..0x7E): what the page's field and a script can both type, and
// nothing that needs escaping rules to agree between JSON, a browser and the card.
inline constexpr std::size_t kMinPasswordBytes = 1;
inline constexpr std::size_t kMaxPasswordBytes = 32;
inline constexpr std::size_t kPasswordSaltBytes = 16;
// The PBKDF2 iteration count for new hashes. A compromise: each iteration costs two SHA-256 blocks,
// estimated at 30-45 us each on a Cortex-M4 at 100 MHz (compiled C, 3000-4500 cycles a block), so one
// check takes roughly 0.25-0.4 s of CPU; an attacker with a copy of the flash pays 8192 compressions
// per guess. Stored per record, so a later firmware can raise it and rehash when a password is set.
inline constexpr std::uint32_t kPasswordIterations = 4096;
// What a stored record may ask for: a damaged or hostile record must not keep the card busy for
// minutes (16 times today's count, a few seconds).
inline constexpr std::uint32_t kMaxPasswordIterations = 65536;

inline constexpr std::uint8_t kPasswordNvVersion = 1;
inline constexpr std::size_t kPasswordRecordBytes = 1 + 4 + kPasswordSaltBytes + kSha256Bytes;  // 53
inline constexpr std::size_t kPasswordNvBytes = 1 + kPasswordKinds * kPasswordRecordBytes;      // 107

struct PasswordRecord {
  std::array<std::uint8_t, kPasswordSaltBytes> salt{};
  Sha256Digest hash{};
  std::uint32_t iterations = 0;  // 0: no password set, nothing matches
  bool is_default = false;       // the password is "USER" (GET /api/session "defaults")

  bool operator==(const PasswordRecord&) const = default;
};

// Indexed by PasswordKind.
using PasswordRecords = std::array<PasswordRecord, kPasswordKinds>;

// kOutOfRange: empty or longer than kMaxPasswordBytes; kInvalidArgument: a byte outside 0x20..0x7E.
base::Status CheckPasswordText(std::string_view password);

// The record for `password` under `salt` (kPasswordIterations unless told). Refuses what
// CheckPasswordText refuses, and an iteration count outside 1..kMaxPasswordIterations (kInvalidArgument).
base::Result<PasswordRecord> HashPassword(std::string_view password,
                                          std::span<const std::uint8_t, kPasswordSaltBytes> salt,
                                          std::uint32_t iterations = kPasswordIterations);

// Whether `password` is the one `record` was made from; the hashes are compared in constant time. A
// password the limits refuse never matches (and costs no hashing).
bool VerifyPassword(const PasswordRecord& record, std::string_view password);

void EncodePasswordRecords(const PasswordRecords& records, std::span<std::uint8_t, kPasswordNvBytes> out);
// kOutOfRange: not kPasswordNvBytes long; kDataLoss: another version, unknown flags, or an iteration
// count outside 1..kMaxPasswordIterations.
base::Result<PasswordRecords> ParsePasswordRecords(std::span<const std::uint8_t> bytes);

enum class PasswordSource : std::uint8_t {
  kStored,    // the NV record was read
  kDefaults,  // none, or not readable: both "USER" with fresh salts
};

// The two passwords, kept in RAM as records and in NV record `id`. Until Load() nothing matches.
class PasswordStore {
 public:
  PasswordStore(hal::NvStore& nv, hal::NvRecordId id, hal::RandomSource& random) : nv_(nv), id_(id), random_(random) {}

  PasswordStore(const PasswordStore&) = delete;
  PasswordStore& operator=(const PasswordStore&) = delete;

  // Once at start. When the NV record is missing, damaged or of another version, both passwords become
  // "USER" with fresh random salts and that record is written; a failing write is returned as the error
  // (the defaults are in force all the same, and the next Set tries the store again).
  base::Result<PasswordSource> Load();

  bool Verify(PasswordKind which, std::string_view password) const;

  // A new password with a fresh salt. Refused as CheckPasswordText refuses; a failing NV write is
  // returned and leaves the old password in force, so RAM and NV never disagree.
  base::Status Set(PasswordKind which, std::string_view password);

  // True while either password is "USER".
  bool defaults() const;

 private:
  base::Result<PasswordRecord> NewRecord(std::string_view password);
  base::Status Save(const PasswordRecords& records);

  hal::NvStore& nv_;
  hal::NvRecordId id_;
  hal::RandomSource& random_;
  PasswordRecords records_{};
};

}  // namespace web
