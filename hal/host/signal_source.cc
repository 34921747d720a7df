#include "signal_source.h"

#include <signal.h>
#include <sys/signalfd.h>
#include <unistd.h>

namespace hal::host {

SignalSource::SignalSource() {
  sigset_t set;
  sigemptyset(&set);
  sigaddset(&set, SIGINT);
  sigaddset(&set, SIGTERM);
  sigprocmask(SIG_BLOCK, &set, nullptr);
  fd_ = signalfd(-1, &set, SFD_NONBLOCK | SFD_CLOEXEC);
}

SignalSource::~SignalSource() {
  if (fd_ >= 0) close(fd_);
}

void SignalSource::PrepareWait(PollSet& set, Micros& /*deadline*/) {
  if (fd_ >= 0) slot_ = set.Add(fd_, POLLIN);
}

void SignalSource::AfterWait(const PollSet& set) {
  if (fd_ < 0 || (set.Revents(slot_) & POLLIN) == 0) return;
  signalfd_siginfo info{};
  while (read(fd_, &info, sizeof info) == static_cast<ssize_t>(sizeof info)) stop_requested_ = true;
}

}  // namespace hal::host
