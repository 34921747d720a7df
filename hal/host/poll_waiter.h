// hal::Waiter on the host: one poll() over the file descriptors of every registered device.
//
// Each host device that has descriptors (TAP fd, libslirp sockets, serial socket, control socket) is a
// PollSource. Before sleeping, the waiter asks every source for its descriptors and its own next
// deadline (libslirp has timers); after poll() returns, it lets every source handle what is ready.
// Nothing here blocks except the single poll() call, which is bounded by the earliest deadline.
#pragma once

#include <poll.h>

#include <cstddef>
#include <vector>

#include "hal/clock.h"
#include "hal/waiter.h"

namespace hal::host {

class PollSet {
 public:
  // Adds a descriptor and returns its slot, to be passed to Revents() after the wait.
  std::size_t Add(int fd, short events);
  short Revents(std::size_t slot) const;
  void Clear() { fds_.clear(); }
  pollfd* data() { return fds_.data(); }
  std::size_t size() const { return fds_.size(); }

 private:
  std::vector<pollfd> fds_;
};

class PollSource {
 public:
  virtual ~PollSource() = default;
  // Adds this source's descriptors; lowers `deadline` if the source has an earlier timer of its own.
  virtual void PrepareWait(PollSet& set, Micros& deadline) = 0;
  // Runs after every poll() (also after a timeout): read what is ready, fire due timers.
  virtual void AfterWait(const PollSet& set) = 0;
};

class PollWaiter final : public Waiter {
 public:
  explicit PollWaiter(const Clock& clock) : clock_(clock) {}
  void Register(PollSource& source) { sources_.push_back(&source); }
  void WaitUntil(Micros deadline) override;

  // How many times poll() was entered; lets tests prove the loop sleeps instead of spinning.
  std::size_t wait_count() const { return wait_count_; }

 private:
  const Clock& clock_;
  std::vector<PollSource*> sources_;
  PollSet set_;
  std::size_t wait_count_ = 0;
};

}  // namespace hal::host
