// The CIP drive objects 0x0F/0x28/0x64/0x65 behind a message router, on the scripted register fake, with
// the encapsulation server's part of deferred replies played by hand: OnRequestStarted before each
// pass, the retry once ReadyToRetry, OnRequestFinished after the reply. Shared by the unit tests and
// the fuzz target of these objects.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "cip/drive/cip_parameter_object.h"
#include "cip/drive/drive_access_journal.h"
#include "cip/drive/motor_data_object.h"
#include "cip/drive/parameter_object.h"
#include "cip/message_router.h"
#include "cip/object_model.h"
#include "cip_fakes.h"
#include "drive_registers_fake.h"

namespace cip::drive::test {

using Bytes = std::vector<std::uint8_t>;

struct PassResult {
  Bytes reply;
  bool pending = false;
};

class DriveObjectsHarness {
 public:
  DriveObjectsHarness() {
    (void)registry.Register(parameter64.object());
    (void)registry.Register(parameter65.object());
    (void)registry.Register(motor_data.object());
    (void)registry.Register(parameter0f.object());
  }

  // One execution pass of `request` for `requester` (the reply is meaningless while pending).
  PassResult Pass(const Bytes& request, std::uint32_t requester = 1) {
    journal.OnRequestStarted(requester);
    RequestContext context;
    context.requester = requester;
    std::array<std::uint8_t, 600> buffer{};
    const std::size_t size = router.HandleUnconnected(request, context, buffer);
    return PassResult{Bytes(buffer.begin(), buffer.begin() + static_cast<std::ptrdiff_t>(size)), context.pending};
  }

  // The whole exchange as the server runs it, each access completed from the fake's registers: the
  // reply, with `passes` set to the number of execution passes it took (at most `max_passes`).
  Bytes Exchange(const Bytes& request, int* passes = nullptr, std::uint32_t requester = 1, int max_passes = 20) {
    PassResult result = Pass(request, requester);
    int count = 1;
    while (result.pending && count < max_passes) {
      drive.CompleteAll();
      if (!journal.ReadyToRetry(requester)) break;
      result = Pass(request, requester);
      ++count;
    }
    journal.OnRequestFinished(requester);
    if (passes != nullptr) *passes = count;
    return result.pending ? Bytes{} : result.reply;
  }

  drive_link::test::ScriptedDriveRegisters drive;
  DriveAccessJournal journal{drive};
  ParameterObject parameter64{ParameterClass::k64, journal};
  ParameterObject parameter65{ParameterClass::k65, journal};
  MotorDataObject motor_data{journal};
  cip::test::FakeDeviceInfo device;  // the model the Parameter object 0x0F takes its limits from
  CipParameterObject parameter0f{journal, device};
  ObjectRegistry registry;
  MessageRouter router{registry};
};

}  // namespace cip::drive::test
