// The card's client of the Toshiba inverter protocol: requests out over a hal::SerialPort, replies in,
// timeouts, retries and the state of the link to the inverter (docs/drive-link.md, "Protocol client").
//
// Device-path code: no exceptions, no RTTI, no allocation; every buffer is a member of fixed size.
// One request is on the wire at a time (the link is half-duplex and the inverter a slave that answers
// one frame at a time); the rest wait in a FIFO of kRequestQueueCapacity entries. Time is injected:
// Poll(now) does what is due and NextDeadline() says when it must run again, with the meaning of
// firmware::Service (absolute microseconds on hal::Clock), so the firmware wraps the client in a
// Service without this layer knowing the firmware.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "base/status.h"
#include "drive_link/wire/serial_frame_reader.h"
#include "drive_link/wire/toshiba_frame.h"
#include "hal/clock.h"
#include "hal/serial_port.h"

namespace drive_link {

// Requests waiting or on the wire at most. The cyclic exchange needs a handful (FA06/FA07 out, FD01,
// FD00, FE03, FC91 in); the rest is room for explicit messages and Modbus register access in between.
inline constexpr std::size_t kRequestQueueCapacity = 16;

// Names a submitted request in its completion. Never kNoRequestId; ids count up from 1 and wrap.
using RequestId = std::uint32_t;
inline constexpr RequestId kNoRequestId = 0;

// The fault-reset bit of the command words FA06 (option path) and FA00 (RS485 path): the inverter
// resets and returns no data (seed 003 §13.10, vf-s15-registers.md §3).
inline constexpr std::uint16_t kCommandFA00 = 0xFA00;
inline constexpr std::uint16_t kCommandFA06 = 0xFA06;
inline constexpr std::uint16_t kFaultResetBit = 0x2000;  // bit 13

// The cheap read that probes an inverter that stopped answering: FD01, inverter status 1.
inline constexpr std::uint16_t kDefaultProbeNumber = 0xFD01;

enum class TransactionKind : std::uint8_t {
  kRead,      // R: read one communication number
  kWrite,     // W: write RAM and EEPROM (RAM only for RAM-only numbers such as FA06/FA07)
  kWriteRam,  // P: write RAM only; for anything written often (EEPROM lasts ~10,000 writes)
  kBlock,     // X/Y: write up to 2 words (F870/F871 targets), read up to 5 (F875-F879); binary only
};

// One request. Build it with the factories; the inverter number and the mode come from LinkConfig.
struct Transaction {
  TransactionKind kind = TransactionKind::kRead;
  std::uint16_t comm_number = 0;  // R/W/P
  std::uint16_t data = 0;         // W/P: the value written
  // kBlock: counts as sent; Submit refuses more writes than LinkConfig::block_write_limit allows or
  // more than wire::kMaxBlockReads reads.
  std::uint8_t block_write_count = 0;
  std::uint8_t block_read_count = 0;
  std::array<std::uint16_t, wire::kMaxLedBlockWrites> block_write_data{};
  // The inverter does not answer this request because it resets on it (a fault reset, f899 = 1). It is
  // sent once; its missing reply completes it with Outcome::kNoReply and is not a link failure; the link
  // then sends nothing for LinkConfig::reset_silence. Set automatically for W/P of FA06 or FA00 with
  // kFaultResetBit; a block write whose F870/F871 target is FA06/FA00 must set it by hand.
  bool expect_no_reply = false;

