#include "drive_link/link_client.h"

#include <algorithm>

namespace drive_link {
namespace {

// A partially written frame is retried this often while the port's transmit buffer is full (the
// Waiter does not report a serial port becoming writable).
constexpr hal::Micros kWriteRetryInterval = hal::kMicrosPerMilli;
wire::Command CommandOf(TransactionKind kind) {
  switch (kind) {
    case TransactionKind::kWrite:
      return wire::Command::kWrite;
    case TransactionKind::kWriteRam:
      return wire::Command::kWriteRam;
    case TransactionKind::kRead:
    case TransactionKind::kBlock:
      break;
  }
  return wire::Command::kRead;
}

bool IsFaultReset(const Transaction& transaction) {
  const bool write =
      transaction.kind == TransactionKind::kWrite || transaction.kind == TransactionKind::kWriteRam;
  return write && (transaction.comm_number == kCommandFA06 || transaction.comm_number == kCommandFA00) &&
         (transaction.data & kFaultResetBit) != 0;
}

// Time `bytes` characters of `bits` bits each take on the line at `baud`, rounded up.
hal::Micros WireTime(std::size_t bytes, unsigned bits, std::uint32_t baud) {
  const hal::Micros bit_micros = static_cast<hal::Micros>(bytes) * bits * hal::kMicrosPerSecond;
  return (bit_micros + baud - 1) / baud;
}

}  // namespace

const char* OutcomeName(Outcome outcome) {
  switch (outcome) {
    case Outcome::kOk:
      return "ok";
    case Outcome::kErrorReply:
      return "error-reply";
    case Outcome::kTimeout:
      return "timeout";
    case Outcome::kNoReply:
      return "no-reply";
    case Outcome::kLinkDown:
      return "link-down";
  }
  return "?";
}

const char* LinkStateName(LinkState state) {
  switch (state) {
    case LinkState::kStarting:
      return "starting";
    case LinkState::kUp:
      return "up";
    case LinkState::kDegraded:
      return "degraded";
    case LinkState::kFault:
      return "fault";
  }
  return "?";
}

base::Status ValidateLinkConfig(const LinkConfig& config) {
  if (config.serial.baud == 0 || (config.serial.stop_bits != 1 && config.serial.stop_bits != 2)) {
    return base::InvalidArgument();
  }
  if (config.reply_timeout == 0 || config.probe_interval == 0 || config.fault_threshold == 0 ||
      config.max_retries > kMaxRetries) {
    return base::InvalidArgument();
  }
  switch (config.address.kind) {
    case wire::InverterAddress::Kind::kOmitted:
      break;
    case wire::InverterAddress::Kind::kNumber: {
      const std::uint8_t limit = config.mode == wire::Mode::kBinary ? wire::kMaxBinaryInverterNumber
                                                                    : wire::kMaxAsciiInverterNumber;
      if (config.address.value > limit) return base::InvalidArgument();
      break;
    }
    case wire::InverterAddress::Kind::kBroadcast:
    case wire::InverterAddress::Kind::kOnesDigitGroup:
    case wire::InverterAddress::Kind::kTensDigitGroup:
      return base::InvalidArgument();
  }
  return base::OkStatus();
}

LinkClient::LinkClient(hal::SerialPort& port, const LinkConfig& config, LinkObserver* observer)
    : port_(port), config_(config), observer_(observer) {}

base::Status LinkClient::Start(hal::Micros now) {
  if (started_) return base::FailedPrecondition();
  if (base::Status status = ValidateLinkConfig(config_); !status.ok()) return status;
  if (base::Status status = port_.Configure(config_.serial); !status.ok()) return status;
  probe_entry_.transaction = Transaction::Read(config_.probe_number);
  if (base::Status status = Encode(probe_entry_.transaction, probe_entry_); !status.ok()) return status;
  started_ = true;
  state_ = LinkState::kStarting;
  quiet_until_ = now + config_.startup_silence;
  next_send_at_ = now;
  return base::OkStatus();
}

base::Status LinkClient::Encode(const Transaction& transaction, Entry& entry) const {
  base::Result<std::size_t> length = base::InvalidArgument();
  if (transaction.kind == TransactionKind::kBlock) {
    if (config_.mode != wire::Mode::kBinary ||
        transaction.block_write_count > static_cast<std::uint8_t>(config_.block_write_limit) ||
        transaction.block_read_count > wire::kMaxBlockReads) {
      return base::InvalidArgument();
    }
    wire::BlockRequest block;
    block.address = config_.address;
    block.write_count = transaction.block_write_count;
    block.read_count = transaction.block_read_count;
    block.write_data = transaction.block_write_data;
    length = wire::EncodeBlockRequest(block, entry.frame);
  } else {
    wire::Request request;
    request.envelope.mode = config_.mode;
    request.envelope.address = config_.address;
    request.command = CommandOf(transaction.kind);
    request.comm_number = transaction.comm_number;
    request.data = transaction.kind == TransactionKind::kRead ? std::uint16_t{0} : transaction.data;
    length = wire::EncodeRequest(request, entry.frame);
  }
  if (!length.ok()) return base::InvalidArgument();
  entry.frame_length = static_cast<std::uint8_t>(*length);
  return base::OkStatus();
}

base::Result<RequestId> LinkClient::Submit(const Transaction& transaction) {
  if (!started_ || state_ == LinkState::kFault) return base::FailedPrecondition();
  if (queue_count_ == queue_.size()) return base::ResourceExhausted();
  Entry entry;
  entry.transaction = transaction;
  if (IsFaultReset(transaction)) entry.transaction.expect_no_reply = true;
  if (base::Status status = Encode(entry.transaction, entry); !status.ok()) return status;
  entry.id = next_id_;
  next_id_ = next_id_ == UINT32_MAX ? 1 : next_id_ + 1;
  queue_[(queue_head_ + queue_count_) % queue_.size()] = entry;
  ++queue_count_;
  ++counters_.submitted;
  return entry.id;
}

void LinkClient::QuietUntil(hal::Micros deadline) { quiet_until_ = std::max(quiet_until_, deadline); }

const LinkClient::Entry& LinkClient::Current() const { return probe_ ? probe_entry_ : queue_[queue_head_]; }

hal::Micros LinkClient::SendableAt() const { return std::max(next_send_at_, quiet_until_); }

hal::Micros LinkClient::AttemptBudget() const {
  // The card sends start + 8 data + parity + its stop bits; the inverter always sends 2 stop bits.
  const unsigned parity = config_.serial.parity == hal::Parity::kNone ? 0U : 1U;
  const unsigned bits_out = 1U + 8U + parity + config_.serial.stop_bits;
  const unsigned bits_in = 1U + 8U + parity + 2U;
  return config_.reply_timeout + config_.inverter_wait_time +
         WireTime(Current().frame_length, bits_out, config_.serial.baud) +
         WireTime(wire::kMaxFrameLength, bits_in, config_.serial.baud);
}

void LinkClient::Poll(hal::Micros now) {
  if (!started_) return;
  counters_.rx_errors += reader_.Poll(now, *this).damaged_bytes;
  if ((phase_ == Phase::kSending || phase_ == Phase::kAwaiting) && now >= deadline_) AttemptTimedOut(now);
  if (phase_ == Phase::kIdle) LoadNext(now);
  if (phase_ == Phase::kReady && now >= SendableAt()) {
    ++attempts_;
    ++counters_.frames_sent;
    if (attempts_ > 1) ++counters_.retries;
    if (probe_) ++counters_.probes;
    sent_ = 0;
    deadline_ = now + AttemptBudget();
    phase_ = Phase::kSending;
  }
  if (phase_ == Phase::kSending) Send(now);
}

hal::Micros LinkClient::NextDeadline() const {
  if (!started_) return hal::kNever;
  hal::Micros deadline = reader_.NextDeadline();
  switch (phase_) {
    case Phase::kIdle:
      if (queue_count_ > 0) {
        deadline = std::min(deadline, SendableAt());
      } else if (state_ == LinkState::kFault) {
        deadline = std::min(deadline, std::max(next_probe_at_, SendableAt()));
      }
      break;
    case Phase::kReady:
      deadline = std::min(deadline, SendableAt());
      break;
    case Phase::kSending:
      deadline = std::min({deadline, deadline_, last_write_ + kWriteRetryInterval});
      break;
    case Phase::kAwaiting:
      deadline = std::min(deadline, deadline_);
      break;
  }
  return deadline;
}

bool LinkClient::Matches(const wire::DecodedReply& decoded) const {
  const Transaction& transaction = Current().transaction;
  switch (decoded.kind) {
    case wire::ReplyKind::kError:
      // An error reply carries no communication number: it answers whatever is on the wire.
      return decoded.error.envelope.mode == config_.mode && decoded.error.envelope.address == config_.address;
    case wire::ReplyKind::kRegister:
      return transaction.kind != TransactionKind::kBlock && decoded.reply.envelope.mode == config_.mode &&
             decoded.reply.envelope.address == config_.address &&
             decoded.reply.command == CommandOf(transaction.kind) &&
             decoded.reply.comm_number == transaction.comm_number;
    case wire::ReplyKind::kBlock:
      return transaction.kind == TransactionKind::kBlock && decoded.block.address == config_.address &&
             decoded.block.read_count == transaction.block_read_count;
  }
  return false;
}

void LinkClient::OnFrame(std::span<const std::uint8_t> frame, hal::Micros now) {
  const wire::DecodedReply decoded = wire::DecodeReply(frame);
  if (!decoded.ok()) {
    ++counters_.garbled_frames;
    return;
  }
  if (phase_ != Phase::kAwaiting || !Matches(decoded)) {
    ++counters_.stray_frames;
    return;
  }
  ++counters_.replies;
  EndAttempt(now);
  Completion completion;
  switch (decoded.kind) {
    case wire::ReplyKind::kError: {
      ++counters_.error_replies;
      inverter_tripped_ = decoded.error.tripped;
      completion.outcome = Outcome::kErrorReply;
      completion.error = decoded.error.code;
      completion.tripped = decoded.error.tripped;
      if (decoded.error.code == wire::ErrorCode::kChecksumError) {
        // The request was damaged on the way: send it again, and fail the link only when every attempt
        // was damaged. A probe is a single attempt.
        if (!probe_ && attempts_ <= config_.max_retries) {
          phase_ = Phase::kReady;
          return;
        }
        Finish(completion, /*link_failed=*/true, /*link_answered=*/false, now);
        return;
      }
      break;
    }
    case wire::ReplyKind::kRegister:
      inverter_tripped_ = decoded.reply.tripped;
      completion.outcome = Outcome::kOk;
      completion.data = decoded.reply.data;
      completion.tripped = decoded.reply.tripped;
      break;
    case wire::ReplyKind::kBlock:
      inverter_tripped_ = decoded.block.tripped;
      completion.outcome = Outcome::kOk;
      completion.tripped = decoded.block.tripped;
      completion.block_read_count = decoded.block.read_count;
      completion.block_write_status = decoded.block.write_status;
      completion.block_data = decoded.block.read_data;
      break;
  }
  Finish(completion, /*link_failed=*/false, /*link_answered=*/true, now);
}

void LinkClient::EndAttempt(hal::Micros now) {
  phase_ = Phase::kIdle;
  next_send_at_ = now + config_.inter_frame_gap;
}

void LinkClient::AttemptTimedOut(hal::Micros now) {
  // Whatever part of a reply has arrived belongs to this attempt; the next one starts clean.
  reader_.DropPartialFrame();
  EndAttempt(now);
  Completion completion;
  if (Current().transaction.expect_no_reply || deadline_ <= quiet_until_) {
    ++counters_.silent_timeouts;
    completion.outcome = Outcome::kNoReply;
    Finish(completion, /*link_failed=*/false, /*link_answered=*/false, now);
    return;
  }
  ++counters_.timeouts;
  if (!probe_ && attempts_ <= config_.max_retries) {
    phase_ = Phase::kReady;
    return;
  }
  completion.outcome = Outcome::kTimeout;
  Finish(completion, /*link_failed=*/true, /*link_answered=*/false, now);
}

void LinkClient::LoadNext(hal::Micros now) {
  attempts_ = 0;
  if (queue_count_ > 0) {
    probe_ = false;
    phase_ = Phase::kReady;
    return;
  }
  if (state_ == LinkState::kFault && now >= next_probe_at_) {
    probe_ = true;
    phase_ = Phase::kReady;
    // Probes keep their base time; after a long quiet period they restart from now.
    next_probe_at_ += config_.probe_interval;
    if (next_probe_at_ <= now) next_probe_at_ = now + config_.probe_interval;
  }
}

void LinkClient::Send(hal::Micros now) {
  const Entry& entry = Current();
  while (sent_ < entry.frame_length) {
    const std::span<const std::uint8_t> rest =
        std::span<const std::uint8_t>(entry.frame).subspan(sent_, entry.frame_length - sent_);
    const base::Result<std::size_t> written = port_.Write(rest);
    const std::size_t accepted = written.ok() ? std::min(*written, rest.size()) : 0;
    if (accepted < rest.size()) ++counters_.partial_writes;
    if (accepted == 0) break;
    sent_ += accepted;
  }
  last_write_ = now;
  if (sent_ < entry.frame_length) return;
  // The reply timer starts when the whole frame is in the port.
  phase_ = Phase::kAwaiting;
  deadline_ = now + AttemptBudget();
  if (entry.transaction.expect_no_reply) QuietUntil(now + config_.reset_silence);
}

void LinkClient::Finish(Completion completion, bool link_failed, bool link_answered, hal::Micros now) {
  phase_ = Phase::kIdle;
  const bool was_probe = probe_;
  probe_ = false;
  completion.attempts = attempts_;
  attempts_ = 0;

  // The state is final before any callback runs.
  const LinkState previous = state_;
  if (link_answered) {
    consecutive_failures_ = 0;
    state_ = LinkState::kUp;
    next_probe_at_ = hal::kNever;
  } else if (link_failed && !was_probe) {
    ++counters_.failed_transactions;
    if (consecutive_failures_ < UINT8_MAX) ++consecutive_failures_;
    state_ = consecutive_failures_ >= config_.fault_threshold ? LinkState::kFault : LinkState::kDegraded;
  }
  if (state_ == LinkState::kFault && previous != LinkState::kFault) {
    ++counters_.faults;
    next_probe_at_ = now + config_.probe_interval;
  }

  if (!was_probe) {
    const Entry entry = queue_[queue_head_];
    queue_head_ = (queue_head_ + 1) % queue_.size();
    --queue_count_;
    completion.kind = entry.transaction.kind;
    completion.comm_number = entry.transaction.comm_number;
    ++counters_.completed;
    if (observer_ != nullptr) observer_->OnComplete(entry.id, completion);
  }
  if (state_ != previous) {
    if (observer_ != nullptr) observer_->OnLinkStateChanged(previous, state_);
    if (state_ == LinkState::kFault) FlushQueue();
  }
}

void LinkClient::FlushQueue() {
  while (queue_count_ > 0) {
    const Entry entry = queue_[queue_head_];
    queue_head_ = (queue_head_ + 1) % queue_.size();
    --queue_count_;
    Completion completion;
    completion.outcome = Outcome::kLinkDown;
    completion.kind = entry.transaction.kind;
    completion.comm_number = entry.transaction.comm_number;
    ++counters_.completed;
    if (observer_ != nullptr) observer_->OnComplete(entry.id, completion);
  }
}

}  // namespace drive_link
