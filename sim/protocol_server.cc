#include "sim/protocol_server.h"

#include <algorithm>
#include <optional>
#include <span>

namespace sim {

namespace wire = drive_link::wire;

namespace {

// A refused write (transmit buffer full) is retried this much later: bounded, never a spin.
constexpr hal::Micros kWriteRetryInterval = hal::kMicrosPerMilli;

constexpr std::uint16_t kF802InverterNumber = 0x0802;
constexpr std::uint16_t kF805WaitingTime = 0x0805;  // 0.01 s
constexpr std::uint16_t kF870BlockWrite1 = 0x0870;
constexpr std::uint16_t kF875BlockRead1 = 0x0875;  // F875-F879 are 0875-0879

// F870/F871 choices (seed 003 §4): 0 none, 1 FA00, 2 FA20, 3 FA01, 4 FA50, 5 FA51.
constexpr std::array<std::uint16_t, 6> kBlockWriteTargets = {0, 0xFA00, 0xFA20, 0xFA01, 0xFA50, 0xFA51};
// F875-F879 choices: 0 none (dummy 0000), 1 FD01, 2 FD00, 3 FE03, 4 FE05, 5 FC91, 6 FE22, 7 FD06, 8 FD07,
// 9 FE35, 10 FE36.
constexpr std::array<std::uint16_t, 11> kBlockReadSources = {0,      0xFD01, 0xFD00, 0xFE03, 0xFE05, 0xFC91,
                                                             0xFE22, 0xFD06, 0xFD07, 0xFE35, 0xFE36};

// The register an F870/F871 or F875-F879 choice selects; 0 for none or an unknown choice.
template <std::size_t N>
std::uint16_t Selected(const std::array<std::uint16_t, N>& table, std::int32_t choice) {
  return choice > 0 && static_cast<std::size_t>(choice) < N ? table[static_cast<std::size_t>(choice)] : 0;
}

// Model outcome -> the manual's transmission-error code (seed 003 §3.4, §3.9; docs/simulator.md).
wire::ErrorCode ErrorFor(WriteOutcome outcome) {
  switch (outcome) {
    case WriteOutcome::kNoSuchRegister:
      return wire::ErrorCode::kCommunicationNumberError;  // 0002 "no such communication number"
    case WriteOutcome::kOutOfRange:
      return wire::ErrorCode::kDataError;  // 0001 "data out of range"
    case WriteOutcome::kNotWritableWhileRunning:
    case WriteOutcome::kReadOnly:
    case WriteOutcome::kOk:
      break;
  }
  return wire::ErrorCode::kImpossibleToExecute;  // 0000 "communication normal but cannot execute"
}

bool IsRead(wire::Command command) {
  return command == wire::Command::kRead || command == wire::Command::kReadTwoWire;
}

bool IsBroadcast(wire::InverterAddress address) {
  return address.kind == wire::InverterAddress::Kind::kBroadcast ||
         address.kind == wire::InverterAddress::Kind::kOnesDigitGroup ||
         address.kind == wire::InverterAddress::Kind::kTensDigitGroup;
}

// Makes the reply fail the receiver's check (kCorrupt): binary = the checksum byte, ASCII = the first SUM
// digit (another hex digit), or without &SUM the first data digit (the only damage a receiver could see
// is a wrong value).
void Corrupt(std::span<std::uint8_t> frame) {
  if (frame.empty()) return;
  if (frame[0] == wire::kBinaryStartCode) {
    frame[frame.size() - 1] ^= 0x01U;
    return;
  }
  auto mark = std::find(frame.begin(), frame.end(), wire::kAsciiChecksumMark);
  std::size_t index = 0;
  if (mark != frame.end() && mark + 1 != frame.end()) {
    index = static_cast<std::size_t>(mark - frame.begin()) + 1;
  } else {
    // "(" [NN] letter NNNN DDDD: the data's first digit is 4 before the trailer (")" and CR, or CR).
    std::size_t end = frame.size() - 1;  // the CR
    if (end > 0 && frame[end - 1] == wire::kAsciiStopCode) --end;
    index = end >= 4 ? end - 4 : 0;
  }
  frame[index] = frame[index] == '0' ? std::uint8_t{'1'} : std::uint8_t{'0'};
}

}  // namespace

ServerConfig Rs485Profile() {
  ServerConfig config;
  config.baud = 19200;
  config.bits_per_character = 11;
  config.processing_delay = 20 * hal::kMicrosPerMilli;
  return config;
}

const char* FaultKindName(Fault::Kind kind) {
  switch (kind) {
    case Fault::Kind::kDrop:
      return "drop";
    case Fault::Kind::kDelay:
      return "delay";
    case Fault::Kind::kCorrupt:
      return "corrupt";
    case Fault::Kind::kSilent:
      return "silent";
  }
  return "?";
}

InverterProtocolServer::InverterProtocolServer(InverterModel& model, hal::SerialPort& line,
                                               const hal::Clock& clock, ServerConfig config)
    : model_(model), line_(line), clock_(clock), config_(config) {
  if (config_.baud == 0) config_.baud = 19200;
  if (config_.bits_per_character == 0) config_.bits_per_character = 11;
}

std::uint8_t InverterProtocolServer::inverter_number() const {
  if (config_.inverter_number >= 0) return static_cast<std::uint8_t>(std::min(config_.inverter_number, 255));
  const base::Result<std::uint16_t> f802 = model_.Read(kF802InverterNumber);
  return f802.ok() ? static_cast<std::uint8_t>(std::min<std::uint16_t>(*f802, 255)) : 0;
}

hal::Micros InverterProtocolServer::TransmissionTime(std::size_t bytes) const {
  const hal::Micros bits = static_cast<hal::Micros>(bytes) * config_.bits_per_character * hal::kMicrosPerSecond;
  return (bits + config_.baud - 1) / config_.baud;
}

hal::Micros InverterProtocolServer::ProcessingDelay() const {
  const base::Result<std::uint16_t> f805 = model_.Read(kF805WaitingTime);
  const hal::Micros waiting = f805.ok() ? static_cast<hal::Micros>(*f805) * 10 * hal::kMicrosPerMilli : 0;
  return std::max(config_.processing_delay, waiting);
}

void InverterProtocolServer::Inject(const Fault& fault) {
  faults_.push_back({fault, fault.count});
}

void InverterProtocolServer::ClearFaults() { faults_.clear(); }

bool InverterProtocolServer::TakeFault(Fault::Kind kind, hal::Micros* delay_us) {
  for (auto it = faults_.begin(); it != faults_.end(); ++it) {
    if (it->fault.kind != kind) continue;
    if (delay_us != nullptr) *delay_us = it->fault.delay_us;
    if (it->fault.count != Fault::kUntilCleared && --it->remaining == 0) faults_.erase(it);
    return true;
  }
  return false;
}

void InverterProtocolServer::Poll(hal::Micros now) {
  // The model moves when a request looks at it (OnFrame) and once per tick, not on every poll:
  // Advance applies whatever fell due in between (a loss action at its deadline) at its instant.
  if (now >= next_model_tick_) {
    model_.Advance(now);
    next_model_tick_ = now + kModelTick;
  }
  const wire::ReadOutcome read = reader_.Poll(now, *this);
  counters_.rx_errors += read.damaged_bytes;
  if (read.partial_frame_timed_out) ++counters_.timeouts;
  Transmit(now);
}

hal::Micros InverterProtocolServer::NextDeadline() const {
  hal::Micros deadline = reader_.NextDeadline();
  if (write_retry_at_ != hal::kNever) {
    deadline = std::min(deadline, write_retry_at_);  // the line refused bytes: retry later, never spin
  } else if (!pending_.empty()) {
    deadline = std::min(deadline, pending_.front().release_at);
  }
  return deadline;
}

void InverterProtocolServer::OnFrame(std::span<const std::uint8_t> frame, hal::Micros now) {
  ++counters_.requests;
  model_.Advance(now);
  const wire::DecodedRequest decoded = wire::DecodeRequest(frame);
  const bool block = decoded.kind == wire::RequestKind::kBlock;
  const wire::Mode mode = block ? wire::Mode::kBinary : decoded.request.envelope.mode;
  const wire::InverterAddress address = block ? decoded.block.address : decoded.request.envelope.address;
  const std::uint8_t own = inverter_number();

  // Addressing first: another inverter's frame is not ours whatever its faults (seed 003 §3.9).
  const wire::Addressing addressing = wire::ResolveAddress(mode, address, own);
  const bool refused_broadcast_read = !config_.broadcast_reads && decoded.ok() && !block &&
                                      IsRead(decoded.request.command) && IsBroadcast(address);
  if (addressing == wire::Addressing::kIgnore || refused_broadcast_read) {
    ++counters_.ignored;
    return;
  }
  // The drive initialises (power-on, fault reset, f899): it does not communicate at all.
  if (model_.in_reset(now)) {
    ++counters_.in_reset;
    return;
  }
  if (TakeFault(Fault::Kind::kSilent)) {
    ++counters_.dropped;
    return;
  }

  if (!decoded.ok()) {
    const std::optional<wire::ErrorCode> code = wire::ErrorReplyFor(decoded);
    if (!code || addressing != wire::Addressing::kExecuteAndReply) {
      ++counters_.unanswered;
      return;
    }
    wire::Envelope envelope = decoded.request.envelope;
    if (block) envelope = {.mode = wire::Mode::kBinary, .address = address};
    SendError(envelope, *code, own, model_.tripped(), now);
    return;
  }
  if (block) {
    HandleBlock(decoded.block, addressing, own, now);
  } else {
    HandleRegister(decoded.request, addressing, own, now);
  }
}

void InverterProtocolServer::HandleRegister(const wire::Request& request, wire::Addressing addressing,
                                            std::uint8_t own, hal::Micros now) {
  ++counters_.executed;
  // The case of the reply letter is the state when the request arrives: the manual's emergency-stop
  // write (PFA009000) is echoed in uppercase (seed 003 §3.8).
  const bool tripped = model_.tripped();
  const bool reply = addressing == wire::Addressing::kExecuteAndReply;
  wire::Reply out{.envelope = wire::ReplyEnvelope(request.envelope, own),
                  .command = request.command,
                  .tripped = tripped,
                  .comm_number = request.comm_number,
                  .data = request.data};
  if (IsRead(request.command)) {
    const base::Result<std::uint16_t> value = model_.Read(request.comm_number);
    if (!value.ok()) {
      if (reply) SendError(request.envelope, wire::ErrorCode::kCommunicationNumberError, own, tripped, now);
      return;
    }
    out.data = *value;
  } else {
    const WriteTarget target =
        request.command == wire::Command::kWriteRam ? WriteTarget::kRamOnly : WriteTarget::kRamAndEeprom;
    const WriteResult result = model_.Write(request.comm_number, request.data, target);
    if (result.no_reply) {
      // Fault-reset edge: "no data is returned from the drive" (seed 000 §3.2.4.2, seed 003 §13.10).
      ++counters_.no_reply;
      return;
    }
    if (!result.ok()) {
      if (reply) SendError(request.envelope, ErrorFor(result.outcome), own, tripped, now);
      return;
    }
  }
  if (!reply) return;
  std::array<std::uint8_t, wire::kMaxFrameLength> bytes{};
  Queue(wire::EncodeReply(out, bytes), bytes, /*error=*/false, now);
}

void InverterProtocolServer::HandleBlock(const wire::BlockRequest& request, wire::Addressing addressing,
                                         std::uint8_t own, hal::Micros now) {
  ++counters_.executed;
  const bool tripped = model_.tripped();
  wire::BlockReply out{.address = wire::ReplyAddress(request.address, own), .tripped = tripped};
  bool no_reply = false;
  // Writes go to RAM, to the targets F870/F871 selected at the last power-on or reset (ActiveValue):
  // "dummy" data for an unselected target is not written and sets its WSTAT bit (seed 003 §4 example).
  for (std::size_t i = 0; i < request.write_count && i < wire::kMaxBlockWrites; ++i) {
    const std::int32_t choice = model_.ActiveValue(static_cast<std::uint16_t>(kF870BlockWrite1 + i));
    const std::uint16_t target = Selected(kBlockWriteTargets, choice);
    bool failed = true;
    if (target != 0) {
      const WriteResult result = model_.Write(target, request.write_data[i], WriteTarget::kRamOnly);
      failed = !result.ok();
      no_reply = no_reply || result.no_reply;
    }
    if (failed) out.write_status = static_cast<std::uint8_t>(out.write_status | (1U << i));
  }
  // Reads after the writes, from the sources F875-F879 selected; 0000 for none or a missing register.
  out.read_count = wire::ReadGroupsToReturn(request);
  for (std::size_t i = 0; i < out.read_count; ++i) {
    const std::int32_t choice = model_.ActiveValue(static_cast<std::uint16_t>(kF875BlockRead1 + i));
    const std::uint16_t source = Selected(kBlockReadSources, choice);
    if (source == 0) continue;
    const base::Result<std::uint16_t> value = model_.Read(source);
    out.read_data[i] = value.ok() ? *value : 0;
  }
  if (no_reply) {
    ++counters_.no_reply;
    return;
  }
  if (addressing != wire::Addressing::kExecuteAndReply) return;
  std::array<std::uint8_t, wire::kMaxFrameLength> bytes{};
  Queue(wire::EncodeBlockReply(out, bytes), bytes, /*error=*/false, now);
}

void InverterProtocolServer::SendError(const wire::Envelope& request, wire::ErrorCode code, std::uint8_t own,
                                       bool tripped, hal::Micros now) {
  const wire::ErrorReply out{.envelope = wire::ReplyEnvelope(request, own), .tripped = tripped, .code = code};
  std::array<std::uint8_t, wire::kMaxFrameLength> bytes{};
  Queue(wire::EncodeErrorReply(out, bytes), bytes, /*error=*/true, now);
}

void InverterProtocolServer::Queue(const base::Result<std::size_t>& encoded, std::span<const std::uint8_t> bytes,
                                   bool error, hal::Micros now) {
  if (!encoded.ok() || *encoded > bytes.size()) {
    ++counters_.unanswered;  // a field the reply cannot carry (cannot happen for decoded requests)
    return;
  }
  if (TakeFault(Fault::Kind::kDrop) || pending_.size() >= kMaxPendingReplies) {
    ++counters_.dropped;
    return;
  }
  PendingReply reply;
  reply.length = *encoded;
  std::copy_n(bytes.begin(), reply.length, reply.bytes.begin());
  if (error) ++counters_.errors;
  if (TakeFault(Fault::Kind::kCorrupt)) {
    Corrupt(std::span<std::uint8_t>(reply.bytes).first(reply.length));
    ++counters_.corrupted;
  }
  // Half duplex: a reply starts after the processing delay and after the previous reply has left.
  const hal::Micros start = std::max(now + ProcessingDelay(), line_free_at_);
  reply.release_at = start + TransmissionTime(reply.length);
  hal::Micros delay = 0;
  if (TakeFault(Fault::Kind::kDelay, &delay)) {
    reply.release_at += delay;
    ++counters_.delayed;
  }
  line_free_at_ = reply.release_at;
  pending_.push_back(reply);
}

void InverterProtocolServer::Transmit(hal::Micros now) {
  if (write_retry_at_ != hal::kNever && now < write_retry_at_) return;
  write_retry_at_ = hal::kNever;
  while (!pending_.empty() && pending_.front().release_at <= now) {
    PendingReply& reply = pending_.front();
    const std::span<const std::uint8_t> rest =
        std::span<const std::uint8_t>(reply.bytes).subspan(reply.sent, reply.length - reply.sent);
    const base::Result<std::size_t> written = line_.Write(rest);
    if (!written.ok() || *written == 0) {
      write_retry_at_ = now + kWriteRetryInterval;
      return;
    }
    reply.sent += std::min(*written, rest.size());
    if (reply.sent < reply.length) {
      write_retry_at_ = now + kWriteRetryInterval;
      return;
    }
    ++counters_.replies;
    pending_.pop_front();
  }
}

void ProtocolServerPollSource::PrepareWait(hal::host::PollSet& /*set*/, hal::Micros& deadline) {
  deadline = std::min(deadline, server_.NextDeadline());
}

void ProtocolServerPollSource::AfterWait(const hal::host::PollSet& /*set*/) {
  server_.Poll(server_.clock().NowMicros());
}

}  // namespace sim
