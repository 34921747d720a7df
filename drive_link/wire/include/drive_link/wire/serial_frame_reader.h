// Frames arriving on a serial line: bounded reads from a hal::SerialPort into a StreamFramer, with the
// kFrameTimeout receive timer. Both ends of the link use it: the card's drive-link client (replies)
// and the simulated inverter (requests).
//
// Bounds: at most kMaxReadsPerPoll reads of kReadChunk bytes per Poll, so a babbling line cannot hold
// the event loop; when that bound was reached, NextDeadline() is "now" and the next pass reads on.
// A byte the port reports damaged (kDataLoss: parity, framing) ends the frame it belonged to.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

#include "drive_link/wire/toshiba_frame.h"
#include "hal/clock.h"
#include "hal/serial_port.h"

namespace drive_link::wire {

class FrameSink {
 public:
  virtual ~FrameSink() = default;
  // Called for every complete frame (unchecked: the sink decodes it).
  virtual void OnFrame(std::span<const std::uint8_t> frame, hal::Micros now) = 0;
};

// What one Poll saw besides frames, for the owner's counters.
struct ReadOutcome {
  std::uint32_t damaged_bytes = 0;    // kDataLoss reports from the port
  bool partial_frame_timed_out = false;  // a frame started kFrameTimeout ago and was dropped
};

class SerialFrameReader {
 public:
  // 256 bytes per pass is over 130 ms of traffic at 19200 baud, far more than one exchange.
  static constexpr std::size_t kReadChunk = 32;
  static constexpr std::size_t kMaxReadsPerPoll = 8;

  SerialFrameReader(hal::SerialPort& port, Direction direction) : port_(port), framer_(direction) {}

  ReadOutcome Poll(hal::Micros now, FrameSink& sink);
  // "now" of the last Poll when more bytes may wait, the partial frame's timeout, or hal::kNever.
  hal::Micros NextDeadline() const;
  // Drops a partial frame (e.g. the exchange it belonged to is over).
  void DropPartialFrame();
  const FramerCounters& framer_counters() const { return framer_.counters(); }

 private:
  void Read(hal::Micros now, FrameSink& sink, ReadOutcome& outcome);

  hal::SerialPort& port_;
  StreamFramer framer_;
  hal::Micros frame_started_at_ = 0;
  hal::Micros last_poll_ = 0;
  bool more_waiting_ = false;
};

}  // namespace drive_link::wire
