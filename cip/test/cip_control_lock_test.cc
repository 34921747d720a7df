// The exclusive-owner write lock (cip/drive/control_lock.h, docs/security.md "Exclusive-owner write lock")
// through the message router with the real drive objects: while an exclusive owner from 10.0.0.1 is
// open, control requests from any other IP address get 0x10 before the object sees them (nothing
// changes, no drive access starts); the owner's own IP address and every Get pass; without an owner
// nothing is locked. And the Connection Manager's part: an exclusive owner from another originator is
// refused with 0x0106.
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "cip/drive/control_lock.h"
#include "cip/drive/parameter_object.h"
#include "cip_connection_fakes.h"
#include "drive_channel_fake.h"

namespace cip::drive {
namespace {

using Access = drive_link::test::ScriptedDriveRegisters::Access;
using test::Bytes;
using test::Hex;

constexpr base::Ipv4Address kOwner{10, 0, 0, 1};
constexpr base::Ipv4Address kStranger{10, 0, 0, 2};

// The Connection Manager's answer, without the connections: who owns the drive.
class FakeConnectionTable final : public ConnectionTable {
 public:
  std::size_t ListConnections(std::span<ConnectionInfo>) const override { return 0; }
  bool IsOwned(std::uint32_t) const override { return false; }
  bool OwnedByAnotherOriginator(base::Ipv4Address originator) const override {
    return owner.has_value() && *owner != originator;
  }
  ExtendedDeviceStatus IoStatus() const override { return ExtendedDeviceStatus::kNoIoConnections; }

  std::optional<base::Ipv4Address> owner;
};

// An Identity object stand-in that only counts the Resets that reach it.
class CountingIdentity final : public CipObject {
 public:
  std::uint16_t class_id() const override { return kClassIdentity; }
  bool HasInstance(std::uint32_t instance) const override { return instance <= 1; }
  bool SupportsService(std::uint32_t, std::uint8_t service) const override { return service == kServiceReset; }
  ServiceStatus Execute(const ServiceRequest&, base::ByteWriter&) override {
    ++resets;
    return Success();
  }
  int resets = 0;
};

class ControlLockTest : public ::testing::Test {
 protected:
  void SetUp() override {
    (void)card_.objects.Register(parameter64_.object());
    (void)card_.objects.Register(parameter65_.object());
    (void)card_.objects.Register(identity_);
    card_.router.set_guard(&lock_);
    card_.Drive(test::kStandby);
    card_.registers.registers = {{0x0009, 100}, {0xFA06, 0}, {0xFA07, 0}, {0xFA23, 0}, {0x0003, 4}};
    table_.owner = kOwner;
  }

  // A request from `originator`, retried as the encapsulation server does until it is answered.
  Bytes AskFrom(base::Ipv4Address originator, const Bytes& request) {
    std::vector<std::uint8_t> reply(600);
    for (int pass = 0; pass < 8; ++pass) {
      RequestContext context;
      context.peer = Ipv4Endpoint{originator, 50000};
      card_.journal.OnRequestStarted(context.requester);
      const std::size_t size = card_.router.HandleUnconnected(request, context, reply);
      if (!context.pending) {
        card_.journal.OnRequestFinished(context.requester);
        reply.resize(size);
        return reply;
      }
      card_.registers.CompleteAll();
    }
    return Bytes{};
  }

