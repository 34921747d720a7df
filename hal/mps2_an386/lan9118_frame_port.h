// hal::FramePort on the SMSC LAN9118 of mps2-an386: one MAC, one port (PortCount() == 1, port L).
//
// Receive is interrupt driven: the chip interrupts when a frame's status enters its RX status FIFO
// (and on PHY and error events); the handler only clears the interrupt and wakes the loop. Receive()
// then takes the oldest frame from the chip's RX FIFOs: its status word (length, error summary), then
// its data words. A frame the MAC flagged (CRC, runt, too long) is read out and dropped as kDataLoss;
// one longer than kMaxFrameBytes or the caller's buffer as kOutOfRange; both count as rx errors.
// Transmit() checks the TX data FIFO's free space (kResourceExhausted when the frame does not fit),
// writes command A/B and the data, and tags the frame with its length; the TX status words are collected
// on every Receive()/Transmit() and count the frame sent (tx_frames, tx_octets) or failed (tx_errors).
// Link: the PHY's basic status register (link, auto-negotiation done) and the best mode both ends
// advertise, read at start and on every PHY interrupt; the MAC's duplex follows it. Multicast: the hash
// filter of MulticastFilter (multicast_filter.h), reprogrammed at each join and leave.
//
// Register sequences of the MAC and PHY (MAC_CSR_CMD/DATA) run with interrupts masked, since the
// interrupt handler uses them too (a PHY event).
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <span>

#include "base/status.h"
#include "hal/frame_port.h"
#include "interrupts.h"
#include "multicast_filter.h"

namespace hal::mps2 {

class Lan9118FramePort final : public FramePort, private InterruptHandler {
 public:
  Lan9118FramePort() = default;
  Lan9118FramePort(const Lan9118FramePort&) = delete;
  Lan9118FramePort& operator=(const Lan9118FramePort&) = delete;

  // Resets the chip, programs `mac`, the filters and the PHY (auto-negotiation, all modes), enables
  // receive, transmit and the interrupt. kUnavailable: the chip does not answer (BYTE_TEST) or does not
  // come out of reset; kNotFound: an unknown chip ID. After a failure the port stays without link.
  base::Status Start(const base::MacAddress& mac);
  // The chip's ID_REV as read by Start() (0: not read).
  std::uint32_t chip_id() const { return chip_id_; }

  base::MacAddress Mac() const override { return mac_; }
  std::size_t PortCount() const override { return 1; }
  LinkState Link(PortId port) const override;
  PortCounters Counters(PortId port) const override;
  base::Result<ReceivedFrame> Receive(std::span<std::uint8_t> buffer) override;
  base::Status Transmit(PortId port, std::span<const std::uint8_t> frame) override;
  base::Status JoinMulticast(const base::MacAddress& group) override;
  base::Status LeaveMulticast(const base::MacAddress& group) override;

 private:
  bool OnInterrupt() override;
  std::uint32_t ReadMac(std::uint32_t index) const;
  void WriteMac(std::uint32_t index, std::uint32_t value);
  std::uint32_t ReadPhy(std::uint32_t index) const;
  void WritePhy(std::uint32_t index, std::uint32_t value);
  void UpdateLink();           // reads the PHY; sets the MAC's duplex (interrupts masked)
  void ProgramMulticast();     // HASHH/HASHL and MCPAS from filter_ (interrupts masked)
  void CollectTransmitStatus();
  void DiscardWords(std::size_t words);

  base::MacAddress mac_{};
  std::uint32_t chip_id_ = 0;
  bool started_ = false;
  LinkState link_{};
  MulticastFilter filter_;
  PortCounters counters_{};
  // Counted by the interrupt handler (added to counters_ when read).
  std::atomic<std::uint32_t> irq_rx_errors_{0};
  std::atomic<std::uint32_t> irq_tx_errors_{0};
};

}  // namespace hal::mps2
