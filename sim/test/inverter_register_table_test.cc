#include "sim/register_table.h"

#include <gtest/gtest.h>

#include <cstddef>
#include <cstdint>
#include <optional>
#include <set>
#include <string>
#include <string_view>

namespace sim {
namespace {

// Looks `number` up and fails the test (returning a harmless row) when it is missing.
const RegisterInfo& Get(std::uint16_t number) {
  static constexpr RegisterInfo kMissing{0xFFFF, "?", "?", StorageClass::kMonitor, Access::kReadOnly,
                                         {0, 0, 0}, {0, 0, 0}, {Unit::kNone, 0}, false, false,
                                         ModelMask::kBoth};
  const RegisterInfo* info = FindRegister(number);
  EXPECT_NE(info, nullptr) << "no register 0x" << std::hex << number;
  return info != nullptr ? *info : kMissing;
}

TEST(InverterRegisterTable, IsSortedByNumberWithoutDuplicates) {
  const auto all = AllRegisters();
  ASSERT_GT(all.size(), 200u);
  for (std::size_t i = 1; i < all.size(); ++i) EXPECT_LT(all[i - 1].number, all[i].number) << all[i].title;
}

TEST(InverterRegisterTable, NoNumberEndsInAToF) {
  for (const RegisterInfo& r : AllRegisters()) {
    EXPECT_LE(r.number & 0xF, 9) << r.title;
    EXPECT_TRUE(CommunicationNumberMayExist(r.number)) << r.title;
  }
}

TEST(InverterRegisterTable, CommunicationNumberMayExistRejectsHexLetterEndings) {
  EXPECT_TRUE(CommunicationNumberMayExist(0x0009));
  EXPECT_FALSE(CommunicationNumberMayExist(0x000A));  // the 2-word read at acc skips to dec (0x0010)
  EXPECT_FALSE(CommunicationNumberMayExist(0x000F));
  EXPECT_TRUE(CommunicationNumberMayExist(0x0010));
  EXPECT_FALSE(CommunicationNumberMayExist(0xFE0A));
  EXPECT_TRUE(CommunicationNumberMayExist(0xFA06));  // an A elsewhere is fine
  EXPECT_FALSE(CommunicationNumberMayExist(0xFFFF));
}

TEST(InverterRegisterTable, UnknownNumbersDoNotExist) {
  EXPECT_EQ(FindRegister(0x000A), nullptr);
  EXPECT_EQ(FindRegister(0x0001), nullptr);
  EXPECT_EQ(FindRegister(0xFFFF), nullptr);  // Modbus write to FFFFH gets exception 02 (E6581913 p.31)
  EXPECT_EQ(FindRegister(0xFA52), nullptr);  // AM output: VF-AS3 only
  EXPECT_EQ(FindRegister(0xC150), nullptr);  // PROFIBUS option parameters are not the IPE002Z's
  EXPECT_EQ(FindRegister(0x0000, Model::kVfS15)->title, std::string_view("au1"));
}

TEST(InverterRegisterTable, EveryRowIsConsistent) {
  std::set<std::string> titles;
  for (const RegisterInfo& r : AllRegisters()) {
    for (Model m : {Model::kVfMb1, Model::kVfS15}) {
      EXPECT_LE(r.min(m), r.default_value(m)) << r.title;
      EXPECT_LE(r.default_value(m), r.max(m)) << r.title;
    }
    std::string lower;
    for (const char* c = r.title; *c != '\0'; ++c) {
      lower.push_back((*c >= 'A' && *c <= 'Z') ? static_cast<char>(*c - 'A' + 'a') : *c);
    }
    EXPECT_EQ(lower, r.title) << "titles are lower case";
    EXPECT_TRUE(titles.insert(lower).second) << "duplicate title " << r.title;
    if (r.storage == StorageClass::kMonitor || r.storage == StorageClass::kTripHold) {
      EXPECT_FALSE(r.HostWritable()) << r.title;
      EXPECT_FALSE(r.write_during_run) << r.title;
    }
    const unsigned area = r.number >> 8;
    if (area == 0xFB || area == 0xFC || area == 0xFD || area == 0xFE) {
      EXPECT_TRUE(r.storage == StorageClass::kMonitor || r.storage == StorageClass::kTripHold) << r.title;
    }
    if (area == 0xFA) {
      EXPECT_EQ(r.storage, StorageClass::kRamOnly) << r.title;
    }
  }
}

// Seed 000 section 3.1: c500 protocol, 0-1, default 0, (*3) effective after reset; comm no 0xC500.
TEST(InverterRegisterTable, C500IsTheProtocolParameter) {
  const RegisterInfo& c500 = Get(0xC500);
  EXPECT_STREQ(c500.title, "c500");
  EXPECT_EQ(c500.storage, StorageClass::kEeprom);
  for (Model m : {Model::kVfMb1, Model::kVfS15}) {
    EXPECT_EQ(c500.min(m), 0);
    EXPECT_EQ(c500.max(m), 1);
    EXPECT_EQ(c500.default_value(m), 0);
  }
  EXPECT_TRUE(c500.effective_after_reset);
  EXPECT_TRUE(c500.HostWritable());
}

TEST(InverterRegisterTable, CParametersFollowSeed000Section3) {
  // Scanner menus: c001-c006 0-17 defaults 1,3,0,0,0,0; c021-c026 0-35 defaults 1,2,0,0,0,0; all (*3).
  const std::int32_t in_defaults[] = {1, 3, 0, 0, 0, 0};
  const std::int32_t out_defaults[] = {1, 2, 0, 0, 0, 0};
  for (std::uint16_t k = 0; k < 6; ++k) {
    const RegisterInfo& in = Get(static_cast<std::uint16_t>(0xC001 + k));
    EXPECT_EQ(in.max(Model::kVfMb1), 17);
    EXPECT_EQ(in.default_value(Model::kVfMb1), in_defaults[k]);
    EXPECT_TRUE(in.effective_after_reset);
    const RegisterInfo& out = Get(static_cast<std::uint16_t>(0xC021 + k));
    EXPECT_EQ(out.max(Model::kVfS15), 35);
    EXPECT_EQ(out.default_value(Model::kVfS15), out_defaults[k]);
    EXPECT_TRUE(out.effective_after_reset);
  }
  // Device name: one ASCII character per parameter, c081-c096 (0xC081-0xC096, all decimal digits).
  for (std::uint16_t n = 0xC081; n <= 0xC096; ++n) {
    if (!CommunicationNumberMayExist(n)) {
      EXPECT_EQ(FindRegister(n), nullptr);
      continue;
    }
    EXPECT_EQ(Get(n).scale.unit, Unit::kAscii);
  }
  EXPECT_EQ(FindRegister(0xC097), nullptr);
  // Loss handling: c100 0.0-100.0 s; c101 0-5 default 4; c102 0-15; c103 0-2 default 0 (seed 000 wins).
  EXPECT_EQ(Get(0xC100).max(Model::kVfMb1), 1000);
  EXPECT_EQ(Get(0xC100).scale.decimals, 1);
  EXPECT_EQ(Get(0xC101).default_value(Model::kVfMb1), 4);
  EXPECT_EQ(Get(0xC101).max(Model::kVfMb1), 5);
  EXPECT_EQ(Get(0xC102).max(Model::kVfMb1), 15);
  EXPECT_EQ(Get(0xC103).default_value(Model::kVfS15), 0);
  EXPECT_FALSE(Get(0xC100).effective_after_reset);
  // c523 time-out: default 2 s, in 0.1 s; c554 web server default 1; c604 IO scan default 0.
  EXPECT_EQ(Get(0xC523).default_value(Model::kVfMb1), 20);
  EXPECT_EQ(Get(0xC554).default_value(Model::kVfMb1), 1);
  EXPECT_TRUE(Get(0xC554).effective_after_reset);
  EXPECT_EQ(Get(0xC604).default_value(Model::kVfMb1), 0);
  // Every c5xx/c6xx of section 3 exists: c500-c536, c554, c555, c600-c604.
  for (std::uint16_t n = 0xC500; n <= 0xC536; ++n) {
    if (CommunicationNumberMayExist(n)) {
      EXPECT_NE(FindRegister(n), nullptr) << std::hex << n;
    }
  }
  const std::uint16_t others[] = {0xC554, 0xC555, 0xC600, 0xC601, 0xC602, 0xC603, 0xC604};
  for (std::uint16_t n : others) {
    EXPECT_NE(FindRegister(n), nullptr) << std::hex << n;
  }
  // Values the card writes back are not host-writable.
  const std::uint16_t written_by_card[] = {0xC502, 0xC503, 0xC517, 0xC522, 0xC524, 0xC535, 0xC536, 0xC555};
  for (std::uint16_t n : written_by_card) {
    EXPECT_EQ(Get(n).access, Access::kOption) << std::hex << n;
    EXPECT_FALSE(Get(n).HostWritable()) << std::hex << n;
  }
}

TEST(InverterRegisterTable, BasicParameters) {
  const RegisterInfo& acc = Get(0x0009);
  EXPECT_STREQ(acc.title, "acc");
  EXPECT_EQ(acc.scale.unit, Unit::kSecond);
  EXPECT_EQ(acc.scale.decimals, 1);  // 0.1 s: 5 s is written as 0x32 (seed 000 section 4.8)
  EXPECT_TRUE(acc.write_during_run);
  EXPECT_EQ(acc.storage, StorageClass::kEeprom);
  EXPECT_STREQ(Get(0x0010).title, "dec");
  EXPECT_EQ(Get(0x0010).max(Model::kVfMb1), 60000);  // 6000 s
  EXPECT_STREQ(Get(0x0003).title, "cmod");
  EXPECT_EQ(Get(0x0003).default_value(Model::kVfMb1), 1);
  EXPECT_EQ(Get(0x0003).max(Model::kVfS15), 4);
  EXPECT_FALSE(Get(0x0011).write_during_run);  // fh: the manuals' example of a refused write
  EXPECT_EQ(Get(0x0011).scale.decimals, 2);
  EXPECT_STREQ(Get(0x0018).title, "sr1");
  EXPECT_STREQ(Get(0x0024).title, "sr7");
  EXPECT_STREQ(Get(0x0287).title, "f287");  // preset speed 8
  EXPECT_STREQ(Get(0x0294).title, "f294");  // preset speed 15
  EXPECT_EQ(FindRegister(0x0295), nullptr);
  // f856 pole pairs 1-8 default 2; f899 communication reset 0-1 default 0, reads 0 after execution.
  EXPECT_EQ(Get(0x0856).min(Model::kVfMb1), 1);
  EXPECT_EQ(Get(0x0856).max(Model::kVfMb1), 8);
  EXPECT_EQ(Get(0x0856).default_value(Model::kVfMb1), 2);
  EXPECT_EQ(Get(0x0899).max(Model::kVfMb1), 1);
  EXPECT_EQ(Get(0x0899).storage, StorageClass::kRamOnly);
  // f829 protocol and f800 baud rate take effect after a reset (E6581913 p.4-5).
  EXPECT_TRUE(Get(0x0829).effective_after_reset);
  EXPECT_TRUE(Get(0x0800).effective_after_reset);
  EXPECT_EQ(Get(0x0880).max(Model::kVfMb1), 65535);
}

// fmod 12-14 are VF-S15 only (seed 000 section 3.1 (*1)): the models' limits differ.
TEST(InverterRegisterTable, PerModelLimits) {
  const RegisterInfo& fmod = Get(0x0004);
  EXPECT_EQ(fmod.max(Model::kVfMb1), 11);
  EXPECT_EQ(fmod.max(Model::kVfS15), 14);
  EXPECT_TRUE(fmod.InRange(Model::kVfS15, 14));
  EXPECT_FALSE(fmod.InRange(Model::kVfMb1, 14));
  EXPECT_TRUE(fmod.AppliesTo(Model::kVfMb1));
  EXPECT_TRUE(fmod.AppliesTo(Model::kVfS15));
  EXPECT_EQ(Get(0xFE70).default_value(Model::kVfMb1), 48);  // the 4.8 A drive of seed 000 section 3.2.4.9
}

TEST(InverterRegisterTable, CommandRegistersAreRamOnly) {
  const std::uint16_t commands[] = {0xFA00, 0xFA01, 0xFA06, 0xFA07, 0xFA23, 0xFA50, 0xFA51};
  for (std::uint16_t n : commands) {
    const RegisterInfo& r = Get(n);
    EXPECT_EQ(r.storage, StorageClass::kRamOnly) << r.title;
    EXPECT_TRUE(r.write_during_run) << r.title;
    EXPECT_TRUE(r.HostWritable()) << r.title;
  }
  EXPECT_EQ(Get(0xFA07).scale.unit, Unit::kHertz);
  EXPECT_EQ(Get(0xFA07).scale.decimals, 2);
  EXPECT_TRUE(Get(0xFA07).InRange(Model::kVfMb1, 0x1F40));  // 80 Hz
  EXPECT_EQ(Get(0xFA50).max(Model::kVfMb1), 3);
  EXPECT_EQ(Get(0xFA51).max(Model::kVfMb1), 1000);
  // FA20/FA26 exist on VF-S11 only; FA03 likewise.
  EXPECT_EQ(FindRegister(0xFA20), nullptr);
  EXPECT_EQ(FindRegister(0xFA26), nullptr);
  EXPECT_EQ(FindRegister(0xFA03), nullptr);
}

TEST(InverterRegisterTable, Monitors) {
  const RegisterInfo& fd01 = Get(0xFD01);
  EXPECT_EQ(fd01.storage, StorageClass::kMonitor);
  EXPECT_EQ(fd01.access, Access::kReadOnly);
  EXPECT_FALSE(fd01.HostWritable());
  EXPECT_EQ(fd01.scale.unit, Unit::kBits);
  EXPECT_EQ(Get(0xFD00).scale.decimals, 2);
  EXPECT_EQ(Get(0xFD03).scale.unit, Unit::kPercent);
  EXPECT_EQ(Get(0xFE70).scale.decimals, 1);  // 0.1 A
  for (std::uint16_t n = 0xFE10; n <= 0xFE13; ++n) EXPECT_EQ(Get(n).storage, StorageClass::kTripHold);
  EXPECT_EQ(Get(0xFC90).storage, StorageClass::kMonitor);
  EXPECT_EQ(Get(0xFB05).storage, StorageClass::kMonitor);
}

// FE36 (VIB) is signed, -100.00..+100.00 % = 0xD8F0..0x2710 (seed 000 section 3.2.4.10).
TEST(InverterRegisterTable, SignedRegistersUseTwosComplementWords) {
  const RegisterInfo& vib = Get(0xFE36);
  EXPECT_TRUE(vib.is_signed());
  EXPECT_EQ(vib.min(Model::kVfMb1), -10000);
  EXPECT_EQ(vib.max(Model::kVfMb1), 10000);
  EXPECT_EQ(vib.ToWord(-10000), 0xD8F0);
  EXPECT_EQ(vib.FromWord(0xD8F0), -10000);
  EXPECT_EQ(vib.FromWord(0x2710), 10000);
  const RegisterInfo& via = Get(0xFE35);
  EXPECT_FALSE(via.is_signed());
  EXPECT_EQ(via.FromWord(0xD8F0), 0xD8F0);
  EXPECT_EQ(via.max(Model::kVfS15), 10000);
}

TEST(InverterRegisterTable, LookupByTitleIgnoresCase) {
  EXPECT_EQ(FindRegisterByTitle("acc"), FindRegister(0x0009));
  EXPECT_EQ(FindRegisterByTitle("ACC"), FindRegister(0x0009));
  EXPECT_EQ(FindRegisterByTitle("Acc"), FindRegister(0x0009));
  EXPECT_EQ(FindRegisterByTitle("FA06"), FindRegister(0xFA06));
  EXPECT_EQ(FindRegisterByTitle("fa06"), FindRegister(0xFA06));
  EXPECT_EQ(FindRegisterByTitle("c500"), FindRegister(0xC500));
  EXPECT_EQ(FindRegisterByTitle("C500"), FindRegister(0xC500));
  EXPECT_EQ(FindRegisterByTitle("F856"), FindRegister(0x0856));
  EXPECT_EQ(FindRegisterByTitle("vlv"), FindRegister(0x0409));
  EXPECT_NE(FindRegisterByTitle("acc"), nullptr);
  EXPECT_EQ(FindRegisterByTitle("ac"), nullptr);
  EXPECT_EQ(FindRegisterByTitle("accx"), nullptr);
  EXPECT_EQ(FindRegisterByTitle(""), nullptr);
  EXPECT_EQ(FindRegisterByTitle("0009"), nullptr);
}

// requirements.md PAR-1 and PAR-2: every register the scanner menus c001-c006 and c021-c026 reach.
TEST(InverterRegisterTable, EveryScannerMenuRegisterExists) {
  const std::uint16_t inputs[] = {0xFA06, 0xFA23, 0xFA07, 0xFA50, 0xFA51, 0x0601,
                                  0x0009, 0x0010, 0x0012, 0x0016, 0x0409};
  for (std::uint16_t n : inputs) {
    const RegisterInfo* r = FindRegister(n);
    ASSERT_NE(r, nullptr) << std::hex << n;
    EXPECT_TRUE(r->HostWritable()) << r->title;
    EXPECT_TRUE(r->AppliesTo(Model::kVfMb1) && r->AppliesTo(Model::kVfS15)) << r->title;
  }
  EXPECT_STREQ(Get(0x0012).title, "ul");
  EXPECT_STREQ(Get(0x0016).title, "vb");
  EXPECT_STREQ(Get(0x0409).title, "vlv");
  EXPECT_EQ(Get(0x0016).scale.decimals, 1);  // 0.1 %
  EXPECT_EQ(Get(0x0409).scale.unit, Unit::kVolt);
  const std::uint16_t outputs[] = {0xFD01, 0xFD00, 0xFD03, 0xFD05, 0xFC91, 0xFD22, 0xFD06, 0xFD07,
                                   0xFE36, 0xFE35, 0xFE37, 0xFD04, 0xFD16, 0xFD18, 0x0880, 0xFD29,
                                   0xFD30, 0xFE14, 0xFE40, 0xFD20, 0xFD23, 0xFD24, 0xFD25, 0xFD26,
                                   0xFD27, 0xFE56, 0xFE70, 0xFE76, 0xFE77, 0xFD83};
  for (std::uint16_t n : outputs) {
    const RegisterInfo* r = FindRegister(n);
    ASSERT_NE(r, nullptr) << std::hex << n;
    EXPECT_TRUE(r->AppliesTo(Model::kVfMb1) && r->AppliesTo(Model::kVfS15)) << r->title;
  }
}

TEST(InverterRegisterTable, ModelNames) {
  EXPECT_EQ(ModelFromName("vf-mb1"), Model::kVfMb1);
  EXPECT_EQ(ModelFromName("vf-s15"), Model::kVfS15);
  EXPECT_EQ(ModelFromName("vf-s11"), std::nullopt);
  EXPECT_STREQ(ModelName(Model::kVfS15), "vf-s15");
  EXPECT_STREQ(StorageClassName(StorageClass::kTripHold), "trip-hold");
}

}  // namespace
}  // namespace sim
