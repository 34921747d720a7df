#include "modbus/connection.h"

#include <algorithm>
#include <cstring>

#include "drive_link/drive_registers.h"
#include "modbus/device_identification.h"

namespace modbus {
namespace {

// The option command registers (FA00-FAFF): writing them is commanding the drive.
constexpr std::uint16_t kCommandAreaFirst = 0xFA00;
constexpr std::uint16_t kCommandAreaLast = 0xFAFF;

bool WritesCommandArea(std::uint16_t first, std::uint16_t count) {
  std::uint32_t number = first;
  for (std::uint16_t i = 0; i < count && number <= 0xFFFF; ++i, number = NextCommunicationNumber(number)) {
    if (number >= kCommandAreaFirst && number <= kCommandAreaLast) return true;
  }
  return false;
}

// Which functions each server implements (docs/modbus.md "Functions"): the board's server is
// read-only (its configuration lives in the inverter as c-parameters) and FC 23 is reserved for IO
// scanning (§8.7).
bool ServesFunction(UnitKind unit, std::uint8_t function) {
  switch (function) {
    case fc::kReadHoldingRegisters:
    case fc::kEncapsulatedInterface:
      return true;
    case fc::kWriteSingleRegister:
    case fc::kWriteMultipleRegisters:
      return unit == UnitKind::kDrive || unit == UnitKind::kIoScanner;
    case fc::kReadWriteMultipleRegisters:
      return unit == UnitKind::kIoScanner;
    default:
      return false;
  }
}

}  // namespace

void Connection::Open(const base::Ipv4Address& peer, hal::Micros now) {
  open_ = true;
  must_close_ = false;
  peer_ = peer;
  last_request_at_ = now;
  now_hint_ = now;
  input_length_ = 0;
  framed_ = 0;
  broken_ = false;
  released_ = 0;
  answer_length_ = 0;
  busy_ = false;
  transfer_.Reset();
}

void Connection::Close() {
  if (shared_ != nullptr && transfer_.state() == DriveTransfer::State::kRunning) shared_->drive.Cancel(*this);
  transfer_.Reset();
  open_ = false;
  busy_ = false;
  must_close_ = false;
  input_length_ = 0;
  framed_ = 0;
  broken_ = false;
  released_ = 0;
  answer_length_ = 0;
}

std::size_t Connection::Receive(std::span<const std::uint8_t> bytes, hal::Micros now) {
  if (!open_) return 0;
  now_hint_ = now;
  if (must_close_) {
    // Nothing more is served: take the bytes so that they do not hold the window.
    released_ += bytes.size();
    return bytes.size();
  }
  const std::size_t taken = std::min(bytes.size(), input_.size() - input_length_);
  std::copy_n(bytes.begin(), taken, input_.begin() + static_cast<std::ptrdiff_t>(input_length_));
  input_length_ += taken;
  Frame(now);
  Serve(now);
  return taken;
}

// Delimits the ADUs that became whole and does what their arrival means: the idle and c523 timers
// run from the moment a request arrived, not from when its turn came.
void Connection::Frame(hal::Micros now) {
  while (!broken_) {
    const std::span<const std::uint8_t> rest =
        std::span<const std::uint8_t>(input_).subspan(framed_, input_length_ - framed_);
    const FrameResult frame = FindFrame(rest);
    if (frame.check == FrameCheck::kNeedMore) return;
    if (frame.check == FrameCheck::kBadHeader) {
      broken_ = true;
      ++shared_->counters.framing_errors;
      return;
    }
    ++shared_->counters.requests;
    last_request_at_ = now;
    if (CountsAsCommunication(frame.header, PduOf(rest.first(frame.adu_length)))) {
      ++shared_->counters.counted;
      shared_->loss.Communicated(now);
    }
    framed_ += frame.adu_length;
  }
}

// docs/modbus.md "Loss supervision": with IO scanning (c604 = 1), a write of output words to unit
// 255 by a client allowed to scan; without it, a write (FC 06/16) to units 0-248 that reaches the
// command area FA00-FAFF. Reads, parameter writes and malformed requests do not count: a monitoring
// client must neither keep a lost master's drive running nor trip it when it goes away.
bool Connection::CountsAsCommunication(const MbapHeader& header, std::span<const std::uint8_t> pdu) const {
  const DecodedRequest decoded = DecodeRequest(pdu);
  if (!decoded.ok()) return false;
  const Request& request = decoded.request;
  const UnitKind unit = ClassifyUnit(header.unit_id);
  if (shared_->config.io_scanning) {
    return unit == UnitKind::kIoScanner && IsIoScanningWrite(request) &&
           IoScanningAccess(shared_->config, peer_) == ExceptionCode::kNone;
  }
  const bool write = request.function == fc::kWriteSingleRegister ||
                     request.function == fc::kWriteMultipleRegisters;
  return unit == UnitKind::kDrive && write && WritesCommandArea(request.write_address, request.write_count);
}

// Serves the framed requests in order while the answer buffer has room for a largest answer.
void Connection::Serve(hal::Micros now) {
  while (open_ && !must_close_ && !busy_ && framed_ > 0 && answers_.size() - answer_length_ >= kMaxAduBytes) {
    const std::span<const std::uint8_t> front = std::span<const std::uint8_t>(input_).first(framed_);
    const FrameResult frame = FindFrame(front);
    const std::span<const std::uint8_t> adu = front.first(frame.adu_length);
    Begin(frame.header, PduOf(adu), now);
  }
  if (open_ && broken_ && !busy_ && framed_ == 0) {
    // Everything before the bad header is answered: drop the rest and let the binding close.
    released_ += input_length_;
    input_length_ = 0;
    must_close_ = true;
  }
}

void Connection::Begin(const MbapHeader& header, std::span<const std::uint8_t> pdu, hal::Micros now) {
  header_ = header;
  const UnitKind unit = ClassifyUnit(header.unit_id);
  const std::uint8_t function = pdu.empty() ? std::uint8_t{0} : pdu[0];
  // The order of the Modbus specification: the server, the function, then the data.
  if (unit == UnitKind::kNone) return AnswerException(function, ExceptionCode::kGatewayPathUnavailable);
  if (!ServesFunction(unit, function)) return AnswerException(function, ExceptionCode::kIllegalFunction);
  if (unit == UnitKind::kIoScanner && function != fc::kEncapsulatedInterface) {
    const ExceptionCode access = IoScanningAccess(shared_->config, peer_);
    if (access != ExceptionCode::kNone) return AnswerException(function, access);
  }
  const DecodedRequest decoded = DecodeRequest(pdu);
  if (!decoded.ok()) return AnswerException(function, decoded.exception);
  const Request& request = decoded.request;

  std::array<std::uint8_t, kMaxPduBytes> pdu_buffer{};
  base::ByteWriter writer(pdu_buffer);
  if (request.function == fc::kEncapsulatedInterface) {
    const IdentitySubject subject = unit == UnitKind::kDrive ? IdentitySubject::kDrive : IdentitySubject::kOptionBoard;
    WriteDeviceIdentification(writer, subject, shared_->board, request.device_id_code, request.object_id);
    return Answer(writer.written());
  }
  switch (unit) {
    case UnitKind::kIoScanner:
      ServeIoScanner(request, shared_->scanner, writer);
      return Answer(writer.written());
    case UnitKind::kOptionBoard: {
      const OptionBoardView view{shared_->board, shared_->config, shared_->clients, shared_->loss.state()};
      std::array<std::uint16_t, kMaxReadRegisters> values{};
      for (std::uint16_t i = 0; i < request.read_count; ++i) {
        const base::Result<std::uint16_t> value =
            ReadOptionBoardRegister(view, static_cast<std::uint16_t>(request.read_address + i));
        if (!value.ok()) return AnswerException(function, ExceptionCode::kIllegalDataAddress);
        values[i] = *value;
      }
      WriteRegisterValues(writer, request.function, std::span<const std::uint16_t>(values).first(request.read_count));
      return Answer(writer.written());
    }
    case UnitKind::kDrive:
      return BeginDrive(request, now);
    case UnitKind::kNone:
      break;
  }
}

void Connection::BeginDrive(const Request& request, hal::Micros now) {
  const ExceptionCode check =
      request.function == fc::kReadHoldingRegisters
          ? CheckDriveRead(request.read_address, request.read_count)
          : CheckDriveWrite(request.write_address, request.values(), shared_->drive,
                            ControlLockedFor(shared_->config, peer_));
  if (check != ExceptionCode::kNone) return AnswerException(request.function, check);
  request_ = request;
  busy_ = true;
  if (request.function == fc::kReadHoldingRegisters) {
    transfer_.StartRead(shared_->drive, *this, request.read_address, request.read_count, now);
  } else {
    transfer_.StartWrite(shared_->drive, *this, request.write_address, request.values(), now);
  }
  if (transfer_.done()) FinishDrive();
}

void Connection::FinishDrive() {
  busy_ = false;
  const ExceptionCode exception = transfer_.exception();
  if (exception != ExceptionCode::kNone) {
    transfer_.Reset();
    return AnswerException(request_.function, exception);
  }
  std::array<std::uint8_t, kMaxPduBytes> pdu_buffer{};
  base::ByteWriter writer(pdu_buffer);
  switch (request_.function) {
    case fc::kReadHoldingRegisters:
      WriteRegisterValues(writer, request_.function, transfer_.values());
      break;
    case fc::kWriteSingleRegister:
      WriteSingleRegisterAnswer(writer, request_.write_address, request_.write_values[0]);
      break;
    default:
      WriteMultipleRegistersAnswer(writer, request_.write_address, request_.write_count);
      break;
  }
  transfer_.Reset();
  Answer(writer.written());
}

void Connection::AnswerException(std::uint8_t function, ExceptionCode code) {
  ++shared_->counters.exceptions;
  std::array<std::uint8_t, 2> pdu_buffer{};
  base::ByteWriter writer(pdu_buffer);
  WriteException(writer, function, code);
  Answer(writer.written());
}

// Appends the answer to the request at the front of the input and releases that request.
void Connection::Answer(std::span<const std::uint8_t> pdu) {
  base::ByteWriter writer(std::span<std::uint8_t>(answers_).subspan(answer_length_));
  WriteMbapHeader(writer, header_, pdu.size());
  writer.Bytes(pdu);
  // Serve() only starts a request with room for a largest answer, so this always fits.
  if (writer.ok()) answer_length_ += writer.size();
  ReleaseFront();
}

void Connection::ReleaseFront() {
  const std::size_t length = FindFrame(std::span<const std::uint8_t>(input_).first(framed_)).adu_length;
  std::memmove(input_.data(), input_.data() + length, input_length_ - length);
  input_length_ -= length;
  framed_ -= length;
  released_ += length;
}

void Connection::ConsumeAnswers(std::size_t count, hal::Micros now) {
  count = std::min(count, answer_length_);
  std::memmove(answers_.data(), answers_.data() + count, answer_length_ - count);
  answer_length_ -= count;
  now_hint_ = now;
  Serve(now);
}

std::size_t Connection::TakeReleasedInput() {
  const std::size_t released = released_;
  released_ = 0;
  return released;
}

void Connection::Poll(hal::Micros now) {
  if (!open_) return;
  now_hint_ = now;
  if (busy_) {
    transfer_.Poll(now);
    if (transfer_.done()) FinishDrive();
  }
  Serve(now);
  const hal::Micros idle = shared_->idle_timeout;
  if (!must_close_ && idle != 0 && now - last_request_at_ >= idle) {
    must_close_ = true;
    ++shared_->counters.idle_closes;
  }
}

hal::Micros Connection::NextDeadline() const {
  if (!open_ || must_close_) return hal::kNever;
  hal::Micros deadline = busy_ ? transfer_.NextDeadline() : hal::kNever;
  if (shared_->idle_timeout != 0) deadline = std::min(deadline, last_request_at_ + shared_->idle_timeout);
  return deadline;
}

void Connection::OnAccessDone(drive_link::AccessToken token, const drive_link::AccessResult& result) {
  if (!open_ || !busy_) return;
  if (!transfer_.Complete(token, result, now_hint_)) return;
  if (!transfer_.done()) return;
  FinishDrive();
  Serve(now_hint_);
}

}  // namespace modbus
