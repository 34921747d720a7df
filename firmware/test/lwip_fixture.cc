#include "lwip_fixture.h"

#include "lwip/init.h"
#include "lwip_port.h"
#include "stderr_console.h"

namespace hal::test {

FakeClock& LwipTestClock() {
  static FakeClock clock(1'000'000);
  return clock;
}

void EnsureLwipInitialised() {
  static bool done = false;
  if (done) return;
  static CountingRandom random;
  static hal::host::StderrConsole console;
  firmware::BindLwipPlatform(LwipTestClock(), random, console, console);
  lwip_init();
  done = true;
}

}  // namespace hal::test
