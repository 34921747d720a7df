// Fakes of the facades the CIP drive profile's runtime works through (DriveCommandChannel,
// ScannerImage, DriveStatusSource, OwnershipQuery), and a card made of them: the runtime, the
// assemblies, the Control Supervisor 0x29 and the AC/DC Drive 0x2A behind a message router, with the
// registers of drive_registers_fake.h and the deferred-reply journal.
#pragma once

#include <cstdint>
#include <set>
#include <vector>

#include "cip/assembly_object.h"
#include "cip/drive/ac_dc_drive_object.h"
#include "cip/drive/control_supervisor_object.h"
#include "cip/drive/drive_access_journal.h"
#include "cip/drive/drive_assemblies.h"
#include "cip/drive/drive_profile_runtime.h"
#include "cip/message_router.h"
#include "cip/object_model.h"
#include "cip_test_support.h"
#include "drive_link/register_access.h"
#include "drive_registers_fake.h"

namespace cip::drive::test {

using cip::test::Bytes;
using cip::test::Hex;
using cip::test::Of;

class FakeDriveCommandChannel final : public drive_link::DriveCommandChannel {
 public:
  struct MaskedWords {
    drive_link::ScannerWords words{};
    std::uint8_t mask = 0;
    bool operator==(const MaskedWords&) const = default;
  };

  void SetDriveCommand(const drive_link::DriveCommandWords& words) override {
    commands.push_back(words);
    taken = true;
  }
  void ReleaseDriveCommand() override {
    taken = false;
    ++releases;
  }
  bool drive_command_taken() const override { return taken; }
  bool CommandsHeldByLoss() const override { return held_by_loss; }
  void HoldStopDuringLoss(std::uint16_t fa06) override { held_stops.push_back(fa06); }
  void SetCommandWordsMasked(const drive_link::ScannerWords& words, std::uint8_t mask) override {
    masked.push_back(MaskedWords{words, mask});
  }
  void SetFeedbackWanted(bool value) override {
    wanted = value;
    wanted_calls.push_back(value);
  }
  drive_link::DriveFeedbackWords DriveFeedback() const override { return feedback; }

  std::vector<drive_link::DriveCommandWords> commands;  // every SetDriveCommand, in order
  std::vector<MaskedWords> masked;                      // every SetCommandWordsMasked
  std::vector<bool> wanted_calls;
  bool taken = false;
  bool held_by_loss = false;
  std::vector<std::uint16_t> held_stops;  // every HoldStopDuringLoss, in order
  bool wanted = false;
  int releases = 0;
  drive_link::DriveFeedbackWords feedback;
};

class FakeScannerImage final : public drive_link::ScannerImage {
 public:
  void SetCommandWords(const drive_link::ScannerWords& words) override { command_words = words; }
  drive_link::ScannerWords CommandWords() const override { return command_words; }
  drive_link::ScannerWords MonitorWords() const override { return monitor_words; }
  bool IsScannerTarget(std::uint16_t) const override { return false; }

  drive_link::ScannerWords command_words{};
  drive_link::ScannerWords monitor_words{};
};

class FakeDriveStatus final : public DriveStatusSource {
 public:
  DriveStatus CurrentDriveStatus() const override { return status; }
  DriveStatus status{true, 0x4000};  // link up, standby (FD01 bit 14): the supervisor settles in Ready
};

class FakeOwnership final : public OwnershipQuery {
 public:
  bool IsOwned(std::uint32_t point) const override { return owned.count(point) != 0; }
  std::set<std::uint32_t> owned;
};

// FD01 values of seed 000 §3.2.4.7 the tests use.
inline constexpr std::uint16_t kStandby = 0x4000;          // bit 14: ready, stopped
inline constexpr std::uint16_t kRunningForward = 0x6400;   // bits 14, 13 (ST/RUN), 10 (running)
inline constexpr std::uint16_t kRunningReverse = 0x6600;   // ... and bit 9 (reverse)
inline constexpr std::uint16_t kTripped = 0x0002;          // bit 1

struct DriveCard {
  DriveCard() {
    (void)assemblies.Register(assembly_object);
    (void)objects.Register(assembly_object.object());
    (void)objects.Register(supervisor_object.object());
    (void)objects.Register(drive_object.object());
  }

  // The status the inverter reports: FD01 through the status source, FD00/FE02 through the channel.
  void Drive(std::uint16_t fd01, std::uint16_t fd00 = 0, std::uint16_t fe02 = 0) {
    status.status = DriveStatus{true, fd01};
    channel.feedback = drive_link::DriveFeedbackWords{fd01, fd00, fe02, true};
  }

  // One message router request executed as the encapsulation server would: again after every access it
  // started has completed (from `registers.registers`), until it is answered.
  Bytes Ask(const Bytes& request) {
    std::vector<std::uint8_t> reply(600);
    for (int pass = 0; pass < 8; ++pass) {
      RequestContext context;
      journal.OnRequestStarted(context.requester);
      const std::size_t size = router.HandleUnconnected(request, context, reply);
      if (!context.pending) {
        journal.OnRequestFinished(context.requester);
        reply.resize(size);
        return reply;
      }
      ++deferrals;
      registers.CompleteAll();
    }
    return Bytes{};
  }

  FakeDriveCommandChannel channel;
  FakeScannerImage scanner;
  drive_link::test::ScriptedDriveRegisters registers;
  FakeDriveStatus status;
  FakeOwnership ownership;
  DriveProfileRuntime runtime{DriveProfileLinks{channel, scanner, registers, status, ownership}};
  DriveAssemblies assemblies{runtime};
  AssemblyObject assembly_object;
  DriveAccessJournal journal{registers};
  ControlSupervisorObject supervisor_object{runtime};
  AcDcDriveObject drive_object{runtime, journal};
  ObjectRegistry objects;
  MessageRouter router{objects};
  int deferrals = 0;  // passes Ask had to repeat
};

}  // namespace cip::drive::test
