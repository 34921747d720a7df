// hal::SerialPort on a CMSDK APB UART, interrupt driven both ways: the receive interrupt moves each
// byte into a queue the loop reads (SerialReceiveQueue: losses reported as kDataLoss at their place),
// Write() queues bytes that the transmit interrupt feeds to the one-byte transmit buffer.
//
// Parity: the CMSDK UART has no parity generator or checker; it always sends 8N1. The drive link asks
// for 8E1 (Toshiba protocol). What Configure() does with that depends on what the UART is wired to
// (Line): on a real RS-485 line (kWire) 8E1 cannot be made and Configure() refuses it
// (kInvalidArgument), so a board that needs 8E1 must use a UART with parity (docs/board.md "Parity");
// under QEMU the UART ends in a character device (kEmulatedByteStream) that carries whole bytes, with no
// bit framing on which parity or stop bits could exist, so any framing is accepted as given.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

#include "base/status.h"
#include "byte_ring.h"
#include "cmsdk_uart_registers.h"
#include "cortex_m.h"
#include "hal/serial_port.h"
#include "interrupts.h"
#include "mmio.h"
#include "mps2_an386.h"
#include "serial_receive_queue.h"

namespace hal::mps2 {

enum class UartLine : std::uint8_t {
  kWire,                // a real line: only what the UART can do (8N1)
  kEmulatedByteStream,  // QEMU's chardev: bytes without bit framing
};

template <std::size_t kReceiveBytes, std::size_t kTransmitBytes>
class CmsdkUart final : public SerialPort {
 public:
  CmsdkUart(std::uintptr_t base, Irq receive_irq, Irq transmit_irq, UartLine line)
      : base_(base), receive_irq_(receive_irq), transmit_irq_(transmit_irq), line_(line) {}
  CmsdkUart(const CmsdkUart&) = delete;
  CmsdkUart& operator=(const CmsdkUart&) = delete;

  // Programs the baud rate and enables both directions with their interrupts. kInvalidArgument: a baud
  // rate the divider cannot make (BAUDDIV 16 .. 2^20 - 1), stop bits other than 1 or 2, or a framing
  // this line cannot carry (see UartLine).
  base::Status Configure(const SerialConfig& config) override {
    const std::uint32_t divider = config.baud == 0 ? 0 : kSystemClockHz / config.baud;
    if (divider < uart_reg::kMinBaudDiv || divider > 0xFFFFF) return base::InvalidArgument();
    if (config.stop_bits != 1 && config.stop_bits != 2) return base::InvalidArgument();
    if (line_ == UartLine::kWire && (config.parity != Parity::kNone || config.stop_bits != 1)) {
      return base::InvalidArgument();
    }
    CriticalSection masked;
    Write32(base_ + uart_reg::kCtrl, 0);
    Write32(base_ + uart_reg::kBaudDiv, divider);
    Write32(base_ + uart_reg::kIntStatus, uart_reg::kIntTx | uart_reg::kIntRx);
    Write32(base_ + uart_reg::kState, uart_reg::kStateTxOverrun | uart_reg::kStateRxOverrun);
    Write32(base_ + uart_reg::kCtrl, uart_reg::kCtrlTxEnable | uart_reg::kCtrlRxEnable | uart_reg::kCtrlTxInterrupt |
                                         uart_reg::kCtrlRxInterrupt);
    if (!bound_) {
      BindInterrupt(receive_irq_, receive_handler_);
      BindInterrupt(transmit_irq_, transmit_handler_);
      bound_ = true;
    }
    configured_ = true;
    FeedTransmitter();
    return base::OkStatus();
  }

  base::Result<std::size_t> Read(std::span<std::uint8_t> buffer) override { return received_.Read(buffer); }

  // Queues what fits; the bytes go out as the transmitter takes them (none before Configure()).
  base::Result<std::size_t> Write(std::span<const std::uint8_t> bytes) override {
    std::size_t queued = 0;
    while (queued < bytes.size() && transmit_.Push(bytes[queued])) ++queued;
    if (configured_) {
      CriticalSection masked;
      FeedTransmitter();
    }
    return queued;
  }

  // Bytes not yet handed to the transmitter.
  std::size_t transmit_pending() const { return transmit_.size(); }
  // Bytes the transmit queue can still take.
  std::size_t transmit_room() const { return kTransmitBytes - transmit_.size(); }
  // Receive losses (overruns, a full queue) so far.
  std::uint32_t receive_losses() const { return received_.losses(); }

 private:
  // Fills the one-byte transmit buffer while it is free (under QEMU the byte leaves at once, so this
  // drains the whole queue). Runs with the transmit interrupt unable to preempt it.
  void FeedTransmitter() {
    std::uint8_t byte;
    while ((Read32(base_ + uart_reg::kState) & uart_reg::kStateTxFull) == 0 && transmit_.Pop(byte)) {
      Write32(base_ + uart_reg::kData, byte);
    }
  }

  bool OnReceive() {
    Write32(base_ + uart_reg::kIntStatus, uart_reg::kIntRx);
    if ((Read32(base_ + uart_reg::kState) & uart_reg::kStateRxOverrun) != 0) {
      Write32(base_ + uart_reg::kState, uart_reg::kStateRxOverrun);
      received_.MarkLoss();
    }
    while ((Read32(base_ + uart_reg::kState) & uart_reg::kStateRxFull) != 0) {
      received_.Store(static_cast<std::uint8_t>(Read32(base_ + uart_reg::kData)));
    }
    return true;
  }

  bool OnTransmit() {
    Write32(base_ + uart_reg::kIntStatus, uart_reg::kIntTx);
    FeedTransmitter();
    return false;  // a byte gone out is no work for the loop
  }

  class ReceiveHandler final : public InterruptHandler {
   public:
    explicit ReceiveHandler(CmsdkUart& uart) : uart_(uart) {}
    bool OnInterrupt() override { return uart_.OnReceive(); }

   private:
    CmsdkUart& uart_;
  };
  class TransmitHandler final : public InterruptHandler {
   public:
    explicit TransmitHandler(CmsdkUart& uart) : uart_(uart) {}
    bool OnInterrupt() override { return uart_.OnTransmit(); }

   private:
    CmsdkUart& uart_;
  };

  const std::uintptr_t base_;
  const Irq receive_irq_;
  const Irq transmit_irq_;
  const UartLine line_;
  SerialReceiveQueue<kReceiveBytes> received_;
  ByteRing<kTransmitBytes> transmit_;
  ReceiveHandler receive_handler_{*this};
  TransmitHandler transmit_handler_{*this};
  bool configured_ = false;
  bool bound_ = false;
};

}  // namespace hal::mps2
