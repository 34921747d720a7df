#include "web/password_store.h"

#include <algorithm>

#include "base/byte_reader.h"
#include "base/byte_writer.h"

namespace web {
namespace {

constexpr std::uint8_t kFlagDefault = 0x01;

std::span<const std::uint8_t> Bytes(std::string_view text) {
  return {reinterpret_cast<const std::uint8_t*>(text.data()), text.size()};
}

std::size_t Index(PasswordKind which) { return static_cast<std::size_t>(which); }

bool IterationsAllowed(std::uint32_t iterations) { return iterations >= 1 && iterations <= kMaxPasswordIterations; }

void EncodeRecord(const PasswordRecord& record, std::span<std::uint8_t, kPasswordRecordBytes> out) {
  base::ByteWriter writer(out);  // flag, iterations, salt and hash fill the record exactly
  writer.U8(record.is_default ? kFlagDefault : std::uint8_t{0});
  writer.U32Le(record.iterations);
  writer.Bytes(record.salt);
  writer.Bytes(record.hash);
}

base::Result<PasswordRecord> ParseRecord(std::span<const std::uint8_t, kPasswordRecordBytes> in) {
  base::ByteReader reader(in);  // the record's fixed size holds every field: the reader cannot fail
  const std::uint8_t flags = reader.U8();
  if ((flags & ~kFlagDefault) != 0) return base::DataLoss();
  PasswordRecord record;
  record.is_default = (flags & kFlagDefault) != 0;
  record.iterations = reader.U32Le();
  if (!IterationsAllowed(record.iterations)) return base::DataLoss();
  const std::span<const std::uint8_t> salt = reader.Bytes(kPasswordSaltBytes);
  const std::span<const std::uint8_t> hash = reader.Bytes(kSha256Bytes);
  std::copy(salt.begin(), salt.end(), record.salt.begin());
  std::copy(hash.begin(), hash.end(), record.hash.begin());
  return record;
}

}  // namespace

base::Status CheckPasswordText(std::string_view password) {
  if (password.size() < kMinPasswordBytes || password.size() > kMaxPasswordBytes) return base::OutOfRange();
  const bool printable = std::all_of(password.begin(), password.end(), [](char c) {
    const auto byte = static_cast<unsigned char>(c);
    return byte >= 0x20 && byte <= 0x7E;
  });
  return printable ? base::OkStatus() : base::InvalidArgument();
}

base::Result<PasswordRecord> HashPassword(std::string_view password,
                                          std::span<const std::uint8_t, kPasswordSaltBytes> salt,
                                          std::uint32_t iterations) {
  if (base::Status text = CheckPasswordText(password); !text.ok()) return text;
  if (!IterationsAllowed(iterations)) return base::InvalidArgument();
  PasswordRecord record;
  std::copy(salt.begin(), salt.end(), record.salt.begin());
  record.iterations = iterations;
  // Not secret: the flag only answers "is it still the factory password", which the page shows anyway.
  record.is_default = password == kDefaultPassword;
  if (base::Status derived = Pbkdf2HmacSha256(Bytes(password), record.salt, iterations, record.hash); !derived.ok()) {
    return derived;
  }
  return record;
}

bool VerifyPassword(const PasswordRecord& record, std::string_view password) {
  if (!IterationsAllowed(record.iterations) || !CheckPasswordText(password).ok()) return false;
  Sha256Digest candidate{};
  if (!Pbkdf2HmacSha256(Bytes(password), record.salt, record.iterations, candidate).ok()) return false;
  return DigestsEqual(candidate, record.hash);
}

void EncodePasswordRecords(const PasswordRecords& records, std::span<std::uint8_t, kPasswordNvBytes> out) {
  out[0] = kPasswordNvVersion;
  for (std::size_t i = 0; i < kPasswordKinds; ++i) {
    EncodeRecord(records[i], out.subspan(1 + i * kPasswordRecordBytes).first<kPasswordRecordBytes>());
  }
}

base::Result<PasswordRecords> ParsePasswordRecords(std::span<const std::uint8_t> bytes) {
  if (bytes.size() != kPasswordNvBytes) return base::OutOfRange();
  if (bytes[0] != kPasswordNvVersion) return base::DataLoss();
  PasswordRecords records{};
  for (std::size_t i = 0; i < kPasswordKinds; ++i) {
    const base::Result<PasswordRecord> record =
        ParseRecord(bytes.subspan(1 + i * kPasswordRecordBytes).first<kPasswordRecordBytes>());
    if (!record.ok()) return record.status();
    records[i] = *record;
  }
  return records;
}

base::Result<PasswordSource> PasswordStore::Load() {
  // One byte more than the layout: a longer record is read whole and then refused for its length,
  // instead of failing the read with kOutOfRange and looking like a different problem.
  std::array<std::uint8_t, kPasswordNvBytes + 1> stored{};
  const base::Result<std::size_t> read = nv_.Read(id_, stored);
  if (read.ok()) {
    const base::Result<PasswordRecords> parsed = ParsePasswordRecords(std::span(stored).first(*read));
    if (parsed.ok()) {
      records_ = *parsed;
      return PasswordSource::kStored;
    }
  }
  PasswordRecords defaults{};
  for (PasswordRecord& record : defaults) {
    const base::Result<PasswordRecord> made = NewRecord(kDefaultPassword);
    if (!made.ok()) return made.status();  // not reached: "USER" passes every check
    record = *made;
  }
  records_ = defaults;
  if (base::Status saved = Save(records_); !saved.ok()) return saved;
  return PasswordSource::kDefaults;
}

bool PasswordStore::Verify(PasswordKind which, std::string_view password) const {
  return VerifyPassword(records_[Index(which)], password);
}

base::Status PasswordStore::Set(PasswordKind which, std::string_view password) {
  const base::Result<PasswordRecord> made = NewRecord(password);
  if (!made.ok()) return made.status();
  PasswordRecords changed = records_;
  changed[Index(which)] = *made;
  if (base::Status saved = Save(changed); !saved.ok()) return saved;
  records_ = changed;
  return base::OkStatus();
}

bool PasswordStore::defaults() const {
  return std::any_of(records_.begin(), records_.end(),
                     [](const PasswordRecord& record) { return record.iterations != 0 && record.is_default; });
}

base::Result<PasswordRecord> PasswordStore::NewRecord(std::string_view password) {
  if (base::Status text = CheckPasswordText(password); !text.ok()) return text;
  std::array<std::uint8_t, kPasswordSaltBytes> salt{};
  random_.Fill(salt);
  return HashPassword(password, salt);
}

base::Status PasswordStore::Save(const PasswordRecords& records) {
  std::array<std::uint8_t, kPasswordNvBytes> bytes{};
  EncodePasswordRecords(records, bytes);
  return nv_.Write(id_, bytes);
}

}  // namespace web