  static constexpr Transaction Read(std::uint16_t number) {
    Transaction t;
    t.kind = TransactionKind::kRead;
    t.comm_number = number;
    return t;
  }
  static constexpr Transaction Write(std::uint16_t number, std::uint16_t value) {
    Transaction t;
    t.kind = TransactionKind::kWrite;
    t.comm_number = number;
    t.data = value;
    return t;
  }
  static constexpr Transaction WriteRam(std::uint16_t number, std::uint16_t value) {
    Transaction t = Write(number, value);
    t.kind = TransactionKind::kWriteRam;
    return t;
  }
  // Words beyond block_write_data's capacity are not copied, but counted, so Submit refuses them.
  static constexpr Transaction Block(std::span<const std::uint16_t> writes, std::uint8_t read_count) {
    Transaction t;
    t.kind = TransactionKind::kBlock;
    t.block_write_count =
        writes.size() > 0xFF ? std::uint8_t{0xFF} : static_cast<std::uint8_t>(writes.size());
    t.block_read_count = read_count;
    for (std::size_t i = 0; i < writes.size() && i < t.block_write_data.size(); ++i) {
      t.block_write_data[i] = writes[i];
    }
    return t;
  }
};

enum class Outcome : std::uint8_t {
  kOk,          // answered: `data` (R/W/P) or the block fields hold the reply
  kErrorReply,  // answered with an error reply: `error` holds the inverter's code, passed through as sent
  kTimeout,     // no valid reply to any attempt (1 + LinkConfig::max_retries frames sent)
  kNoReply,     // no reply while silence was expected (expect_no_reply, QuietUntil): not a failure
  kLinkDown,    // never sent: the link went into fault (option fault e-23) while it waited in the queue
};

const char* OutcomeName(Outcome outcome);

struct Completion {
  Outcome outcome = Outcome::kTimeout;
  TransactionKind kind = TransactionKind::kRead;
  std::uint16_t comm_number = 0;  // the request's
  std::uint16_t data = 0;         // kOk, R: the value read; W/P: the value the inverter echoed
  wire::ErrorCode error = wire::ErrorCode::kImpossibleToExecute;  // kErrorReply only
  // The reply's letter was lowercase: the inverter is tripped, waiting for a retry or holding a trip.
  // Only meaningful for kOk and kErrorReply.
  bool tripped = false;
  std::uint8_t attempts = 0;  // frames sent for this request (0 for kLinkDown)
  // kBlock, kOk: the reply's read groups and write status (bit set per failed write, bit0 = data 1).
  std::uint8_t block_read_count = 0;
  std::uint8_t block_write_status = 0;
  std::array<std::uint16_t, wire::kMaxBlockReads> block_data{};

