// ipe002z-host: the card's firmware running natively on Linux (see docs/architecture.md).
#include <linux/close_range.h>
#include <sys/prctl.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "host_card.h"
#include "host_options.h"

namespace {

// A fresh state directory for a run that did not name one.
bool MakeTemporaryStateDir(std::string& dir) {
  const char* base = std::getenv("TMPDIR");
  std::string pattern = std::string(base != nullptr && *base != '\0' ? base : "/tmp") + "/ipe002z-XXXXXX";
  if (mkdtemp(pattern.data()) == nullptr) return false;
  dir = pattern;
  return true;
}

// A reset restarts the whole process image, as a reset restarts a card: every lwIP pool, timer and
// socket starts from scratch. The state dir is passed on explicitly so it survives the restart.
[[noreturn]] void Restart(int argc, char** argv, const std::string& state_dir) {
  std::vector<char*> args(argv, argv + argc);
  std::string flag = "--state-dir";
  std::string dir = state_dir;
  if (std::find(args.begin(), args.end(), flag) == args.end()) {
    args.push_back(flag.data());
    args.push_back(dir.data());
  }
  args.push_back(nullptr);
  std::fflush(nullptr);
  // Sockets libslirp opened are not close-on-exec; the new image must be able to bind them again.
  syscall(SYS_close_range, 3U, ~0U, 0U);
  execv("/proc/self/exe", args.data());
  std::perror("ipe002z-host: restart failed");
  std::exit(1);
}

}  // namespace

int main(int argc, char** argv) {
  host::HostOptions options;
  std::string error;
  switch (host::ParseHostOptions(argc, argv, options, error)) {
    case host::ParseOutcome::kHelp:
      std::fputs(host::HostUsage(), stdout);
      return 0;
    case host::ParseOutcome::kError:
      std::fprintf(stderr, "ipe002z-host: %s\n%s", error.c_str(), host::HostUsage());
      return 2;
    case host::ParseOutcome::kRun:
      break;
  }
  if (options.state_dir.empty() && !MakeTemporaryStateDir(options.state_dir)) {
    std::perror("ipe002z-host: cannot create a temporary state dir");
    return 1;
  }
  std::error_code ignored;
  std::filesystem::create_directories(options.state_dir, ignored);

  // The kernel may delay a timed wake-up by the timer slack (50 µs by default) to batch wake-ups;
  // I/O production slots want the earliest wake-up it can give (docs/eip-bench.md, eip-io).
  static_cast<void>(prctl(PR_SET_TIMERSLACK, 1UL, 0UL, 0UL, 0UL));
  switch (host::RunHostCard(options, error)) {
    case host::CardExit::kStopped:
      return 0;
    case host::CardExit::kRestart:
      Restart(argc, argv, options.state_dir);
    case host::CardExit::kFailed:
      std::fprintf(stderr, "ipe002z-host: %s\n", error.c_str());
      return 1;
  }
  return 1;
}
