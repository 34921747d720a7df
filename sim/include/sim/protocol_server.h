// The simulated inverter's Toshiba-protocol server: the glue between the serial byte stream the card
// talks on and the behaviour model (inverter_model.h).
//
// Reads request bytes from the inverter end of the serial line, cuts them into frames (StreamFramer,
// Direction::kRequests, receive timer kFrameTimeout), decodes them (DecodeRequest), resolves the inverter
// number (ResolveAddress), executes them on the model and queues the reply in the request's mode, with the
// lowercase letter while the model is tripped. A reply leaves no earlier than the modelled transmission
// end: reception + max(processing delay, F805) + reply bytes x character time. docs/simulator.md
// "Protocol server" lists every decision (error codes, timing, broadcast, fault injection).
//
// Host-only, single-threaded, never blocking: Poll(now) does what is due, NextDeadline() says when it must
// run again without I/O (hal::kNever when idle), like firmware::Service. Bytes arriving on the line wake the
// event loop through the serial port's own PollSource; ProtocolServerPollSource adds the server's timers.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <vector>

#include "drive_link/wire/serial_frame_reader.h"
#include "drive_link/wire/toshiba_frame.h"
#include "hal/clock.h"
#include "hal/serial_port.h"
#include "sim/inverter_model.h"
#include "poll_waiter.h"

namespace sim {

struct ServerConfig {
  // Line speed. Reply bytes take bits_per_character / baud seconds each on the wire. The default 11 bits
  // is 8E1 (start + 8 data + even parity + 1 stop), as the issue asks; a real VF-S11 sends 2 stop bits
  // (12 bits, seed 003 §1), set 12 to model that.
  std::uint32_t baud = 19200;
  std::uint8_t bits_per_character = 11;
  // Time from the end of a request to the start of its reply (the manual's "inverter processing time",
  // at most 20 ms, about 8 ms on a VF-S9). 2 ms by default: fast tests, still visible. F805 (waiting time)
  // lengthens it when larger (seed 003 §7.4).
  hal::Micros processing_delay = 2 * hal::kMicrosPerMilli;
  // The inverter number; kUseF802 = the model's F802 at each frame (F802 acts at once, seed 003 §7.2).
  static constexpr int kUseF802 = -1;
  int inverter_number = kUseF802;
  // Broadcast R/G: answered by the representative as the manual's p.9 example (true), or ignored as its
  // p.22 text says ("invalid"). Seed 003 §13.19 asks for the choice.
  bool broadcast_reads = true;
};

// RS485 as the issue describes it: 19200 baud 8E1 and the manual's worst-case 20 ms processing time.
ServerConfig Rs485Profile();

// Injected faults, for tests and the control socket.
struct Fault {
  enum class Kind : std::uint8_t {
    kDrop,     // decode and execute, but do not send the reply
    kDelay,    // send the reply delay_us later than it would go
    kCorrupt,  // change one byte: binary checksum byte, ASCII first SUM digit (first data digit without &SUM)
    kSilent,   // neither execute nor answer: the request is lost on the way in
  };
  static constexpr std::uint32_t kUntilCleared = 0;

  Kind kind = Kind::kDrop;
  // How many replies (kSilent: requests addressed to this inverter) it affects; kUntilCleared = all until
  // ClearFaults().
  std::uint32_t count = 1;
  hal::Micros delay_us = 0;  // kDelay only
};

const char* FaultKindName(Fault::Kind kind);

struct ServerCounters {
  std::uint64_t requests = 0;     // complete frames from the framer
  std::uint64_t ignored = 0;      // for another inverter (or a refused broadcast read): no action
  std::uint64_t executed = 0;     // requests executed on the model (register or block)
  std::uint64_t replies = 0;      // frames written to the line (error replies included)
  std::uint64_t errors = 0;       // error replies (N/n) queued
  std::uint64_t unanswered = 0;   // decode faults the codec answers with silence, inter-drive 'S'
  std::uint64_t in_reset = 0;     // frames that arrived while the drive initialised: no reply
  std::uint64_t no_reply = 0;     // executed writes the model says not to answer (fault-reset edge)
  std::uint64_t dropped = 0;      // replies held back by an injected kDrop, requests lost to kSilent
  std::uint64_t delayed = 0;      // replies delayed by an injected kDelay
  std::uint64_t corrupted = 0;    // replies damaged by an injected kCorrupt
  std::uint64_t rx_errors = 0;    // kDataLoss from the line (parity/framing): the frame is lost
  std::uint64_t timeouts = 0;     // partial frames dropped by the kFrameTimeout receive timer
};

class InverterProtocolServer : private drive_link::wire::FrameSink {
 public:
  InverterProtocolServer(InverterModel& model, hal::SerialPort& line, const hal::Clock& clock,
                         ServerConfig config = {});

