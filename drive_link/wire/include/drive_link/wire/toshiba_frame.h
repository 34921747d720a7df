// Toshiba inverter protocol, wire format only (VF-S11 manual E6581222 ch. 4; VF-MB1/S15 keep it).
//
// One codec for both ends of the serial link: the card encodes requests and decodes replies, the
// simulated inverter decodes requests and encodes replies. No allocation, no exceptions: frames come in
// as spans and go out into caller-provided spans; no decoder reads outside the span it is given.
// What a register means, whether it exists and whether a value is in range are the register file's
// business, not this codec's. docs/toshiba-protocol.md lists what is supported and every decision taken
// where the manual is unclear.
#pragma once

#include <array>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>

#include "base/status.h"

namespace drive_link::wire {

// Longest frame of the protocol (manual p.4, p.7): an ASCII request with inverter number, 4 data digits,
// checksum and stop code. Binary frames are at most 16 bytes (block frames carrying 5 words).
inline constexpr std::size_t kMaxFrameLength = 17;

// A frame not complete this long after its start code is dropped silently (p.7, p.21: "the CR code
// cannot be found ... within 0.5 seconds"). The block page (p.17) says 1 s; 0.5 s is used for every
// frame, since the longest frame takes 170 ms even at 1200 baud. The manual gives no inter-character
// limit; a caller restarting its timer at each byte drops the same broken frames a little later.
inline constexpr std::chrono::milliseconds kFrameTimeout{500};

inline constexpr std::uint8_t kAsciiStartCode = '(';
inline constexpr std::uint8_t kBinaryStartCode = 0x2F;  // '/'
inline constexpr std::uint8_t kAsciiChecksumMark = '&';
inline constexpr std::uint8_t kAsciiStopCode = ')';
inline constexpr std::uint8_t kCarriageReturn = 0x0D;

// Command letters that are not single-register commands (4.2, 4.1.3, 6.2).
inline constexpr std::uint8_t kBlockRequestLetter = 'X';  // binary block write + read request
inline constexpr std::uint8_t kBlockReplyLetter = 'Y';    // its reply
inline constexpr std::uint8_t kErrorReplyLetter = 'N';    // error reply
inline constexpr std::uint8_t kInterDriveLetter = 'S';    // inter-drive frequency write: unsupported
inline constexpr std::uint8_t kMaintenanceLetter = 'M';   // maintenance command: always refused (0000)
// A reply's letter is lowercase (letter + 20h) while the inverter is tripped, waiting for a retry or
// holding a trip (p.8-9, p.12).
inline constexpr std::uint8_t kTrippedOffset = 0x20;

// Block communication limits (4.1.3, 8.4.1).
inline constexpr std::size_t kMaxBlockWrites = 2;     // write data 1-2, targets chosen by F870/F871
inline constexpr std::size_t kMaxLedBlockWrites = 5;  // FA80 = 1: write data go to FA70-FA74
inline constexpr std::size_t kMaxBlockReads = 5;      // read data 1-5, chosen by F875-F879

// Inverter numbers each mode can carry (p.22, 7.2).
inline constexpr std::uint8_t kMaxAsciiInverterNumber = 99;
inline constexpr std::uint8_t kMaxBinaryInverterNumber = 0x3F;
inline constexpr std::uint8_t kBinaryBroadcast = 0xFF;

// The start code picks the mode per frame; both are always accepted (ch. 3).
enum class Mode : std::uint8_t { kAscii, kBinary };

// Single-register commands, by the manual's letters (4.2).
enum class Command : std::uint8_t {
  kRead = 'R',         // read the value at a communication number
  kWrite = 'W',        // write RAM and EEPROM (RAM only for RAM-only parameters such as FA00)
  kWriteRam = 'P',     // write RAM only: use it for values that need not survive power-off
  kReadTwoWire = 'G',  // binary only: read with 2 dummy data bytes, for two-wire RS485 buses
};

// Error codes of the transmission-error table (4.3). Format and receive errors have no code: the
// inverter stays silent.
enum class ErrorCode : std::uint16_t {
  kImpossibleToExecute = 0x0000,        // e.g. not writable during run, typ in progress, maintenance
  kDataError = 0x0001,                  // data out of range or too many digits
  kCommunicationNumberError = 0x0002,   // no such communication number
  kCommandError = 0x0003,               // no such command (ASCII only; binary stays silent)
  kChecksumError = 0x0004,              // checksum mismatch
};

// The inverter number field (p.8, p.22). ASCII carries 00-99, "**" (all), "*n" (ones digit n) and
// "n*" (tens digit n); binary carries 00h-3Fh and FFh (all). Replies carry a plain number or nothing.
struct InverterAddress {
  enum class Kind : std::uint8_t { kOmitted, kNumber, kBroadcast, kOnesDigitGroup, kTensDigitGroup };
  Kind kind = Kind::kOmitted;
  std::uint8_t value = 0;  // kNumber: the inverter number; digit groups: the fixed digit 0-9

