// SIGINT/SIGTERM as an event of the poll loop (signalfd), so a stop request can never be lost
// between checking a flag and falling asleep in poll().
#pragma once

#include "poll_waiter.h"

namespace hal::host {

class SignalSource final : public PollSource {
 public:
  SignalSource();  // blocks SIGINT and SIGTERM for the process and opens the signalfd
  ~SignalSource() override;
  SignalSource(const SignalSource&) = delete;
  SignalSource& operator=(const SignalSource&) = delete;

  bool stop_requested() const { return stop_requested_; }
  void PrepareWait(PollSet& set, Micros& deadline) override;
  void AfterWait(const PollSet& set) override;

 private:
  int fd_ = -1;
  std::size_t slot_ = 0;
  bool stop_requested_ = false;
};

}  // namespace hal::host
