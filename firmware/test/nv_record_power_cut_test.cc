// Power loss during the write of each of the card's NV records (docs/robustness.md "Power loss"): the
// factory MAC, the web passwords and the TCP/IP settings' extras, each through the code that owns it and
// a real FileNvStore. For every number of bytes of the new record file that may have reached the disk
// when power failed (0 .. all of them, not yet renamed) and for a cut just after the rename, the store
// is opened again on the same directory as the card does when power returns, and the record must be
// exactly the old bytes (or absent when there were none) or exactly the new ones; the owner, started
// again, must take it as stored.
#include <gtest/gtest.h>
#include <stdlib.h>

#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "card_records.h"
#include "card_records_harness.h"
#include "file_nv_store.h"
#include "web/password_store.h"

namespace {

namespace fs = std::filesystem;
using Bytes = std::vector<std::uint8_t>;
using firmware::test::CountingRandom;
using hal::host::FileNvStore;

class NvDirectory {
 public:
  NvDirectory() {
    std::string pattern = (fs::temp_directory_path() / "ipe-nv-cut-XXXXXX").string();
    EXPECT_NE(mkdtemp(pattern.data()), nullptr);
    dir_ = pattern;
  }
  ~NvDirectory() { fs::remove_all(dir_); }

  // The store as the card opens it at start (which deletes what an interrupted write left).
  std::unique_ptr<FileNvStore> Open() const {
    std::string error;
    auto store = FileNvStore::Open(dir_.string(), &error);
    EXPECT_TRUE(store.ok()) << error;
    return std::move(store.value());
  }

  // Record `id` as a fresh store reads it: its bytes, or nothing when it is absent.
  std::optional<Bytes> Record(hal::NvRecordId id) const {
    Bytes buffer(hal::kMaxRecordBytes);
    const base::Result<std::size_t> n = Open()->Read(id, buffer);
    if (n.status() == base::NotFound()) return std::nullopt;
    EXPECT_TRUE(n.ok()) << base::StatusName(n.status());
    if (!n.ok()) return Bytes{0xDE, 0xAD};  // never a valid record of any kind
    buffer.resize(*n);
    return buffer;
  }

  // `write` makes exactly one Write of record `id` on the store it is given. It runs once without a
  // cut to learn the new record, then, from the old state each time, once per cut. After each cut the
  // record must be `old` exactly (a cut before the rename) or the new one (after it), and `restarted`
  // (the owner starting again on a fresh store) is told which of the two it must see.
  void CheckEveryCut(hal::NvRecordId id, const std::function<void(hal::NvStore&)>& write,
                     const std::function<void(hal::NvStore&, bool new_expected)>& restarted) {
    const std::optional<Bytes> old = Record(id);
    const fs::path backup = dir_.string() + ".old";
    fs::remove_all(backup);
    fs::copy(dir_, backup);
    write(*Open());
    const std::optional<Bytes> fresh = Record(id);
    ASSERT_TRUE(fresh.has_value());
    ASSERT_NE(fresh, old) << "the write changed nothing: the test would prove nothing";
    const std::size_t file_size = FileNvStore::kHeaderBytes + fresh->size();

    const auto back_to_old = [&] {
      fs::remove_all(dir_);
      fs::copy(backup, dir_);
    };
    for (std::size_t cut = 0; cut <= file_size; ++cut) {
      back_to_old();
      {
        std::unique_ptr<FileNvStore> dying = Open();
        dying->CutPowerAfterBytesForTest(cut);
        write(*dying);
      }
      ASSERT_EQ(fs::file_size(dir_ / FileNvStore::TempFileName(id)), cut);  // what reached the disk
      ASSERT_EQ(Record(id), old) << "cut after " << cut << " of " << file_size << " bytes";
      ASSERT_FALSE(fs::exists(dir_ / FileNvStore::TempFileName(id))) << "cut after " << cut;
      std::unique_ptr<FileNvStore> store = Open();
      restarted(*store, false);
      ASSERT_FALSE(::testing::Test::HasFatalFailure()) << "cut after " << cut;
    }
    back_to_old();
    {
      std::unique_ptr<FileNvStore> dying = Open();
      dying->CutPowerAfterRenameForTest();
      write(*dying);
    }
    ASSERT_EQ(Record(id), fresh) << "cut after the rename";
    std::unique_ptr<FileNvStore> store = Open();
    restarted(*store, true);
    fs::remove_all(backup);
  }

