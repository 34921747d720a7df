// Registers of the SMSC LAN9118 family (LAN9118/LAN9218/LAN9220 datasheets; QEMU hw/net/lan9118.c):
// the system control and status registers (CSRs) on the bus, the MAC's registers behind MAC_CSR_CMD/
// MAC_CSR_DATA and the internal PHY's behind the MAC's MII_ACC/MII_DATA. 32-bit accesses only.
#pragma once

#include <cstdint>

namespace hal::mps2::lan9118 {

// System CSRs (offsets from the chip's base).
inline constexpr std::uintptr_t kRxDataFifo = 0x00;
inline constexpr std::uintptr_t kTxDataFifo = 0x20;
inline constexpr std::uintptr_t kRxStatusFifo = 0x40;
inline constexpr std::uintptr_t kTxStatusFifo = 0x48;
inline constexpr std::uintptr_t kIdRev = 0x50;
inline constexpr std::uintptr_t kIrqCfg = 0x54;
inline constexpr std::uintptr_t kIntSts = 0x58;
inline constexpr std::uintptr_t kIntEn = 0x5C;
inline constexpr std::uintptr_t kByteTest = 0x64;
inline constexpr std::uintptr_t kFifoInt = 0x68;
inline constexpr std::uintptr_t kRxCfg = 0x6C;
inline constexpr std::uintptr_t kTxCfg = 0x70;
inline constexpr std::uintptr_t kHwCfg = 0x74;
inline constexpr std::uintptr_t kRxFifoInf = 0x7C;
inline constexpr std::uintptr_t kTxFifoInf = 0x80;
inline constexpr std::uintptr_t kPmtCtrl = 0x84;
inline constexpr std::uintptr_t kFreeRun = 0x9C;
inline constexpr std::uintptr_t kRxDrop = 0xA0;
inline constexpr std::uintptr_t kMacCsrCmd = 0xA4;
inline constexpr std::uintptr_t kMacCsrData = 0xA8;
inline constexpr std::uintptr_t kAfcCfg = 0xAC;

inline constexpr std::uint32_t kByteTestValue = 0x87654321;

inline constexpr std::uint32_t kIrqCfgType = 1U << 0;      // push-pull
inline constexpr std::uint32_t kIrqCfgPolarity = 1U << 4;  // active high
inline constexpr std::uint32_t kIrqCfgEnable = 1U << 8;

// INT_STS / INT_EN
inline constexpr std::uint32_t kIntRxStatusLevel = 1U << 3;  // RSFL: RX status FIFO above its level
inline constexpr std::uint32_t kIntRxDropped = 1U << 6;      // RXDF: RX_DROP counter passed half way
inline constexpr std::uint32_t kIntTxError = 1U << 13;       // TXE
inline constexpr std::uint32_t kIntRxError = 1U << 14;       // RXE
inline constexpr std::uint32_t kIntPhy = 1U << 18;

inline constexpr std::uint32_t kHwCfgSoftReset = 1U << 0;
inline constexpr std::uint32_t kHwCfgTxFifo5K = 5U << 16;
inline constexpr std::uint32_t kHwCfgMustBeOne = 1U << 20;
inline constexpr std::uint32_t kPmtCtrlReady = 1U << 0;
inline constexpr std::uint32_t kTxCfgTxOn = 1U << 1;
// TX and RX status FIFO levels for their interrupts: TX data available 0x48 (the reset value), RX status
// level 0 (an interrupt for every received frame).
inline constexpr std::uint32_t kFifoIntLevels = 0x48000000;
// Automatic flow control thresholds (the datasheet's recommended value).
inline constexpr std::uint32_t kAfcCfgDefault = 0x006E3740;

inline constexpr std::uint32_t kMacCsrBusy = 1U << 31;
inline constexpr std::uint32_t kMacCsrRead = 1U << 30;

// RX status word
inline constexpr std::uint32_t kRxStatusFilterFail = 1U << 30;
inline constexpr std::uint32_t kRxStatusErrorSummary = 1U << 15;
inline constexpr unsigned kRxStatusLengthShift = 16;
inline constexpr std::uint32_t kRxStatusLengthMask = 0x3FFF;
// TX status word
inline constexpr std::uint32_t kTxStatusErrorSummary = 1U << 15;
// TX command A / B
inline constexpr std::uint32_t kTxCmdAFirstSegment = 1U << 13;
inline constexpr std::uint32_t kTxCmdALastSegment = 1U << 12;

// MAC registers (MAC_CSR_CMD index)
inline constexpr std::uint32_t kMacCr = 1;
inline constexpr std::uint32_t kMacAddrH = 2;
inline constexpr std::uint32_t kMacAddrL = 3;
inline constexpr std::uint32_t kMacHashH = 4;
inline constexpr std::uint32_t kMacHashL = 5;
inline constexpr std::uint32_t kMacMiiAcc = 6;
inline constexpr std::uint32_t kMacMiiData = 7;

inline constexpr std::uint32_t kMacCrRxEnable = 1U << 2;
inline constexpr std::uint32_t kMacCrTxEnable = 1U << 3;
inline constexpr std::uint32_t kMacCrHashPerfectFilter = 1U << 13;  // multicast by the hash table
inline constexpr std::uint32_t kMacCrPassAllMulticast = 1U << 19;
inline constexpr std::uint32_t kMacCrFullDuplex = 1U << 20;

inline constexpr std::uint32_t kMiiBusy = 1U << 0;
inline constexpr std::uint32_t kMiiWrite = 1U << 1;
inline constexpr unsigned kMiiRegisterShift = 6;
inline constexpr unsigned kMiiPhyShift = 11;
inline constexpr std::uint32_t kInternalPhy = 1;

// PHY registers (IEEE 802.3 clause 22, plus the chip's interrupt source and mask)
inline constexpr std::uint32_t kPhyBasicControl = 0;
inline constexpr std::uint32_t kPhyBasicStatus = 1;
inline constexpr std::uint32_t kPhyAdvertisement = 4;
inline constexpr std::uint32_t kPhyPartnerAbility = 5;
inline constexpr std::uint32_t kPhyInterruptSource = 29;
inline constexpr std::uint32_t kPhyInterruptMask = 30;

inline constexpr std::uint32_t kBcrReset = 1U << 15;
inline constexpr std::uint32_t kBcrSpeed100 = 1U << 13;
inline constexpr std::uint32_t kBcrAutoNegEnable = 1U << 12;
inline constexpr std::uint32_t kBcrRestartAutoNeg = 1U << 9;
inline constexpr std::uint32_t kBcrFullDuplex = 1U << 8;
inline constexpr std::uint32_t kBsrLinkUp = 1U << 2;
inline constexpr std::uint32_t kBsrAutoNegComplete = 1U << 5;
// Advertisement / partner ability: 100BASE-TX FD, 100BASE-TX, 10BASE-T FD, 10BASE-T, selector 802.3.
inline constexpr std::uint32_t kAbility100Full = 1U << 8;
inline constexpr std::uint32_t kAbility100Half = 1U << 7;
inline constexpr std::uint32_t kAbility10Full = 1U << 6;
inline constexpr std::uint32_t kAbility10Half = 1U << 5;
inline constexpr std::uint32_t kAdvertiseAll = kAbility100Full | kAbility100Half | kAbility10Full | kAbility10Half | 1U;
// PHY interrupts: energy on, auto-negotiation complete, link down.
inline constexpr std::uint32_t kPhyIntEnergyOn = 1U << 7;
inline constexpr std::uint32_t kPhyIntAutoNegComplete = 1U << 6;
inline constexpr std::uint32_t kPhyIntLinkDown = 1U << 4;

}  // namespace hal::mps2::lan9118
