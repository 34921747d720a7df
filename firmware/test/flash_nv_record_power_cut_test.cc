// The card's own NV records on a board's flash: the factory MAC, the web passwords and the TCP/IP
// settings' extras, each through the code that owns it and a hal::FlashNvStore on the flash the card
// needs (2 sectors of 4 KiB; docs/robustness.md "Power loss"). The spirit of nv_record_power_cut_test.cc
// on flash: for every step of the change (each byte programmed, each sector erase) power is cut, leaving
// a seeded random mix in the unit or sector being written; a store started afresh must read exactly the
// old record (or none) or exactly the new one, and the owner, started again, must take it as stored.
#include <gtest/gtest.h>

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "card_records.h"
#include "card_records_harness.h"
#include "fake_flash.h"
#include "hal/flash_nv_store.h"
#include "web/password_store.h"

namespace {

using Bytes = std::vector<std::uint8_t>;
using firmware::test::CountingRandom;
using hal::FlashNvStore;
using hal::test::CutMix;
using hal::test::FakeFlash;

// The flash the card needs (docs/robustness.md): two 4 KiB sectors; 8-byte program units as on a part
// with ECC (the larger the unit, the more each record takes).
constexpr std::size_t kSectorBytes = 4096;
constexpr std::size_t kSectors = 2;
constexpr std::size_t kProgramUnit = 8;

class CardFlash {
 public:
  // Runs `session` on a store started on this flash, as the card does at power-on.
  void Session(const std::function<void(hal::NvStore&)>& session) {
    FlashNvStore store(flash_);
    ASSERT_EQ(store.Mount(), base::OkStatus());
    session(store);
  }

  // Record `id` as a freshly started store reads it: its bytes, or nothing when it is absent.
  static std::optional<Bytes> Record(FakeFlash& flash, hal::NvRecordId id) {
    FlashNvStore store(flash);
    EXPECT_EQ(store.Mount(), base::OkStatus());
    Bytes buffer(hal::kMaxRecordBytes);
    const base::Result<std::size_t> n = store.Read(id, buffer);
    if (n.status() == base::NotFound()) return std::nullopt;
    EXPECT_TRUE(n.ok()) << base::StatusName(n.status());
    if (!n.ok()) return Bytes{0xDE, 0xAD};  // never a valid record of any kind
    buffer.resize(*n);
    return buffer;
  }
  std::optional<Bytes> Record(hal::NvRecordId id) { return Record(flash_, id); }

  // `change` changes record `id` on a store started on the flash, after `warm_up` (when given) made
  // other changes in the same session. It runs once without a cut to learn the new record, then, from
  // the same start each time, once per step the change takes with power cut there. After each cut the
  // record must be the old one exactly or the new one, and `restarted` (the owner starting again on a
  // fresh store) is told which of the two it must see. Returns the cuts tried.
  std::uint64_t CheckEveryCut(hal::NvRecordId id, const std::function<void(hal::NvStore&)>& change,
                              const std::function<void(hal::NvStore&, bool new_expected)>& restarted,
                              const std::function<void(hal::NvStore&)>& warm_up = nullptr) {
    const std::optional<Bytes> old = Record(id);
    const FakeFlash before = flash_;
    std::uint64_t first = 0;
    Session([&](hal::NvStore& store) {
      if (warm_up) warm_up(store);
      first = flash_.steps() - before.steps();
      change(store);
    });
    const std::uint64_t last = flash_.steps() - before.steps();
    const std::optional<Bytes> fresh = Record(id);
    EXPECT_TRUE(fresh.has_value());
    EXPECT_NE(fresh, old) << "the change changed nothing: the test would prove nothing";

    for (std::uint64_t cut = first; cut < last; ++cut) {
      const std::string where = "cut at step " + std::to_string(cut - first) + " of " + std::to_string(last - first);
      FakeFlash flash = before;
      {
        FlashNvStore dying(flash);
        EXPECT_EQ(dying.Mount(), base::OkStatus());
        if (warm_up) warm_up(dying);
        flash.CutPowerAtStep(before.steps() + cut, CutMix::kRandom, static_cast<std::uint32_t>(cut + 1));
        change(dying);
        EXPECT_FALSE(flash.powered()) << where;
        flash.PowerOn();
      }
      const std::optional<Bytes> seen = Record(flash, id);
      EXPECT_TRUE(seen == old || seen == fresh) << where;
      FlashNvStore store(flash);
      EXPECT_EQ(store.Mount(), base::OkStatus());
      restarted(store, seen == fresh);
      EXPECT_EQ(flash.violations(), 0) << where;
      if (::testing::Test::HasFailure()) {
        ADD_FAILURE() << where;
        break;
      }
    }
    return last - first;
  }

