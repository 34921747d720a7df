#include "lan9118_frame_port.h"

#include "base/byte_reader.h"
#include "cortex_m.h"
#include "lan9118_registers.h"
#include "mmio.h"
#include "mps2_an386.h"

namespace hal::mps2 {
namespace {

using namespace lan9118;  // NOLINT: the register names of this one chip

constexpr std::uintptr_t kBase = address::kEthernet;
// Polls of a busy bit (a soft reset takes ~ms on the chip; QEMU is done at once).
constexpr unsigned kBusySpins = 1'000'000;

std::uint32_t Csr(std::uintptr_t offset) { return Read32(kBase + offset); }
void SetCsr(std::uintptr_t offset, std::uint32_t value) { Write32(kBase + offset, value); }

// ID_REV bits 31..16: LAN9118 (QEMU's model), LAN9220 (the real MPS2 board); both have the same
// registers for what this driver does.
bool KnownChip(std::uint32_t id_rev) {
  const std::uint32_t id = id_rev >> 16;
  return id == 0x0118 || id == 0x9220;
}

bool WaitWhile(std::uintptr_t offset, std::uint32_t mask, std::uint32_t value) {
  for (unsigned spin = 0; spin < kBusySpins; ++spin) {
    if ((Csr(offset) & mask) != value) return true;
  }
  return false;
}

// The fastest mode both ends of an auto-negotiated link advertise.
LinkState Resolve(std::uint32_t control, std::uint32_t status, std::uint32_t advertised, std::uint32_t partner) {
  LinkState link;
  link.up = (status & kBsrLinkUp) != 0;
  if (!link.up) return link;
  link.auto_negotiated = (control & kBcrAutoNegEnable) != 0 && (status & kBsrAutoNegComplete) != 0;
  if (!link.auto_negotiated) {
    link.speed = (control & kBcrSpeed100) != 0 ? LinkSpeed::k100Mbps : LinkSpeed::k10Mbps;
    link.full_duplex = (control & kBcrFullDuplex) != 0;
    return link;
  }
  const std::uint32_t common = advertised & partner;
  if ((common & kAbility100Full) != 0) {
    link.speed = LinkSpeed::k100Mbps;
    link.full_duplex = true;
  } else if ((common & kAbility100Half) != 0) {
    link.speed = LinkSpeed::k100Mbps;
  } else if ((common & kAbility10Full) != 0) {
    link.speed = LinkSpeed::k10Mbps;
    link.full_duplex = true;
  } else {
    link.speed = LinkSpeed::k10Mbps;
  }
  return link;
}

}  // namespace

base::Status Lan9118FramePort::Start(const base::MacAddress& mac) {
  mac_ = mac;
  if (Csr(kByteTest) != kByteTestValue) return base::Unavailable();
  chip_id_ = Csr(kIdRev);
  if (!KnownChip(chip_id_)) return base::NotFound();

  SetCsr(kHwCfg, kHwCfgSoftReset);
  if (!WaitWhile(kHwCfg, kHwCfgSoftReset, kHwCfgSoftReset)) return base::Unavailable();
  if (!WaitWhile(kPmtCtrl, kPmtCtrlReady, 0)) return base::Unavailable();
  SetCsr(kHwCfg, kHwCfgMustBeOne | kHwCfgTxFifo5K);
  SetCsr(kAfcCfg, kAfcCfgDefault);
  SetCsr(kIntEn, 0);
  SetCsr(kIntSts, 0xFFFFFFFFU);
  SetCsr(kFifoInt, kFifoIntLevels);
  SetCsr(kRxCfg, 0);  // no offset, 4-byte end alignment
  SetCsr(kTxCfg, kTxCfgTxOn);

  {
    CriticalSection masked;
    // ADDRL holds octets 0-3 and ADDRH octets 4-5, each little-endian.
    base::ByteReader octets(mac.octets());
    WriteMac(kMacAddrL, octets.U32Le());
    WriteMac(kMacAddrH, octets.U16Le());
    // Own unicast address only (perfect filter), broadcast, multicast by the hash table.
    WriteMac(kMacCr, kMacCrTxEnable | kMacCrRxEnable | kMacCrHashPerfectFilter);
    ProgramMulticast();

    WritePhy(kPhyBasicControl, kBcrReset);
    for (unsigned spin = 0; spin < kBusySpins && (ReadPhy(kPhyBasicControl) & kBcrReset) != 0; ++spin) {
    }
    WritePhy(kPhyAdvertisement, kAdvertiseAll);
    WritePhy(kPhyBasicControl, kBcrAutoNegEnable | kBcrRestartAutoNeg);
    WritePhy(kPhyInterruptMask, kPhyIntEnergyOn | kPhyIntAutoNegComplete | kPhyIntLinkDown);
    static_cast<void>(ReadPhy(kPhyInterruptSource));  // clears what the reset left
    UpdateLink();
    started_ = true;
  }

  SetCsr(kIntSts, 0xFFFFFFFFU);
  SetCsr(kIntEn, kIntRxStatusLevel | kIntRxDropped | kIntRxError | kIntTxError | kIntPhy);
  // Push-pull, active high: the level the NVIC line expects.
  SetCsr(kIrqCfg, kIrqCfgEnable | kIrqCfgPolarity | kIrqCfgType);
  BindInterrupt(Irq::kEthernet, *this);
  return base::OkStatus();
}

std::uint32_t Lan9118FramePort::ReadMac(std::uint32_t index) const {
  SetCsr(kMacCsrCmd, kMacCsrBusy | kMacCsrRead | index);
  WaitWhile(kMacCsrCmd, kMacCsrBusy, kMacCsrBusy);
  return Csr(kMacCsrData);
}

void Lan9118FramePort::WriteMac(std::uint32_t index, std::uint32_t value) {
  SetCsr(kMacCsrData, value);
  SetCsr(kMacCsrCmd, kMacCsrBusy | index);
  WaitWhile(kMacCsrCmd, kMacCsrBusy, kMacCsrBusy);
}

std::uint32_t Lan9118FramePort::ReadPhy(std::uint32_t index) const {
  SetCsr(kMacCsrData, kInternalPhy << kMiiPhyShift | index << kMiiRegisterShift | kMiiBusy);
  SetCsr(kMacCsrCmd, kMacCsrBusy | kMacMiiAcc);
  WaitWhile(kMacCsrCmd, kMacCsrBusy, kMacCsrBusy);
  for (unsigned spin = 0; spin < kBusySpins && (ReadMac(kMacMiiAcc) & kMiiBusy) != 0; ++spin) {
  }
  return ReadMac(kMacMiiData) & 0xFFFFU;
}

void Lan9118FramePort::WritePhy(std::uint32_t index, std::uint32_t value) {
  SetCsr(kMacCsrData, value & 0xFFFFU);
  SetCsr(kMacCsrCmd, kMacCsrBusy | kMacMiiData);
  WaitWhile(kMacCsrCmd, kMacCsrBusy, kMacCsrBusy);
  SetCsr(kMacCsrData, kInternalPhy << kMiiPhyShift | index << kMiiRegisterShift | kMiiWrite | kMiiBusy);
  SetCsr(kMacCsrCmd, kMacCsrBusy | kMacMiiAcc);
  WaitWhile(kMacCsrCmd, kMacCsrBusy, kMacCsrBusy);
  for (unsigned spin = 0; spin < kBusySpins && (ReadMac(kMacMiiAcc) & kMiiBusy) != 0; ++spin) {
  }
}

void Lan9118FramePort::UpdateLink() {
  const std::uint32_t control = ReadPhy(kPhyBasicControl);
  const std::uint32_t status = ReadPhy(kPhyBasicStatus);
  const std::uint32_t advertised = ReadPhy(kPhyAdvertisement);
  const std::uint32_t partner = ReadPhy(kPhyPartnerAbility);
  link_ = Resolve(control, status, advertised, partner);
  const std::uint32_t mac_cr = ReadMac(kMacCr);
  const std::uint32_t duplex = link_.full_duplex ? kMacCrFullDuplex : 0;
  if ((mac_cr & kMacCrFullDuplex) != duplex) WriteMac(kMacCr, (mac_cr & ~kMacCrFullDuplex) | duplex);
}

void Lan9118FramePort::ProgramMulticast() {
  const std::uint64_t table = filter_.HashTable();
  WriteMac(kMacHashH, static_cast<std::uint32_t>(table >> 32));
  WriteMac(kMacHashL, static_cast<std::uint32_t>(table));
  const std::uint32_t mac_cr = ReadMac(kMacCr);
  const std::uint32_t pass_all = filter_.PassAll() ? kMacCrPassAllMulticast : 0;
  if ((mac_cr & kMacCrPassAllMulticast) != pass_all) WriteMac(kMacCr, (mac_cr & ~kMacCrPassAllMulticast) | pass_all);
}

bool Lan9118FramePort::OnInterrupt() {
  const std::uint32_t pending = Csr(kIntSts) & Csr(kIntEn);
  SetCsr(kIntSts, pending);
  if ((pending & kIntRxError) != 0) irq_rx_errors_.fetch_add(1, std::memory_order_relaxed);
  if ((pending & kIntTxError) != 0) irq_tx_errors_.fetch_add(1, std::memory_order_relaxed);
  // Frames the chip dropped for want of FIFO space (the counter clears when read).
  if ((pending & kIntRxDropped) != 0) irq_rx_errors_.fetch_add(Csr(kRxDrop), std::memory_order_relaxed);
  if ((pending & kIntPhy) != 0) {
    static_cast<void>(ReadPhy(kPhyInterruptSource));  // reading clears the PHY's sources
    UpdateLink();
  }
  return (pending & (kIntRxStatusLevel | kIntPhy)) != 0;
}

LinkState Lan9118FramePort::Link(PortId port) const {
  if (port != PortId::kLeft || !started_) return LinkState{};
  CriticalSection masked;
  return link_;
}

PortCounters Lan9118FramePort::Counters(PortId port) const {
  if (port != PortId::kLeft) return PortCounters{};
  PortCounters counters = counters_;
  counters.rx_errors += irq_rx_errors_.load(std::memory_order_relaxed);
  counters.tx_errors += irq_tx_errors_.load(std::memory_order_relaxed);
  return counters;
}

void Lan9118FramePort::CollectTransmitStatus() {
  std::uint32_t waiting = (Csr(kTxFifoInf) >> 16) & 0xFFU;
  while (waiting-- > 0) {
    const std::uint32_t status = Csr(kTxStatusFifo);
    if ((status & kTxStatusErrorSummary) != 0) {
      ++counters_.tx_errors;
    } else {
      ++counters_.tx_frames;
      counters_.tx_octets += status >> 16;  // the tag: the frame's length
    }
  }
}

void Lan9118FramePort::DiscardWords(std::size_t words) {
  while (words-- > 0) static_cast<void>(Csr(kRxDataFifo));
}

base::Result<ReceivedFrame> Lan9118FramePort::Receive(std::span<std::uint8_t> buffer) {
  if (!started_) return base::Unavailable();
  CollectTransmitStatus();
  if (((Csr(kRxFifoInf) >> 16) & 0xFFU) == 0) return base::Unavailable();
  const std::uint32_t status = Csr(kRxStatusFifo);
  // The length includes the 4 FCS bytes; the data FIFO holds it in whole words.
  const std::size_t stored = (status >> kRxStatusLengthShift) & kRxStatusLengthMask;
  const std::size_t words = (stored + 3) / 4;
  if ((status & (kRxStatusErrorSummary | kRxStatusFilterFail)) != 0 || stored < kMinFrameBytes + 4) {
    DiscardWords(words);
    ++counters_.rx_errors;
    return base::DataLoss();
  }
  const std::size_t length = stored - 4;
  if (length > kMaxFrameBytes || length > buffer.size()) {
    DiscardWords(words);
    ++counters_.rx_errors;
    return base::OutOfRange();
  }
  std::size_t copied = 0;
  for (std::size_t word = 0; word < words; ++word) {
    const std::uint32_t data = Csr(kRxDataFifo);
    for (unsigned byte = 0; byte < 4 && copied < length; ++byte) {
      buffer[copied++] = static_cast<std::uint8_t>(data >> (8 * byte));
    }
  }
  ++counters_.rx_frames;
  counters_.rx_octets += length;
  return ReceivedFrame{length, PortId::kLeft};
}

base::Status Lan9118FramePort::Transmit(PortId port, std::span<const std::uint8_t> frame) {
  if (port != PortId::kLeft) return base::NotFound();
  if (frame.size() < kMinFrameBytes || frame.size() > kMaxFrameBytes) return base::InvalidArgument();
  if (!started_ || !Link(port).up) {
    ++counters_.tx_errors;
    return base::FailedPrecondition();
  }
  CollectTransmitStatus();
  const std::size_t words = (frame.size() + 3) / 4;
  if ((Csr(kTxFifoInf) & 0xFFFFU) < (words + 2) * 4) {
    ++counters_.tx_errors;
    return base::ResourceExhausted();
  }
  const auto length = static_cast<std::uint32_t>(frame.size());
  SetCsr(kTxDataFifo, kTxCmdAFirstSegment | kTxCmdALastSegment | length);
  SetCsr(kTxDataFifo, length << 16 | length);  // command B: tag (= length) and packet length
  for (std::size_t word = 0; word < words; ++word) {
    std::uint32_t data = 0;
    for (std::size_t byte = 0; byte < 4; ++byte) {
      const std::size_t at = word * 4 + byte;
      if (at < frame.size()) data |= static_cast<std::uint32_t>(frame[at]) << (8 * byte);
    }
    SetCsr(kTxDataFifo, data);
  }
  return base::OkStatus();
}

base::Status Lan9118FramePort::JoinMulticast(const base::MacAddress& group) {
  CriticalSection masked;
  filter_.Join(group);
  if (started_) ProgramMulticast();
  return base::OkStatus();
}

base::Status Lan9118FramePort::LeaveMulticast(const base::MacAddress& group) {
  CriticalSection masked;
  if (base::Status left = filter_.Leave(group); !left.ok()) return left;
  if (started_) ProgramMulticast();
  return base::OkStatus();
}

}  // namespace hal::mps2
