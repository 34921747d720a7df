// Access to the drive while a Modbus IO scanning master is configured (seed 000 §9, MB-4; docs/modbus.md
// "Unit 255", docs/security.md "Modbus: the IO scanning master"): unit 255 only for the master c600-c603,
// and the control registers (FA00-FAFF, cmod, fmod, f207, f899) closed to every other client through
// units 0-248 (exception 02, nothing written), while reads and other parameters stay open to everyone.
#include <gtest/gtest.h>

#include <vector>

#include "drive_link/drive_registers.h"
#include "modbus_fakes.h"

namespace modbus {
namespace {

using test::Bytes;
using test::ServerHarness;
using Access = test::FakeDriveRegisters::Access;
using drive_link::WriteMode;

// FC 06 to unit 1: `number` = `value`, transaction 0x0031.
Bytes WriteSingle(std::uint16_t number, std::uint16_t value) {
  return {0x00, 0x31, 0x00, 0x00, 0x00, 0x06, 0x01, 0x06, static_cast<std::uint8_t>(number >> 8),
          static_cast<std::uint8_t>(number), static_cast<std::uint8_t>(value >> 8), static_cast<std::uint8_t>(value)};
}
const Bytes kWriteSingleRefused = {0x00, 0x31, 0x00, 0x00, 0x00, 0x03, 0x01, 0x86, 0x02};

class ModbusMasterLockTest : public ::testing::Test {
 protected:
  void SetUp() override {
    config_.io_scanning = true;
    config_.modbus_master = test::kClientAddress;  // 192.168.1.30
    h_.server.Configure(config_);
    h_.drive.registers = {{0x0003, 4},   {0x0004, 7},   {0x0009, 100}, {0x0010, 100}, {0x0207, 1},
                          {0x0899, 0},   {0xFA00, 0},   {0xFA06, 0},   {0xFA07, 0},   {0xFA23, 0},
                          {0xFA50, 0},   {0xFA51, 0},   {0xC600, 192}};
    master_ = h_.Connect(test::kClientAddress);
    other_ = h_.Connect(test::kOtherAddress);
  }