  test::DriveCard card_;
  ParameterObject parameter64_{ParameterClass::k64, card_.journal};
  ParameterObject parameter65_{ParameterClass::k65, card_.journal};
  CountingIdentity identity_;
  FakeConnectionTable table_;
  ControlLock lock_{table_};
};

TEST_F(ControlLockTest, StrangerCommandsRefused0x10NothingHandedToTheDrive) {
  EXPECT_EQ(AskFrom(kStranger, Hex("10 03 20 29 24 01 30 03 01")), Hex("90 00 10 00"));  // Run1
  EXPECT_EQ(AskFrom(kStranger, Hex("10 03 20 29 24 01 30 04 01")), Hex("90 00 10 00"));  // Run2
  EXPECT_EQ(AskFrom(kStranger, Hex("10 03 20 29 24 01 30 05 01")), Hex("90 00 10 00"));  // NetCtrl
  EXPECT_EQ(AskFrom(kStranger, Hex("10 03 20 29 24 01 30 0C 01")), Hex("90 00 10 00"));  // FaultRst
  EXPECT_EQ(AskFrom(kStranger, Hex("05 02 20 29 24 01")), Hex("85 00 10 00"));           // Reset
  EXPECT_EQ(AskFrom(kStranger, Hex("10 03 20 2A 24 01 30 04 01")), Hex("90 00 10 00"));  // NetRef
  EXPECT_EQ(AskFrom(kStranger, Hex("10 03 20 2A 24 01 30 08 08 07")), Hex("90 00 10 00"));  // SpeedRef
  EXPECT_TRUE(card_.channel.commands.empty());
  EXPECT_EQ(lock_.refusals(), 7U);
}

TEST_F(ControlLockTest, StrangerOutputAssemblyDataRefused0x10) {
  for (const std::uint8_t instance : std::array<std::uint8_t, 3>{20, 21, 102}) {
    Bytes request = Hex("10 03 20 04 24 00 30 03");
    request[5] = instance;
    const Bytes data = instance == 102 ? Bytes(12, 0) : Hex("01 00 08 07");
    request.insert(request.end(), data.begin(), data.end());
    EXPECT_EQ(AskFrom(kStranger, request), Hex("90 00 10 00")) << int{instance};
  }
  EXPECT_TRUE(card_.channel.commands.empty());
  EXPECT_TRUE(card_.channel.masked.empty());
  // An input assembly is no control request: the Assembly object's own answer (not settable).
  EXPECT_EQ(AskFrom(kStranger, Hex("10 03 20 04 24 46 30 03 00 00 00 00")), Hex("90 00 0E 00"));
}

TEST_F(ControlLockTest, StrangerControlRegistersRefused0x10WithoutADriveAccess) {
  // 0x65 FA07 = 6000, FA06, FA23; 0x64 cmod (4003), f899 (4899), FA06 (7A06).
  for (const char* request : {"10 04 20 65 25 00 07 FA 30 03 70 17", "10 04 20 65 25 00 06 FA 30 03 00 04",
                              "10 04 20 65 25 00 23 FA 30 03 80 00", "10 04 20 64 25 00 03 40 30 03 00 00",
                              "10 04 20 64 25 00 99 48 30 03 01 00", "10 04 20 64 25 00 06 7A 30 03 00 04"}) {
    EXPECT_EQ(AskFrom(kStranger, Hex(request)), Hex("90 00 10 00")) << request;
  }
  EXPECT_TRUE(card_.registers.log.empty());
}

TEST_F(ControlLockTest, StrangerIdentityResetRefusedBeforeTheObject) {
  EXPECT_EQ(AskFrom(kStranger, Hex("05 02 20 01 24 01")), Hex("85 00 10 00"));
  EXPECT_EQ(identity_.resets, 0);
  EXPECT_EQ(AskFrom(kOwner, Hex("05 02 20 01 24 01")), Hex("85 00 00 00"));
  EXPECT_EQ(identity_.resets, 1);
}

TEST_F(ControlLockTest, StrangerReadsAndParametersStayOpen) {
  EXPECT_EQ(AskFrom(kStranger, Hex("0E 03 20 29 24 01 30 03")), Hex("8E 00 00 00 00"));
  EXPECT_EQ(AskFrom(kStranger, Hex("0E 04 20 65 25 00 06 FA 30 03")), Hex("8E 00 00 00 00 00"));
  EXPECT_EQ(AskFrom(kStranger, Hex("10 04 20 65 25 00 09 00 30 03 32 00")), Hex("90 00 00 00"));  // acc = 5 s
  EXPECT_EQ(card_.registers.log, (std::vector<Access>{{false, 0xFA06, 0, drive_link::WriteMode::kRamOnly},
                                                      {true, 0x0009, 50, drive_link::WriteMode::kRamAndEeprom}}));
  EXPECT_EQ(lock_.refusals(), 0U);
}

TEST_F(ControlLockTest, TheOwnersOwnAddressMayCommand) {
  EXPECT_EQ(AskFrom(kOwner, Hex("10 03 20 29 24 01 30 03 01")), Hex("90 00 00 00"));
  EXPECT_EQ(card_.channel.commands, (std::vector<drive_link::DriveCommandWords>{{0x0400, 0x0000}}));
  EXPECT_EQ(AskFrom(kOwner, Hex("10 04 20 65 25 00 23 FA 30 03 80 00")), Hex("90 00 00 00"));
  EXPECT_EQ(card_.registers.registers[0xFA23], 0x0080);
}

TEST_F(ControlLockTest, NoExclusiveOwner_NothingLocked) {
  table_.owner.reset();
  EXPECT_EQ(AskFrom(kStranger, Hex("10 03 20 29 24 01 30 03 01")), Hex("90 00 00 00"));
  EXPECT_EQ(AskFrom(kStranger, Hex("10 04 20 65 25 00 07 FA 30 03 70 17")), Hex("90 00 00 00"));
  EXPECT_EQ(card_.registers.registers[0xFA07], 6000);
}

TEST_F(ControlLockTest, RefusedBeforeTheDataIsLookedAt) {
  // A BOOL of two bytes is 0x15 for whoever may set it, 0x10 for a stranger.
  EXPECT_EQ(AskFrom(kStranger, Hex("10 03 20 29 24 01 30 03 01 00")), Hex("90 00 10 00"));
  EXPECT_EQ(AskFrom(kOwner, Hex("10 03 20 29 24 01 30 03 01 00")), Hex("90 00 15 00"));
  // An attribute that is not a command keeps its own answer (0x14 unknown, 0x0E not settable).
  EXPECT_EQ(AskFrom(kStranger, Hex("10 03 20 29 24 01 30 63 01")), Hex("90 00 14 00"));
  EXPECT_EQ(AskFrom(kStranger, Hex("10 03 20 29 24 01 30 06 01")), Hex("90 00 0E 00"));
}

TEST_F(ControlLockTest, MultipleServicePacketMembersJudgedOneByOne) {
  // MSP: Get State, Set Run1: the Get is answered, the Set refused, the packet 0x1E.
  EXPECT_EQ(AskFrom(kStranger, Hex("0A 02 20 02 24 01 | 02 00 06 00 0E 00 | 0E 03 20 29 24 01 30 06"
                                   "| 10 03 20 29 24 01 30 03 01")),
            Hex("8A 00 1E 00 | 02 00 06 00 0B 00 | 8E 00 00 00 03 | 90 00 10 00"));
  // Unconnected_Send with a local route carrying Set Run1.
  EXPECT_EQ(AskFrom(kStranger, Hex("52 02 20 06 24 01 0A 0E 09 00 10 03 20 29 24 01 30 03 01 00 01 00 01 00")),
            Hex("90 00 10 00"));
  EXPECT_TRUE(card_.channel.commands.empty());
}

TEST(ControlRequestTest, WhatTheLockCovers) {
  auto request = [](std::uint8_t service, std::uint32_t class_id, std::uint32_t instance,
                    std::optional<std::uint32_t> attribute) {
    ServiceRequest r;
    r.service = service;
    r.path = ApplicationPath{class_id, instance, attribute, std::nullopt};
    return r;
  };
  EXPECT_TRUE(IsControlRequest(request(0x05, 0x01, 1, std::nullopt)));
  EXPECT_FALSE(IsControlRequest(request(0x05, 0x01, 0, std::nullopt)));  // the class: no Reset there
  EXPECT_FALSE(IsControlRequest(request(0x10, 0xF5, 1, 5)));             // TCP/IP settings: configuration
  EXPECT_TRUE(IsControlRequest(request(0x10, 0x04, 105, 3)));
  EXPECT_FALSE(IsControlRequest(request(0x10, 0x04, 199, 3)));  // heartbeat: no data
  EXPECT_FALSE(IsControlRequest(request(0x0E, 0x04, 100, 3)));
  EXPECT_TRUE(IsControlRequest(request(0x10, 0x29, 1, 12)));
  EXPECT_FALSE(IsControlRequest(request(0x10, 0x2A, 1, 18)));  // AccelTime: a parameter
  EXPECT_TRUE(IsControlRequest(request(0x10, 0x65, 0x0207, 3)));
  EXPECT_FALSE(IsControlRequest(request(0x10, 0x65, 0x0009, 3)));
  EXPECT_FALSE(IsControlRequest(request(0x10, 0x64, 0x7C00, 3)));  // FC00: a monitor, not a command
  EXPECT_TRUE(IsControlRequest(request(0x10, 0x64, 0x7A51, 3)));   // FA51
  // 0x0F: instance = row of the parameter table (cmod 2, acc 6, f899 88, fa06 145).
  EXPECT_TRUE(IsControlRequest(request(0x10, 0x0F, 2, 1)));
  EXPECT_TRUE(IsControlRequest(request(0x10, 0x0F, 88, 1)));
  EXPECT_TRUE(IsControlRequest(request(0x10, 0x0F, 145, 1)));
  EXPECT_FALSE(IsControlRequest(request(0x10, 0x0F, 6, 1)));
  EXPECT_FALSE(IsControlRequest(request(0x0E, 0x0F, 145, 1)));
  EXPECT_FALSE(IsControlRequest(request(0x10, 0x0F, 187, 1)));  // no such row
  EXPECT_FALSE(IsControlRequest(request(0x10, 0x28, 1, 6)));
}

// The Connection Manager: one originator owns the drive.
TEST(CipOneOriginatorOwnsTheDrive, ExclusiveOwnerFromAnotherAddressRefused0x0106) {
  cip::test::ConnectionCard card;
  ASSERT_EQ(card.Open()[2], 0x00);  // 1 / 100 / 150 from 10.0.2.2
  EXPECT_FALSE(card.cm.OwnedByAnotherOriginator(cip::test::kOriginator));
  EXPECT_TRUE(card.cm.OwnedByAnotherOriginator(kStranger));

  cip::test::OpenParams other;  // 102 / 152, another point
  other.triad.connection_serial = 0x2000;
  other.o_to_t.size = 2 + 4 + 12;
  other.t_to_o.size = 2 + 12;
  other.path = Hex("20 04 24 01 2C 66 2C 98");
  card.originator = kStranger;
  EXPECT_EQ(card.Open(other), Hex("D4 00 01 01 06 01 00 20 33 33 78 56 34 12 00 00"));
  // An input-only connection from there is still welcome.
  cip::test::OpenParams watcher;
  watcher.triad.connection_serial = 0x2001;
  watcher.o_to_t.size = 2;
  watcher.path = Hex("20 04 24 01 2C C6 2C 96");
  EXPECT_EQ(card.Open(watcher)[2], 0x00);
  // The owner's own address may open a second exclusive owner.
  card.originator = cip::test::kOriginator;
  EXPECT_EQ(card.Open(other)[2], 0x00);
  // Once the owner has closed both, the other originator may take the drive.
  EXPECT_EQ(card.Ask(cip::test::ForwardCloseRequestBytes(cip::test::OpenParams{}.triad))[2], 0x00);
  EXPECT_EQ(card.Ask(cip::test::ForwardCloseRequestBytes(other.triad, other.path))[2], 0x00);
  card.originator = kStranger;
  other.triad.connection_serial = 0x2002;
  EXPECT_EQ(card.Open(other)[2], 0x00);
}

// Two exclusive owners of different points that command the same thing (the application says so with
// IoConnectionSpec::owner_conflict, e.g. 21 and 100 of the drive profile): the second is 0x0106, from
// the owner's own address too; once the first has closed it may open.
TEST(CipOneOriginatorOwnsTheDrive, ApplicationOwnerConflictRefused0x0106) {
  cip::test::ConnectionCard card;
  ASSERT_EQ(card.Open()[2], 0x00);  // 1 / 100 / 150 from 10.0.2.2
  cip::test::OpenParams other;      // 102 / 152
  other.triad.connection_serial = 0x2000;
  other.o_to_t.size = 2 + 4 + 12;
  other.t_to_o.size = 2 + 12;
  other.path = Hex("20 04 24 01 2C 66 2C 98");
  card.io.conflicting_point = 102;
  EXPECT_EQ(card.Open(other), Hex("D4 00 01 01 06 01 00 20 33 33 78 56 34 12 00 00"));
  EXPECT_EQ(card.cm.ActiveConnections(), 1U);
  // Wrong sizes are answered first: the ownership check is rule 19, after the sizes.
  cip::test::OpenParams wrong = other;
  wrong.o_to_t.size = 2 + 4 + 11;
  EXPECT_EQ(card.Open(wrong)[4], 0x27);
  // An input-only connection never conflicts.
  cip::test::OpenParams watcher;
  watcher.triad.connection_serial = 0x2001;
  watcher.o_to_t.size = 2;
  watcher.path = Hex("20 04 24 01 2C C6 2C 96");
  EXPECT_EQ(card.Open(watcher)[2], 0x00);
  card.io.conflicting_point.reset();
  EXPECT_EQ(card.Open(other)[2], 0x00);
}

}  // namespace
}  // namespace cip::drive