  bool ok() const { return outcome == Outcome::kOk; }
};

// kStarting: no good reply yet. kUp: the last transaction got a good reply. kDegraded: the last
// transaction failed, fewer than LinkConfig::fault_threshold in a row. kFault: fault_threshold failed
// in a row: the card declares option fault e-23 (error code 55, IPE002Z manual §12.1), refuses requests
// and probes the inverter every probe_interval until it answers, then goes back to kUp.
enum class LinkState : std::uint8_t { kStarting, kUp, kDegraded, kFault };

const char* LinkStateName(LinkState state);

// Receives completions and state changes, from inside LinkClient::Poll. The client's state is final
// before the first callback of a Poll step: in OnComplete, state() already says kFault if that
// completion caused it. A callback may Submit() and QuietUntil(); it must not call Poll().
class LinkObserver {
 public:
  virtual ~LinkObserver() = default;
  virtual void OnComplete(RequestId id, const Completion& completion) = 0;
  virtual void OnLinkStateChanged(LinkState previous, LinkState current) {
    static_cast<void>(previous);
    static_cast<void>(current);
  }
};

// Every value is documented with its reason in docs/drive-link.md.
struct LinkConfig {
  // 19200 baud, even parity, 1 stop bit: the VF-S15/MB1 defaults (F800/F801). Applied at Start().
  hal::SerialConfig serial{};
  wire::Mode mode = wire::Mode::kBinary;
  // One card, one inverter: the number may be omitted (the reply omits it too). A number must be one
  // the mode can carry (binary 0-63, ASCII 0-99); broadcasts are refused (nobody would answer).
  wire::InverterAddress address = wire::InverterAddress::Omitted();
  // kLedDisplay only while the inverter runs with FA80 = 1 (block writes go to the LED).
  wire::BlockWriteLimit block_write_limit = wire::BlockWriteLimit::kParameters;
  // Time allowed after the whole request is handed to the port, on top of the wire time of the request
  // and of a longest reply at the configured baud: the inverter's processing time (max 20 ms) plus
  // margin for a loaded inverter and a slow converter.
  hal::Micros reply_timeout = 100 * hal::kMicrosPerMilli;
  // The inverter's F805 communication waiting time: it delays every reply by this much, so the reply
  // timeout grows by it.
  hal::Micros inverter_wait_time = 0;
  // Minimum time between the end of one exchange (reply or timeout) and the next request: turnaround
  // for a slow RS485 converter. 0: send at once.
  hal::Micros inter_frame_gap = 0;
  // Frames resent after a timeout or a checksum-error reply (0004); 2 = 3 attempts per request.
  std::uint8_t max_retries = 2;
  // Failed transactions in a row that declare option fault e-23 (kFault).
  std::uint8_t fault_threshold = 3;
  // While in kFault, a read of probe_number is sent this often (one attempt each).
  hal::Micros probe_interval = 500 * hal::kMicrosPerMilli;
  std::uint16_t probe_number = kDefaultProbeNumber;
  // Nothing is sent this long after Start(): the inverter does not communicate for about 1 s after
  // power-on (seed 003 §1).
  hal::Micros startup_silence = hal::kMicrosPerSecond;
  // Nothing is sent this long after a request with expect_no_reply (a fault reset re-initialises the
  // inverter like a power-on).
  hal::Micros reset_silence = hal::kMicrosPerSecond;
};

// kInvalidArgument when a value cannot work (baud 0, zero timeouts, threshold 0, a broadcast address or
// a number the mode cannot carry, more than kMaxRetries retries).
inline constexpr std::uint8_t kMaxRetries = 10;
base::Status ValidateLinkConfig(const LinkConfig& config);

struct LinkCounters {
  std::uint32_t submitted = 0;            // requests accepted by Submit
  std::uint32_t completed = 0;            // completions delivered (every outcome)
  std::uint32_t frames_sent = 0;          // request frames written: first attempts, retries, probes
  std::uint32_t replies = 0;              // frames that matched the request on the wire
  std::uint32_t retries = 0;              // frames resent
  std::uint32_t timeouts = 0;             // attempts without a reply in time (silence expected excluded)
  std::uint32_t silent_timeouts = 0;      // attempts without a reply while silence was expected
  std::uint32_t error_replies = 0;        // matched error replies (N/n), every code
  std::uint32_t failed_transactions = 0;  // timeouts after every retry, checksum errors after every retry
  std::uint32_t stray_frames = 0;         // well-formed replies that matched nothing outstanding
  std::uint32_t garbled_frames = 0;       // frames the decoder refused (bad checksum, bad layout)
  std::uint32_t rx_errors = 0;            // parity/framing errors the port reported (kDataLoss)
  std::uint32_t partial_writes = 0;       // Write() calls that took fewer bytes than offered
  std::uint32_t probes = 0;               // probe reads sent while in kFault
  std::uint32_t faults = 0;               // transitions into kFault (e-23 declared)
};

class LinkClient : private wire::FrameSink {
 public:
  // `observer` may be null (completions are then only counted). Both references must outlive the client.
  LinkClient(hal::SerialPort& port, const LinkConfig& config, LinkObserver* observer);
  LinkClient(const LinkClient&) = delete;
  LinkClient& operator=(const LinkClient&) = delete;

  // Validates the configuration, configures the port and starts the startup silence. Until it succeeds,
  // Submit refuses and Poll does nothing. kFailedPrecondition when already started.
  base::Status Start(hal::Micros now);

