// One Modbus TCP client connection: its stream framer, its requests and its answers.
//
// Bytes in -> ADUs -> one request at a time -> answers out, in request order. A client may pipeline:
// whatever it sends is kept in the receive buffer (kReceiveBufferBytes, as large as lwIP's receive
// window, so everything TCP delivers fits; the window closes while it is full) and served in order
// after the current answer. A request is started only while the answer buffer has room for a largest
// answer, so a client that does not read its answers stops being served, and then stops being able to
// send. Bytes leave the receive buffer (and are reported for the window) when their request has been
// answered.
//
// Framing (docs/modbus.md "Framing"): a header that cannot be framed (protocol id not 0, length 0, 1
// or above 254) ends the connection once the requests before it are answered: nothing after it can be
// delimited. A connection without a request for `idle_timeout` is closed as well (a client that is
// alive but silent holds one of the 8 slots; dead peers are also found by TCP keepalive).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "config/card_config.h"
#include "drive_link/register_access.h"
#include "hal/clock.h"
#include "modbus/drive_transfer.h"
#include "modbus/io_scanning.h"
#include "modbus/loss_timer.h"
#include "modbus/mbap.h"
#include "modbus/option_board.h"
#include "modbus/pdu.h"

namespace modbus {

// lwIP's TCP_WND (536, one TCP_MSS): the binding checks that the window never exceeds it, and that a
// buffer holding a partial largest ADU (259 bytes) can still free the half window lwIP needs before it
// reopens the window (536 - 259 >= 268). A pipelining client may have about two largest ADUs, or 44
// 12-byte requests, waiting; then its window is closed until requests are answered.
inline constexpr std::size_t kReceiveBufferBytes = 536;
// Two answers: one being handed to TCP while the next is built.
inline constexpr std::size_t kAnswerBufferBytes = 2 * kMaxAduBytes;

struct ServerCounters {
  std::uint32_t accepted = 0;        // connections opened
  std::uint32_t refused = 0;         // connections refused: all kMaxClients slots taken
  std::uint32_t requests = 0;        // ADUs framed
  std::uint32_t exceptions = 0;      // answers that were exceptions
  std::uint32_t framing_errors = 0;  // connections ended by a header that cannot be framed
  std::uint32_t idle_closes = 0;     // connections ended by idle_timeout
  std::uint32_t counted = 0;         // requests that counted as communication for c523
};

// What every connection shares; owned by the Server.
struct ServerShared {
  ServerShared(drive_link::DriveRegisters& drive_registers, drive_link::ScannerImage& scanner_image,
               drive_link::LossSupervision& supervision)
      : drive(drive_registers), scanner(scanner_image), loss(supervision) {}

  drive_link::DriveRegisters& drive;
  drive_link::ScannerImage& scanner;
  LossTimer loss;
  config::CardConfig config;
  OptionBoardData board;
  hal::Micros idle_timeout = 0;  // 0: never
  std::uint16_t clients = 0;
  ServerCounters counters;
};

class Connection final : public drive_link::AccessListener {
 public:
  Connection() = default;
  Connection(const Connection&) = delete;
  Connection& operator=(const Connection&) = delete;

  void Attach(ServerShared& shared) { shared_ = &shared; }

  void Open(const base::Ipv4Address& peer, hal::Micros now);
  // Cancels the drive accesses in flight and forgets everything.
  void Close();
  bool is_open() const { return open_; }

  // Takes as many bytes as the receive buffer has room for; returns how many.
  std::size_t Receive(std::span<const std::uint8_t> bytes, hal::Micros now);
  std::span<const std::uint8_t> answers() const { return std::span<const std::uint8_t>(answers_).first(answer_length_); }
  // The first `count` answer bytes were handed to TCP.
  void ConsumeAnswers(std::size_t count, hal::Micros now);
  // Receive-buffer bytes freed since the last call (for the TCP window).
  std::size_t TakeReleasedInput();
  // Framing error or idle: the connection must be closed (after handing over answers()).
  bool must_close() const { return must_close_; }

  void Poll(hal::Micros now);
  hal::Micros NextDeadline() const;

  void OnAccessDone(drive_link::AccessToken token, const drive_link::AccessResult& result) override;

 private:
  void Frame(hal::Micros now);
  bool CountsAsCommunication(const MbapHeader& header, std::span<const std::uint8_t> pdu) const;
  void Serve(hal::Micros now);
  void Begin(const MbapHeader& header, std::span<const std::uint8_t> pdu, hal::Micros now);
  void BeginDrive(const Request& request, hal::Micros now);
  void FinishDrive();
  void Answer(std::span<const std::uint8_t> pdu);
  void AnswerException(std::uint8_t function, ExceptionCode code);
  void ReleaseFront();

  ServerShared* shared_ = nullptr;
  bool open_ = false;
  bool must_close_ = false;
  base::Ipv4Address peer_{};
  hal::Micros last_request_at_ = 0;
  hal::Micros now_hint_ = 0;  // the latest time seen, for work started from a completion

  std::array<std::uint8_t, kReceiveBufferBytes> input_{};
  std::size_t input_length_ = 0;
  std::size_t framed_ = 0;    // input bytes delimited into whole ADUs (their arrival handled)
  bool broken_ = false;       // the bytes after framed_ start with a header that cannot be framed
  std::size_t released_ = 0;  // freed input bytes not yet reported

  std::array<std::uint8_t, kAnswerBufferBytes> answers_{};
  std::size_t answer_length_ = 0;

  // The request at the front of the input while the drive works on it.
  bool busy_ = false;
  MbapHeader header_;
  Request request_;
  DriveTransfer transfer_;
};

}  // namespace modbus