  // Reads the line, handles complete frames, fires the receive timer and writes the replies that are
  // due. The model's time moves to `now` at each request and at most once per kModelTick otherwise (the
  // first poll sets its time base): work per request or per tick, not per call.
  void Poll(hal::Micros now);
  static constexpr hal::Micros kModelTick = 10 * hal::kMicrosPerMilli;
  // Earliest of: the next reply's release, the receive timer, a retry of a partial write; `now` of the
  // last Poll when the line had more bytes than one Poll reads. hal::kNever when idle.
  hal::Micros NextDeadline() const;

  void Inject(const Fault& fault);
  void ClearFaults();
  std::size_t active_faults() const { return faults_.size(); }

  const ServerCounters& counters() const { return counters_; }
  const drive_link::wire::FramerCounters& framer_counters() const { return reader_.framer_counters(); }
  const ServerConfig& config() const { return config_; }
  const hal::Clock& clock() const { return clock_; }
  // The inverter number in force (the configured one or F802).
  std::uint8_t inverter_number() const;
  // Time `bytes` characters take on the line, in microseconds (rounded up).
  hal::Micros TransmissionTime(std::size_t bytes) const;
  // Processing delay in force: max(config processing_delay, F805).
  hal::Micros ProcessingDelay() const;
  std::size_t pending_replies() const { return pending_.size(); }

  // Replies queued at most (bytes read per Poll are bounded by drive_link::wire::SerialFrameReader).
  static constexpr std::size_t kMaxPendingReplies = 16;

 private:
  struct PendingReply {
    hal::Micros release_at = 0;
    std::array<std::uint8_t, drive_link::wire::kMaxFrameLength> bytes{};
    std::size_t length = 0;
    std::size_t sent = 0;
  };
  struct ActiveFault {
    Fault fault;
    std::uint32_t remaining = 0;  // 0 with kUntilCleared: never runs out
  };

  void OnFrame(std::span<const std::uint8_t> frame, hal::Micros now) override;
  void HandleRegister(const drive_link::wire::Request& request, drive_link::wire::Addressing addressing,
                      std::uint8_t own, hal::Micros now);
  void HandleBlock(const drive_link::wire::BlockRequest& request, drive_link::wire::Addressing addressing,
                   std::uint8_t own, hal::Micros now);
  void SendError(const drive_link::wire::Envelope& request, drive_link::wire::ErrorCode code, std::uint8_t own,
                 bool tripped, hal::Micros now);
  // Queues an encoded reply (or counts a failed encode as unanswered), applying drop/delay/corrupt.
  void Queue(const base::Result<std::size_t>& encoded, std::span<const std::uint8_t> bytes, bool error,
             hal::Micros now);
  void Transmit(hal::Micros now);
  // Consumes one use of the first active fault of this kind; false when none is active.
  bool TakeFault(Fault::Kind kind, hal::Micros* delay_us = nullptr);

  InverterModel& model_;
  hal::SerialPort& line_;
  const hal::Clock& clock_;
  ServerConfig config_;
  drive_link::wire::SerialFrameReader reader_{line_, drive_link::wire::Direction::kRequests};
  hal::Micros line_free_at_ = 0;  // end of the last queued reply's transmission
  hal::Micros write_retry_at_ = hal::kNever;  // a write was refused (line buffer full): try again then
  std::deque<PendingReply> pending_;
  std::vector<ActiveFault> faults_;
  ServerCounters counters_;
  hal::Micros next_model_tick_ = 0;
};

// Lets the host's PollWaiter sleep until the server's next deadline and run Poll after every wait. The
// line's own PollSource (SocketSerialPort) must be registered too: it wakes the waiter when bytes arrive.
class ProtocolServerPollSource final : public hal::host::PollSource {
 public:
  explicit ProtocolServerPollSource(InverterProtocolServer& server) : server_(server) {}
  void PrepareWait(hal::host::PollSet& set, hal::Micros& deadline) override;
  void AfterWait(const hal::host::PollSet& set) override;

 private:
  InverterProtocolServer& server_;
};

}  // namespace sim