 private:
  fs::path dir_;
};

TEST(NvRecordPowerCut, FactoryMacFirstWrite) {
  NvDirectory dir;
  // Cut before the rename: no MAC was ever kept, so the next start makes its own (and keeps it).
  dir.CheckEveryCut(firmware::kNvFactoryMac, firmware::test::MacFirstStart, firmware::test::ExpectMacAfterRestart);
}

TEST(NvRecordPowerCut, WebPasswordChange) {
  NvDirectory dir;
  {
    std::unique_ptr<FileNvStore> store = dir.Open();
    CountingRandom random;
    web::PasswordStore passwords(*store, firmware::kNvWebPasswords, random);
    ASSERT_EQ(passwords.Load().value(), web::PasswordSource::kDefaults);  // writes the defaults' record
  }
  const std::function<void(hal::NvStore&)> change = [](hal::NvStore& store) {
    CountingRandom random;
    web::PasswordStore passwords(store, firmware::kNvWebPasswords, random);
    ASSERT_EQ(passwords.Load().value(), web::PasswordSource::kStored);
    passwords.Set(web::PasswordKind::kWrite, "n3w write").IgnoreError();  // fails when the cut comes
  };
  int checked = 0;
  dir.CheckEveryCut(firmware::kNvWebPasswords, change, [&checked](hal::NvStore& store, bool new_expected) {
    CountingRandom random;
    web::PasswordStore passwords(store, firmware::kNvWebPasswords, random);
    // Stored: the record parsed whole (a damaged one would read as kDefaults and be rewritten).
    ASSERT_EQ(passwords.Load().value(), web::PasswordSource::kStored);
    // Hashing is slow: the passwords themselves are compared at the first cut and after the rename.
    if (checked++ > 0 && !new_expected) return;
    EXPECT_TRUE(passwords.Verify(web::PasswordKind::kRead, "USER"));
    EXPECT_EQ(passwords.Verify(web::PasswordKind::kWrite, "USER"), !new_expected);
    EXPECT_EQ(passwords.Verify(web::PasswordKind::kWrite, "n3w write"), new_expected);
  });
}

using TcpIpExtrasPowerCut = firmware::test::TcpIpExtrasFixture;

TEST_F(TcpIpExtrasPowerCut, TtlMulticastAndDomainChange) {
  StartLoaded();
  MakeWriter();
  NvDirectory dir;
  cip::TcpIpSettings old_settings;
  {
    std::unique_ptr<FileNvStore> store = dir.Open();
    firmware::CardTcpIp tcpip(netif_, addressing_, *writer_, *store);
    ASSERT_TRUE(tcpip.Configure(proxy_->config()).ok());
    old_settings = tcpip.StoredSettings();
    old_settings.ttl = 5;
    ASSERT_TRUE(old_settings.static_configuration.domain_name.Assign(std::string_view("old.example")));
    ASSERT_TRUE(tcpip.StoreSettings(old_settings).ok());
  }
  cip::TcpIpSettings new_settings = old_settings;
  new_settings.ttl = 32;
  new_settings.multicast = {1, 8, 0xEFC00140};
  new_settings.static_configuration.name_server = 0x0A000001;
  ASSERT_TRUE(new_settings.static_configuration.domain_name.Assign(std::string_view("a-longer-plant.example")));
  const std::function<void(hal::NvStore&)> change = [&](hal::NvStore& store) {
    firmware::CardTcpIp tcpip(netif_, addressing_, *writer_, store);
    ASSERT_TRUE(tcpip.Configure(proxy_->config()).ok());
    ASSERT_EQ(tcpip.StoredSettings(), old_settings);
    tcpip.StoreSettings(new_settings).IgnoreError();  // fails when the cut comes
  };
  dir.CheckEveryCut(firmware::kNvTcpIpExtras, change, [&](hal::NvStore& store, bool new_expected) {
    EXPECT_EQ(Restarted(store), new_expected ? new_settings : old_settings);
  });
}

}  // namespace