  static constexpr InverterAddress Omitted() { return {}; }
  static constexpr InverterAddress Number(std::uint8_t n) { return {Kind::kNumber, n}; }
  static constexpr InverterAddress Broadcast() { return {Kind::kBroadcast, 0}; }
  static constexpr InverterAddress OnesDigitGroup(std::uint8_t d) { return {Kind::kOnesDigitGroup, d}; }
  static constexpr InverterAddress TensDigitGroup(std::uint8_t d) { return {Kind::kTensDigitGroup, d}; }
  constexpr bool operator==(const InverterAddress&) const = default;
};

// What the receiving inverter does with a frame, by address alone (p.8-9, p.21-22).
enum class Addressing : std::uint8_t {
  kIgnore,           // another inverter's frame: no processing, no reply, not an error
  kExecuteSilently,  // broadcast member that is not its group's representative
  kExecuteAndReply,  // addressed alone, number omitted, or the broadcast's representative
};

// Everything a frame carries besides its payload. A reply mirrors its request's envelope, with the
// replier's own number in place of the request's (ReplyEnvelope).
struct Envelope {
  Mode mode = Mode::kBinary;
  InverterAddress address{};
  // ASCII only, ignored in binary mode (binary frames always end in a checksum, decoders leave these at
  // their defaults there): whether "&" + SUM and the stop code ")" are present.
  bool ascii_checksum = true;
  bool ascii_stop_code = true;
  constexpr bool operator==(const Envelope&) const = default;
};

struct Request {
  Envelope envelope{};
  Command command = Command::kRead;
  std::uint16_t comm_number = 0;
  std::uint16_t data = 0;  // W/P: value to write; G: dummy; R: always 0
  // ASCII W/P only: hex digits sent, 0-4 (the reply pads to 4). Decoders leave 4 everywhere else.
  std::uint8_t ascii_data_digits = 4;
  constexpr bool operator==(const Request&) const = default;
};

struct Reply {
  Envelope envelope{};
  Command command = Command::kRead;  // echo of the request's command
  bool tripped = false;              // letter in lowercase
  std::uint16_t comm_number = 0;     // echo
  std::uint16_t data = 0;            // R/G: value read; W/P: value written
  constexpr bool operator==(const Reply&) const = default;
};

struct ErrorReply {
  Envelope envelope{};
  bool tripped = false;  // 'n' instead of 'N'
  ErrorCode code = ErrorCode::kImpossibleToExecute;
  constexpr bool operator==(const ErrorReply&) const = default;
};

// Block communication 'X' (binary only, 4.1.3): up to 2 (LED mode: 5) words written to the targets
// chosen by F870/F871, and up to 5 words read from the targets chosen by F875-F879, in one frame.
struct BlockRequest {
  InverterAddress address{};
  std::uint8_t write_count = 0;
  std::uint8_t read_count = 0;  // as sent; above 5 the inverter answers with 0 reads (ReadGroupsToReturn)
  std::array<std::uint16_t, kMaxLedBlockWrites> write_data{};  // first write_count used, rest 0
  constexpr bool operator==(const BlockRequest&) const = default;
};

// Block reply 'Y' ('y' while tripped).
struct BlockReply {
  InverterAddress address{};
  bool tripped = false;
  std::uint8_t read_count = 0;    // 0-5
  std::uint8_t write_status = 0;  // bit set per failed write: bit0 = write data 1, bit1 = write data 2
  std::array<std::uint16_t, kMaxBlockReads> read_data{};  // first read_count used, rest 0
  constexpr bool operator==(const BlockReply&) const = default;
};

// Why a frame did not decode. ErrorReplyFor says which of these the inverter answers, and with what.
enum class FrameFault : std::uint8_t {
  kNone = 0,
  kTruncated,                // shorter than its layout (format error)
  kTrailingBytes,            // bytes after the end of its layout (format error)
  kTooLong,                  // over kMaxFrameLength bytes (format error)
  kBadStartCode,             // neither '(' nor 2Fh
  kBadInverterNumber,        // one-digit or malformed ASCII number, binary number outside 00h-3Fh/FFh
  kBadStopCode,              // ASCII: neither ')' nor CR where the frame must end (format error)
  kUnknownCommand,           // no such command letter (ASCII request: 0003; binary: silent)
  kBadChecksum,              // 0004
  kBadCommunicationNumber,   // ASCII: the 4 characters are not hex digits (0002)
  kBadData,                  // ASCII: too many data digits, data after R; reply data not 4 hex digits
  kBadErrorCode,             // error reply: code not in the table
  kBadBlockWriteCount,       // block request: more write groups than allowed (format error)
  kBadBlockReadCount,        // block reply: more than 5 read groups
  kMaintenanceCommand,       // ASCII 'M': refused with 0000
  kInterDriveCommand,        // binary 'S'/'s': inter-drive communication, unsupported, never answered
};

const char* FrameFaultName(FrameFault fault);

// How many write groups a block request may carry: 2 normally, 5 while FA80 = 1 (LED display mode).
enum class BlockWriteLimit : std::uint8_t {
  kParameters = kMaxBlockWrites,
  kLedDisplay = kMaxLedBlockWrites,
};

enum class RequestKind : std::uint8_t { kRegister, kBlock };

// A decoded request. On a fault, `request.envelope` (or `block.address`) holds what was read before the
// fault, which is all an error reply needs.
struct DecodedRequest {
  FrameFault fault = FrameFault::kNone;
  RequestKind kind = RequestKind::kRegister;
  Request request{};     // kind == kRegister
  BlockRequest block{};  // kind == kBlock
  constexpr bool ok() const { return fault == FrameFault::kNone; }
};

enum class ReplyKind : std::uint8_t { kRegister, kError, kBlock };

struct DecodedReply {
  FrameFault fault = FrameFault::kNone;
  ReplyKind kind = ReplyKind::kRegister;
  Reply reply{};       // kind == kRegister
  ErrorReply error{};  // kind == kError
  BlockReply block{};  // kind == kBlock
  constexpr bool ok() const { return fault == FrameFault::kNone; }
};

// --- Checksums (p.8, p.11, p.14) ---

// Binary: low byte of the sum of every byte from the start code 2Fh through the last data byte (through
// the communication number for R), the inverter number included.
std::uint8_t BinaryChecksum(std::span<const std::uint8_t> bytes);
// ASCII: the low byte of the sum of every character from "(" through "&" inclusive, as the two uppercase
// hex characters that follow the "&".
std::array<std::uint8_t, 2> AsciiChecksum(std::span<const std::uint8_t> bytes);

// --- Addressing ---

// Whether an inverter numbered `own_number` (F802) acts on and answers a frame with this address. In a
// broadcast only the representative answers: inverter 00 for "**"/FFh, and the member with 0 in the
// '*' position for "*n"/"n*". Numbers a mode cannot carry (ASCII > 99, binary > 63) are never members.
Addressing ResolveAddress(Mode mode, InverterAddress address, std::uint8_t own_number);
// The address a reply carries: omitted if the request omitted it, else the replier's own number.
InverterAddress ReplyAddress(InverterAddress request, std::uint8_t own_number);
Envelope ReplyEnvelope(const Envelope& request, std::uint8_t own_number);
// Read groups a block reply returns: the request's count, or 0 when it is above 5 (4.1.3).
std::uint8_t ReadGroupsToReturn(const BlockRequest& request);

// --- Decoders: `frame` is exactly one frame (the StreamFramer's output) ---

DecodedRequest DecodeRequest(std::span<const std::uint8_t> frame,
                             BlockWriteLimit block_limit = BlockWriteLimit::kParameters);
DecodedReply DecodeReply(std::span<const std::uint8_t> frame);

// How the inverter answers a request that failed to decode (p.10, p.13, p.17, p.21): an error code for
// checksum errors and, in ASCII, command / communication-number / data errors and 'M'; nothing for
// format, receive, inter-drive and binary command errors. Addressing (ResolveAddress) is decided first.
std::optional<ErrorCode> ErrorReplyFor(Mode mode, FrameFault fault);
// The same for a decoded request, in the mode it came in.
std::optional<ErrorCode> ErrorReplyFor(const DecodedRequest& decoded);

// --- Encoders: write one frame into `out`, return its length ---
// kInvalidArgument when a field cannot be carried (G or a block in ASCII, a number the mode cannot
// carry, a group broadcast in binary or in a reply, more data than the ASCII digit count holds, counts
// over the limits); kResourceExhausted when `out` is too small (kMaxFrameLength always suffices).

base::Result<std::size_t> EncodeRequest(const Request& request, std::span<std::uint8_t> out);
base::Result<std::size_t> EncodeReply(const Reply& reply, std::span<std::uint8_t> out);
base::Result<std::size_t> EncodeErrorReply(const ErrorReply& reply, std::span<std::uint8_t> out);
base::Result<std::size_t> EncodeBlockRequest(const BlockRequest& request, std::span<std::uint8_t> out);
base::Result<std::size_t> EncodeBlockReply(const BlockReply& reply, std::span<std::uint8_t> out);

// --- Stream framer ---

// Which frames a receiver expects: the simulated inverter receives requests, the card receives replies.
// Binary lengths differ between the two (an R request has no data, its reply has).
enum class Direction : std::uint8_t { kRequests, kReplies };

struct FramerCounters {
  std::uint32_t frames = 0;          // complete frames delivered
  std::uint32_t garbage_bytes = 0;   // bytes outside any frame (before a start code)
  std::uint32_t dropped_frames = 0;  // partial frames discarded: restart, overlong, bad header, gap
};

// Cuts a received byte stream into frames, following the inverter's reception rules (p.6-7): bytes
// before a start code are ignored; a new start code before the command restarts the frame ("the last
// one wins"; in ASCII any '(' does); an ASCII frame ends at a CR in or after the position where the
// CR may first stand (a CR inside the 4-character communication number is taken as a character, p.21);
// a binary frame ends when the byte count its command implies has arrived. A frame that cannot be
// completed (over kMaxFrameLength bytes, unknown binary command, block count out of range) is dropped
// and the byte that revealed it is looked at again as a possible start code. Frames are delivered
// whole, never checked: the decoders judge them. Fixed-size, no allocation.
class StreamFramer {
 public:
  struct FeedResult {
    std::size_t consumed = 0;  // bytes of the input taken, up to and including a completed frame
    bool frame_ready = false;  // frame() holds a complete frame
  };