  // Queues a request. kInvalidArgument: the request cannot be carried (a block in ASCII mode, too many
  // block groups); kResourceExhausted: kRequestQueueCapacity requests are waiting or on the wire;
  // kFailedPrecondition: not started, or the link is in kFault (e-23: the inverter does not answer).
  base::Result<RequestId> Submit(const Transaction& transaction);

  // Reads what the port received, matches replies, handles timeouts and retries, writes the next frame.
  void Poll(hal::Micros now);
  // When Poll must run next even if no byte arrives; hal::kNever when nothing is pending. A past value
  // means "at once".
  hal::Micros NextDeadline() const;

  // The inverter is expected not to answer until `deadline` (it is being reset by other means, its
  // control power dipped): nothing new is sent before then, and a request on the wire whose reply
  // deadline falls before then completes with Outcome::kNoReply and is not counted as a failure.
  // Only ever extends the quiet period.
  void QuietUntil(hal::Micros deadline);

  LinkState state() const { return state_; }
  // Option fault e-23 (error code 55): the inverter has not answered fault_threshold transactions.
  bool option_fault() const { return state_ == LinkState::kFault; }
  // The tripped flag of the last reply (lowercase letter); false before any reply.
  bool inverter_tripped() const { return inverter_tripped_; }
  // Requests waiting or on the wire.
  std::size_t queued() const { return queue_count_; }
  const LinkCounters& counters() const { return counters_; }
  const wire::FramerCounters& framer_counters() const { return reader_.framer_counters(); }
  const LinkConfig& config() const { return config_; }

 private:
  // What the current exchange is doing. kReady: a frame is loaded and waits for the inter-frame gap or
  // the end of a quiet period; kSending: part of it is written; kAwaiting: all written, reply pending.
  enum class Phase : std::uint8_t { kIdle, kReady, kSending, kAwaiting };

  struct Entry {
    RequestId id = kNoRequestId;
    Transaction transaction{};
    std::array<std::uint8_t, wire::kMaxFrameLength> frame{};
    std::uint8_t frame_length = 0;
  };

  base::Status Encode(const Transaction& transaction, Entry& entry) const;
  void OnFrame(std::span<const std::uint8_t> frame, hal::Micros now) override;
  bool Matches(const wire::DecodedReply& reply) const;
  void LoadNext(hal::Micros now);
  void Send(hal::Micros now);
  void AttemptTimedOut(hal::Micros now);
  void EndAttempt(hal::Micros now);
  // Ends the exchange: completes the request (or the probe) and moves the link state.
  void Finish(Completion completion, bool link_failed, bool link_answered, hal::Micros now);
  void FlushQueue();
  hal::Micros SendableAt() const;
  hal::Micros AttemptBudget() const;
  const Entry& Current() const;

  hal::SerialPort& port_;
  LinkConfig config_;
  LinkObserver* observer_;
  wire::SerialFrameReader reader_{port_, wire::Direction::kReplies};

  bool started_ = false;
  LinkState state_ = LinkState::kStarting;
  bool inverter_tripped_ = false;
  std::uint8_t consecutive_failures_ = 0;
  RequestId next_id_ = 1;

  std::array<Entry, kRequestQueueCapacity> queue_{};
  std::size_t queue_head_ = 0;
  std::size_t queue_count_ = 0;

  // The exchange: the front of the queue, or the probe when probe_ is set.
  Phase phase_ = Phase::kIdle;
  bool probe_ = false;
  Entry probe_entry_{};
  std::uint8_t attempts_ = 0;
  std::size_t sent_ = 0;
  hal::Micros deadline_ = hal::kNever;   // reply (or transmit) deadline of the attempt
  hal::Micros last_write_ = 0;           // when a partial write was last retried

  hal::Micros next_send_at_ = 0;         // end of the inter-frame gap
  hal::Micros quiet_until_ = 0;          // nothing is sent before this
  hal::Micros next_probe_at_ = hal::kNever;

  LinkCounters counters_;
};

}  // namespace drive_link
