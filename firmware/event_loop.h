// The card's one event loop: single-threaded, never blocks on a peer, never busy-waits.
//
// One pass (RunOnce):
//   1. bring lwIP's link state in line with the ports (a cable pulled or plugged);
//   2. move up to kMaxFramesPerPass received frames into lwIP (bounded, so a flood cannot starve
//      timers or I/O production), kFramesPerBatch at a time: after each full batch, the services whose
//      deadline has passed are polled (an I/O production waits for one batch, not a whole pass);
//   3. run lwIP's due timers (sys_check_timeouts);
//   4. poll the services that have something to do (below);
//   5. sleep in the Waiter until the earliest deadline of lwIP and the services, or until I/O.
// If step 2 stopped at its bound, the pass does not sleep: more frames are waiting.
//
// Deadlines are absolute microseconds on hal::Clock. A service that produces periodically computes its
// next deadline from its previous deadline, not from `now`, so it keeps its base time and does not drift.
//
// Which services a pass polls (step 4). A pass costs the card's MCU what its polls cost, so a service is
// polled when it has something to do, not because the loop woke:
//   - kEveryPass: on every pass (the drive link: its serial bytes are seen only by polling it);
//   - kDueOrEvent: when its deadline has passed, or when the pass saw an event: frames taken, lwIP
//     timers run, a port's link changed, the event probe reported one (the drive link finished a
//     transaction or changed state), or an earlier service of this pass was polled at its deadline
//     (it may have changed state that later services follow: a connection timed out, an address phase);
//   - kDueOnly: when its deadline has passed (I/O production: its poll changes nothing others follow).
// Every service is polled on the first pass after it was added (its deadline is learnt there).
// Work that follows a change is thus done once per change; a pass woken by one deadline polls only
// the services that are due, unless one of them changes something.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "base/status.h"
#include "card_netif.h"
#include "hal/clock.h"
#include "hal/waiter.h"

namespace firmware {

class Service {
 public:
  virtual ~Service() = default;
  // Does whatever is due at `now`. Called once per pass, whatever woke the loop, and also between
  // batches of received frames when NextDeadline() has passed.
  virtual void Poll(hal::Micros now) = 0;
  // The next instant at which Poll() must run even if no I/O arrives; hal::kNever for none. For a
  // service added as kDueOrEvent or kDueOnly it may change only in its Poll() or with an event (a
  // frame, an lwIP timer, a drive-link event, another service's poll): the loop keeps the value
  // between passes without events.
  virtual hal::Micros NextDeadline() const = 0;
};

enum class PollWhen : std::uint8_t { kEveryPass, kDueOrEvent, kDueOnly };

// Something that happens without a frame and that kDueOrEvent services wait for. Asked after each
// kEveryPass service's poll (the drive link's changes happen there).
class EventProbe {
 public:
  virtual ~EventProbe() = default;
  // True once per change since the last call.
  virtual bool TakeEvent() = 0;
};

struct LoopStats {
  std::uint64_t passes = 0;
  std::uint64_t frames_in = 0;
  std::uint64_t bounded_passes = 0;  // passes that hit kMaxFramesPerPass and skipped the sleep
  std::uint64_t link_changes = 0;
  std::uint64_t polls = 0;        // Service::Poll calls (the loop's work, for the instruction bench)
  std::uint64_t event_passes = 0;  // passes that polled the kDueOrEvent services for an event
};

class EventLoop {
 public:
  static constexpr std::size_t kMaxServices = 16;
  static constexpr std::size_t kMaxFramesPerPass = 32;
  static constexpr std::size_t kFramesPerBatch = 8;

  EventLoop(const hal::Clock& clock, hal::Waiter& waiter, CardNetif& netif)
      : clock_(clock), waiter_(waiter), netif_(netif) {}

  // kResourceExhausted when kMaxServices are registered already.
  base::Status AddService(Service& service, PollWhen when = PollWhen::kEveryPass);
  void SetEventProbe(EventProbe* probe) { probe_ = probe; }
  void RunOnce();
  // The deadline the last pass slept towards (kNever: it waited for I/O only). For tests.
  hal::Micros last_deadline() const { return last_deadline_; }
  const LoopStats& stats() const { return stats_; }

 private:
  hal::Micros NextDeadline(hal::Micros now) const;
  void PollDue(hal::Micros now);  // the services whose deadline is at or before `now`
  // Step 4; `event`: the pass took frames, ran lwIP timers or saw a link change.
  void PollServices(hal::Micros now, bool event);

  const hal::Clock& clock_;
  hal::Waiter& waiter_;
  CardNetif& netif_;
  std::array<Service*, kMaxServices> services_{};
  std::array<PollWhen, kMaxServices> when_{};
  std::array<hal::Micros, kMaxServices> deadlines_{};  // NextDeadline() as of the last poll or event
  std::array<bool, kMaxServices> polled_once_{};
  EventProbe* probe_ = nullptr;
  std::size_t service_count_ = 0;
  hal::Micros last_deadline_ = hal::kNever;
  LoopStats stats_;
};

}  // namespace firmware
