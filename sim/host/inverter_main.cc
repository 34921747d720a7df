// ipe002z-inverter: the simulated VF-MB1 / VF-S15 inverter as its own process, serving the Toshiba
// inverter protocol on a listening socket (docs/simulator.md "ipe002z-inverter").
#include <sys/prctl.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "standalone_inverter.h"
#include "standalone_options.h"

namespace {

// A fresh state directory for a run that did not name one.
bool MakeTemporaryStateDir(std::string& dir) {
  const char* base = std::getenv("TMPDIR");
  std::string pattern =
      std::string(base != nullptr && *base != '\0' ? base : "/tmp") + "/ipe002z-inverter-XXXXXX";
  if (mkdtemp(pattern.data()) == nullptr) return false;
  dir = pattern;
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  sim::StandaloneOptions options;
  std::string error;
  switch (sim::ParseStandaloneOptions(argc, argv, options, error)) {
    case sim::StandaloneParse::kHelp:
      std::fputs(sim::StandaloneUsage(), stdout);
      return 0;
    case sim::StandaloneParse::kError:
      std::fprintf(stderr, "ipe002z-inverter: %s\n%s", error.c_str(), sim::StandaloneUsage());
      return 2;
    case sim::StandaloneParse::kRun:
      break;
  }
  if (options.state_dir.empty() && !MakeTemporaryStateDir(options.state_dir)) {
    std::perror("ipe002z-inverter: cannot create a temporary state dir");
    return 1;
  }
  std::error_code ignored;
  std::filesystem::create_directories(options.state_dir, ignored);

  // Replies are released at modelled instants; the kernel's default 50 µs timer slack would add to them.
  static_cast<void>(prctl(PR_SET_TIMERSLACK, 1UL, 0UL, 0UL, 0UL));
  if (sim::RunStandaloneInverter(options, stdout, stderr, error) == sim::StandaloneExit::kFailed) {
    std::fprintf(stderr, "ipe002z-inverter: %s\n", error.c_str());
    return 1;
  }
  return 0;
}