  FakeFlash& flash() { return flash_; }

 private:
  FakeFlash flash_{kSectorBytes, kSectors, kProgramUnit};
};

TEST(FlashNvRecords, TheCardsRecordsTakeAFifthOfASector) {
  // At the sizes the owners write them: MAC 6 bytes, passwords 107, TCP/IP extras 19..67.
  const std::size_t live = FlashNvStore::RecordFootprint(6, kProgramUnit) +
                           FlashNvStore::RecordFootprint(web::kPasswordNvBytes, kProgramUnit) +
                           FlashNvStore::RecordFootprint(19 + cip::kMaxDomainName, kProgramUnit);
  EXPECT_EQ(live, 40u + 144u + 104u);
  EXPECT_LE(FlashNvStore::SectorOverhead(kProgramUnit) + live, kSectorBytes / 5);
  // With the largest program unit the layout takes.
  const std::size_t unit = FlashNvStore::kMaxProgramUnit;
  EXPECT_EQ(FlashNvStore::SectorOverhead(unit) + FlashNvStore::RecordFootprint(6, unit) +
                FlashNvStore::RecordFootprint(web::kPasswordNvBytes, unit) +
                FlashNvStore::RecordFootprint(19 + cip::kMaxDomainName, unit),
            64u + 96u + 192u + 160u);
}

TEST(FlashNvRecords, FactoryMacFirstWrite) {
  CardFlash card;
  // Cut before the commit: no MAC was ever kept, so the next start makes its own (and keeps it).
  const std::uint64_t cuts = card.CheckEveryCut(firmware::kNvFactoryMac, firmware::test::MacFirstStart,
                                                firmware::test::ExpectMacAfterRestart);
  // Formatting: an erase, the sector header and commit, the record.
  EXPECT_EQ(cuts, 1 + 16 + 8 + FlashNvStore::RecordFootprint(6, kProgramUnit));
}

TEST(FlashNvRecords, WebPasswordChanges) {
  CardFlash card;
  card.Session([](hal::NvStore& store) {
    CountingRandom random;
    firmware::LoadOrCreateMac(store, random);
    web::PasswordStore passwords(store, firmware::kNvWebPasswords, random);
    ASSERT_EQ(passwords.Load().value(), web::PasswordSource::kDefaults);  // writes the defaults' record
  });
  ASSERT_EQ(card.Record(firmware::kNvWebPasswords)->size(), web::kPasswordNvBytes);
  const auto set = [](web::PasswordKind kind, std::string_view password) {
    return [kind, password](hal::NvStore& store) {
      CountingRandom random;
      web::PasswordStore passwords(store, firmware::kNvWebPasswords, random);
      ASSERT_EQ(passwords.Load().value(), web::PasswordSource::kStored);
      passwords.Set(kind, password).IgnoreError();  // fails when the cut comes
    };
  };
  int checked = 0;
  // The passwords after a restart: `write` and `read` are the ones stored. Hashing is slow: they are
  // compared at every 16th cut only; that the record parsed whole is checked at every one.
  const auto expect = [&checked](hal::NvStore& store, std::string_view write, std::string_view read) {
    CountingRandom random;
    web::PasswordStore passwords(store, firmware::kNvWebPasswords, random);
    ASSERT_EQ(passwords.Load().value(), web::PasswordSource::kStored);  // a damaged one reads as kDefaults
    if (checked++ % 16 != 0) return;
    EXPECT_TRUE(passwords.Verify(web::PasswordKind::kWrite, write));
    EXPECT_TRUE(passwords.Verify(web::PasswordKind::kRead, read));
  };

  // The first change since the start: a compaction (erase, header, the MAC and the new record, commit).
  const std::uint64_t compacting = card.CheckEveryCut(
      firmware::kNvWebPasswords, set(web::PasswordKind::kWrite, "n3w write"),
      [&](hal::NvStore& store, bool new_expected) { expect(store, new_expected ? "n3w write" : "USER", "USER"); });
  EXPECT_EQ(compacting, 1 + 16 + 8 + FlashNvStore::RecordFootprint(6, kProgramUnit) +
                            FlashNvStore::RecordFootprint(web::kPasswordNvBytes, kProgramUnit));
  // A later change in a session (after another record's): appended.
  const std::uint64_t appended = card.CheckEveryCut(
      firmware::kNvWebPasswords, set(web::PasswordKind::kRead, "n3w read"),
      [&](hal::NvStore& store, bool new_expected) { expect(store, "n3w write", new_expected ? "n3w read" : "USER"); },
      [](hal::NvStore& store) { ASSERT_EQ(store.Write(0x7000, Bytes{1}), base::OkStatus()); });
  EXPECT_EQ(appended, FlashNvStore::RecordFootprint(web::kPasswordNvBytes, kProgramUnit));
}

using FlashTcpIpExtrasPowerCut = firmware::test::TcpIpExtrasFixture;

TEST_F(FlashTcpIpExtrasPowerCut, TtlMulticastAndDomainChange) {
  StartLoaded();
  MakeWriter();
  CardFlash card;
  cip::TcpIpSettings old_settings;
  card.Session([&](hal::NvStore& store) {
    CountingRandom random;
    firmware::LoadOrCreateMac(store, random);
    firmware::CardTcpIp tcpip(netif_, addressing_, *writer_, store);
    ASSERT_TRUE(tcpip.Configure(proxy_->config()).ok());
    old_settings = tcpip.StoredSettings();
    old_settings.ttl = 5;
    ASSERT_TRUE(old_settings.static_configuration.domain_name.Assign(std::string_view("old.example")));
    ASSERT_TRUE(tcpip.StoreSettings(old_settings).ok());
  });
  ASSERT_EQ(card.Record(firmware::kNvTcpIpExtras)->size(), 19u + 11u);
  cip::TcpIpSettings new_settings = old_settings;
  new_settings.ttl = 32;
  new_settings.multicast = {1, 8, 0xEFC00140};
  new_settings.static_configuration.name_server = 0x0A000001;
  ASSERT_TRUE(new_settings.static_configuration.domain_name.Assign(
      std::string_view("a-domain-name-of-the-largest-size-cip-allows.com")));
  ASSERT_EQ(new_settings.static_configuration.domain_name.bytes().size(), cip::kMaxDomainName);
  const std::function<void(hal::NvStore&)> change = [&](hal::NvStore& store) {
    firmware::CardTcpIp tcpip(netif_, addressing_, *writer_, store);
    ASSERT_TRUE(tcpip.Configure(proxy_->config()).ok());
    ASSERT_EQ(tcpip.StoredSettings(), old_settings);
    tcpip.StoreSettings(new_settings).IgnoreError();  // fails when the cut comes
  };
  const std::uint64_t cuts =
      card.CheckEveryCut(firmware::kNvTcpIpExtras, change, [&](hal::NvStore& store, bool new_expected) {
        EXPECT_EQ(Restarted(store), new_expected ? new_settings : old_settings);
      });
  // A compaction: an erase, the sector header and commit, the MAC and the new record.
  EXPECT_EQ(cuts, 1 + 16 + 8 + FlashNvStore::RecordFootprint(6, kProgramUnit) +
                      FlashNvStore::RecordFootprint(19 + cip::kMaxDomainName, kProgramUnit));
  EXPECT_EQ(card.Record(firmware::kNvTcpIpExtras)->size(), 19u + cip::kMaxDomainName);
  EXPECT_EQ(card.Record(firmware::kNvFactoryMac)->size(), 6u) << "the MAC carried through the compactions";
}

}  // namespace