  config::CardConfig config_;
  ServerHarness h_;
  ConnectionId master_ = 0;
  ConnectionId other_ = 0;
};

TEST_F(ModbusMasterLockTest, OtherClient_EveryControlRegisterRefused02NothingWritten) {
  for (const std::uint16_t number : std::vector<std::uint16_t>{0xFA00, 0xFA06, 0xFA07, 0xFA23, 0xFA50, 0xFA51, 0x0003,
                                                               0x0004, 0x0207, 0x0899}) {
    SCOPED_TRACE(number);
    EXPECT_EQ(h_.Exchange(other_, WriteSingle(number, 1)), kWriteSingleRefused);
  }
  EXPECT_TRUE(h_.drive.log.empty());
}

TEST_F(ModbusMasterLockTest, OtherClient_MultipleWriteReachingTheCommandArea_Refused02BeforeAnyWrite) {
  // FC 16 from F9F9 (no such register, but it exists as an address) over FA00: the lock is a precheck.
  EXPECT_EQ(h_.Exchange(other_, {0x00, 0x32, 0x00, 0x00, 0x00, 0x0B, 0x01, 0x10, 0xF9, 0xF9, 0x00, 0x02, 0x04, 0x00,
                                 0x01, 0x00, 0x02}),
            (Bytes{0x00, 0x32, 0x00, 0x00, 0x00, 0x03, 0x01, 0x90, 0x02}));
  EXPECT_TRUE(h_.drive.log.empty());
}

TEST_F(ModbusMasterLockTest, OtherClient_ParametersAndReadsStayOpen) {
  EXPECT_EQ(h_.Exchange(other_, {0x00, 0x33, 0x00, 0x00, 0x00, 0x0B, 0x01, 0x10, 0x00, 0x09, 0x00, 0x02, 0x04, 0x00,
                                 0x32, 0x00, 0x33}),
            (Bytes{0x00, 0x33, 0x00, 0x00, 0x00, 0x06, 0x01, 0x10, 0x00, 0x09, 0x00, 0x02}));
  EXPECT_EQ(h_.Exchange(other_, {0x00, 0x34, 0x00, 0x00, 0x00, 0x06, 0x01, 0x03, 0xFA, 0x06, 0x00, 0x01}),
            (Bytes{0x00, 0x34, 0x00, 0x00, 0x00, 0x05, 0x01, 0x03, 0x02, 0x00, 0x00}));
  EXPECT_EQ(h_.drive.log, (std::vector<Access>{{true, 0x0009, 0x32, WriteMode::kRamAndEeprom},
                                               {true, 0x0010, 0x33, WriteMode::kRamAndEeprom},
                                               {false, 0xFA06, 0, WriteMode::kRamAndEeprom}}));
}

TEST_F(ModbusMasterLockTest, Master_WritesControlRegistersThatAreNotScannerTargets) {
  EXPECT_EQ(h_.Exchange(master_, WriteSingle(0xFA23, 0x0080)),
            (Bytes{0x00, 0x31, 0x00, 0x00, 0x00, 0x06, 0x01, 0x06, 0xFA, 0x23, 0x00, 0x80}));
  EXPECT_EQ(h_.drive.registers[0xFA23], 0x0080);
}

TEST_F(ModbusMasterLockTest, Master_ScannerTargetsStayReservedForTheScanner) {
  h_.scanner.targets = {0xFA06, 0xFA07};
  EXPECT_EQ(h_.Exchange(master_, WriteSingle(0xFA07, 6000)), kWriteSingleRefused);
  EXPECT_TRUE(h_.drive.log.empty());
}

TEST_F(ModbusMasterLockTest, OtherClient_EveryUnit255FunctionRefused01ButIdentityAnswered) {
  const Bytes read = {0x00, 0x41, 0x00, 0x00, 0x00, 0x06, 0xFF, 0x03, 0x00, 0x01, 0x00, 0x02};
  const Bytes write_single = {0x00, 0x42, 0x00, 0x00, 0x00, 0x06, 0xFF, 0x06, 0x00, 0x01, 0x04, 0x00};
  const Bytes write_multiple = {0x00, 0x43, 0x00, 0x00, 0x00, 0x09, 0xFF, 0x10, 0x00, 0x01,
                                0x00, 0x01, 0x02, 0x04, 0x00};
  EXPECT_EQ(h_.Exchange(other_, read), (Bytes{0x00, 0x41, 0x00, 0x00, 0x00, 0x03, 0xFF, 0x83, 0x01}));
  EXPECT_EQ(h_.Exchange(other_, write_single), (Bytes{0x00, 0x42, 0x00, 0x00, 0x00, 0x03, 0xFF, 0x86, 0x01}));
  EXPECT_EQ(h_.Exchange(other_, write_multiple), (Bytes{0x00, 0x43, 0x00, 0x00, 0x00, 0x03, 0xFF, 0x90, 0x01}));
  EXPECT_EQ(h_.scanner.set_calls, 0);
  // The master: the same three served.
  EXPECT_EQ(h_.Exchange(master_, write_single), write_single);
  EXPECT_EQ(h_.scanner.set_calls, 1);
  // FC 43 on unit 255 is the board's identity, for anybody.
  const Bytes identity = h_.Exchange(other_, {0x00, 0x44, 0x00, 0x00, 0x00, 0x05, 0xFF, 0x2B, 0x0E, 0x01, 0x00});
  ASSERT_GE(identity.size(), 9u);
  EXPECT_EQ(identity[7], 0x2B);
}

TEST_F(ModbusMasterLockTest, NoMasterConfigured_NobodyIsLockedOut) {
  config_.modbus_master = {0, 0, 0, 0};
  h_.server.Configure(config_);
  EXPECT_EQ(h_.Exchange(other_, WriteSingle(0xFA23, 1)),
            (Bytes{0x00, 0x31, 0x00, 0x00, 0x00, 0x06, 0x01, 0x06, 0xFA, 0x23, 0x00, 0x01}));
}

TEST_F(ModbusMasterLockTest, IoScanningOff_NobodyIsLockedOut) {
  config_.io_scanning = false;
  h_.server.Configure(config_);
  EXPECT_EQ(h_.Exchange(other_, WriteSingle(0x0899, 1)),
            (Bytes{0x00, 0x31, 0x00, 0x00, 0x00, 0x06, 0x01, 0x06, 0x08, 0x99, 0x00, 0x01}));
}

TEST(ModbusControlLockFor, OnlyWithIoScanningAndAMasterAndAnotherPeer) {
  config::CardConfig config;
  config.io_scanning = true;
  config.modbus_master = {10, 0, 0, 1};
  EXPECT_TRUE(ControlLockedFor(config, {10, 0, 0, 2}));
  EXPECT_FALSE(ControlLockedFor(config, {10, 0, 0, 1}));
  config.modbus_master = {0, 0, 0, 0};
  EXPECT_FALSE(ControlLockedFor(config, {10, 0, 0, 2}));
  config.modbus_master = {10, 0, 0, 1};
  config.io_scanning = false;
  EXPECT_FALSE(ControlLockedFor(config, {10, 0, 0, 2}));
}

TEST(ControlRegisters, TheCommandAreaTheCommandSourcesAndTheReset) {
  namespace reg = drive_link::reg;
  EXPECT_TRUE(reg::IsControlRegister(0xFA00));
  EXPECT_TRUE(reg::IsControlRegister(0xFAFF));
  EXPECT_FALSE(reg::IsControlRegister(0xF9FF));
  EXPECT_FALSE(reg::IsControlRegister(0xFB00));
  EXPECT_TRUE(reg::IsControlRegister(reg::kCmod));
  EXPECT_TRUE(reg::IsControlRegister(reg::kFmod));
  EXPECT_TRUE(reg::IsControlRegister(reg::kF207));
  EXPECT_TRUE(reg::IsControlRegister(reg::kF899));
  EXPECT_FALSE(reg::IsControlRegister(reg::kAcc));
  EXPECT_FALSE(reg::IsControlRegister(reg::kC600));
}

}  // namespace
}  // namespace modbus