  explicit StreamFramer(Direction direction) : direction_(direction) {}

  // Takes bytes until one frame completes or the input ends. Call again with the rest of the input
  // (bytes.subspan(consumed)) for the frames after it.
  FeedResult Feed(std::span<const std::uint8_t> bytes);
  // The frame completed by the last Feed; valid until the next Feed, GapElapsed or Reset.
  std::span<const std::uint8_t> frame() const;
  // The caller's receive timer (kFrameTimeout since the start code) expired: drop a partial frame.
  void GapElapsed();
  void Reset();
  // A partial frame is waiting: the caller should run its receive timer.
  bool frame_in_progress() const { return state_ == State::kAscii || state_ == State::kBinary; }
  const FramerCounters& counters() const { return counters_; }

 private:
  enum class State : std::uint8_t { kHunting, kAscii, kBinary, kReady };

  void Step(std::uint8_t byte);
  void Hunt(std::uint8_t byte);
  void StepAscii(std::uint8_t byte);
  void StepBinary(std::uint8_t byte);
  void Start(std::uint8_t byte, State state);
  void Drop();
  std::size_t BinaryLengthFrom(std::size_t command_index, bool& impossible) const;

  Direction direction_;
  State state_ = State::kHunting;
  std::size_t length_ = 0;
  std::size_t expected_ = 0;  // binary: total length once the command (and count) are known, else 0
  std::array<std::uint8_t, kMaxFrameLength> buffer_{};
  FramerCounters counters_;
};

}  // namespace drive_link::wire
