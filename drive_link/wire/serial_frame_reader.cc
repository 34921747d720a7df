#include "drive_link/wire/serial_frame_reader.h"

#include <algorithm>
#include <array>
#include <chrono>

namespace drive_link::wire {
namespace {

constexpr hal::Micros kFrameTimeoutMicros = static_cast<hal::Micros>(
    std::chrono::duration_cast<std::chrono::microseconds>(kFrameTimeout).count());

}  // namespace

ReadOutcome SerialFrameReader::Poll(hal::Micros now, FrameSink& sink) {
  last_poll_ = now;
  ReadOutcome outcome;
  Read(now, sink, outcome);
  if (framer_.frame_in_progress() && now - frame_started_at_ >= kFrameTimeoutMicros) {
    framer_.GapElapsed();
    outcome.partial_frame_timed_out = true;
  }
  return outcome;
}

hal::Micros SerialFrameReader::NextDeadline() const {
  if (more_waiting_) return last_poll_;
  return framer_.frame_in_progress() ? frame_started_at_ + kFrameTimeoutMicros : hal::kNever;
}

void SerialFrameReader::DropPartialFrame() {
  if (framer_.frame_in_progress()) framer_.GapElapsed();
}

void SerialFrameReader::Read(hal::Micros now, FrameSink& sink, ReadOutcome& outcome) {
  more_waiting_ = false;
  std::array<std::uint8_t, kReadChunk> buffer{};
  for (std::size_t i = 0; i < kMaxReadsPerPoll; ++i) {
    const base::Result<std::size_t> read = port_.Read(buffer);
    if (!read.ok()) {
      if (read.status().code() != base::StatusCode::kDataLoss) return;
      // A damaged byte was discarded: the frame it belonged to cannot be valid any more.
      ++outcome.damaged_bytes;
      DropPartialFrame();
      continue;
    }
    if (*read == 0) return;
    std::span<const std::uint8_t> bytes = std::span<const std::uint8_t>(buffer).first(std::min(*read, buffer.size()));
    while (!bytes.empty()) {
      const bool was_in_progress = framer_.frame_in_progress();
      const std::uint32_t dropped = framer_.counters().dropped_frames;
      const StreamFramer::FeedResult fed = framer_.Feed(bytes);
      if (fed.consumed == 0) break;
      bytes = bytes.subspan(fed.consumed);
      if (fed.frame_ready) sink.OnFrame(framer_.frame(), now);
      // A frame started (or restarted after a drop) in these bytes: its receive timer runs from now.
      if (framer_.frame_in_progress() && (!was_in_progress || dropped != framer_.counters().dropped_frames)) {
        frame_started_at_ = now;
      }
    }
  }
  more_waiting_ = true;
}

}  // namespace drive_link::wire
