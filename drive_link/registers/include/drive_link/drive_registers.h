// The inverter registers the card itself acts on: communication numbers, the FA06 command bits and the
// FD01 status bits of VF-MB1/VF-S15 (seed 000 §3.1, §3.2.4; seed 003 §8-§9). Shared by the card's layers
// (drive link, front ends) and by the simulated inverter, so both sides agree on one definition.
// This header only names things; the rules live with their users.
#pragma once

#include <cstdint>

namespace drive_link::reg {

// --- Parameters the card reads or writes ---
inline constexpr std::uint16_t kCmod = 0x0003;  // command mode: 4 = communication option
inline constexpr std::uint16_t kFmod = 0x0004;  // frequency mode: 7 = communication option
inline constexpr std::uint16_t kAcc = 0x0009;
inline constexpr std::uint16_t kDec = 0x0010;
inline constexpr std::uint16_t kUl = 0x0012;
inline constexpr std::uint16_t kVb = 0x0016;
inline constexpr std::uint16_t kF207 = 0x0207;  // frequency mode 2 (chosen by input function FCHG)
inline constexpr std::uint16_t kVlv = 0x0409;
inline constexpr std::uint16_t kF601 = 0x0601;
inline constexpr std::uint16_t kF856 = 0x0856;  // motor pole pairs
inline constexpr std::uint16_t kF880 = 0x0880;  // free notes
inline constexpr std::uint16_t kF899 = 0x0899;  // communication function reset: 1 = reset option and drive

// --- c-parameters: the card's configuration, stored in the inverter (PAR-1..PAR-5) ---
inline constexpr std::uint16_t kC001 = 0xC001;  // c001-c006 scanner input (command) word menus
inline constexpr std::uint16_t kC021 = 0xC021;  // c021-c026 scanner output (monitor) word menus
inline constexpr std::uint16_t kC041 = 0xC041;  // c041-c046 scanner command values (written by the card)
inline constexpr std::uint16_t kC061 = 0xC061;  // c061-c066 scanner monitor values (written by the card)
inline constexpr std::uint16_t kC081 = 0xC081;  // c081-c096 device name, one ASCII character each
inline constexpr std::uint16_t kC100 = 0xC100;  // loss detection delay, 0.1 s
inline constexpr std::uint16_t kC101 = 0xC101;  // loss action 0-5
inline constexpr std::uint16_t kC102 = 0xC102;  // preset speed for c101 = 5
inline constexpr std::uint16_t kC103 = 0xC103;  // loss condition 0-2
inline constexpr std::uint16_t kC500 = 0xC500;  // protocol: 0 Modbus TCP, 1 EtherNet/IP
inline constexpr std::uint16_t kC501 = 0xC501;  // rate setting
inline constexpr std::uint16_t kC502 = 0xC502;  // actual rate L port (written by the card)
inline constexpr std::uint16_t kC503 = 0xC503;  // actual rate R port (written by the card)
inline constexpr std::uint16_t kC504 = 0xC504;  // IP mode: 0 manual, 1 BOOTP, 2 DHCP
inline constexpr std::uint16_t kC505 = 0xC505;  // c505-c508 IP, c509-c512 mask, c513-c516 gateway
inline constexpr std::uint16_t kC517 = 0xC517;  // c517-c522 MAC (written by the card)
inline constexpr std::uint16_t kC523 = 0xC523;  // network timeout, 0.1 s (0 = disabled)
inline constexpr std::uint16_t kC524 = 0xC524;  // c524-c535 actual IP/mask/gateway (written by the card)
inline constexpr std::uint16_t kC536 = 0xC536;  // Ethernet error (written by the card)
inline constexpr std::uint16_t kC554 = 0xC554;  // web server enable
inline constexpr std::uint16_t kC555 = 0xC555;  // drive status: 3 gate block, 4 run, 23 fault (card)
inline constexpr std::uint16_t kC600 = 0xC600;  // c600-c603 Modbus IO scanning master address
inline constexpr std::uint16_t kC604 = 0xC604;  // IO scanning active

// --- Command registers (RAM only) ---
inline constexpr std::uint16_t kFa00 = 0xFA00;  // RS485 command word (same bits as FA06)
inline constexpr std::uint16_t kFa01 = 0xFA01;  // RS485 frequency command
inline constexpr std::uint16_t kFa06 = 0xFA06;  // option command word 1
inline constexpr std::uint16_t kFa07 = 0xFA07;  // option frequency command, 0.01 Hz
inline constexpr std::uint16_t kFa23 = 0xFA23;  // option command word 2
inline constexpr std::uint16_t kFa50 = 0xFA50;  // terminal output data
inline constexpr std::uint16_t kFa51 = 0xFA51;  // FM analog output data
// Option unit fault request: the option connector's fault line, carried on the serial drive link as a
// write of this number (docs/drive-link.md "Loss actions"). Writing kErr8TripCode trips the inverter
// with err8; 0 does nothing. Not in the Toshiba manuals: a contract between the card and the simulator.
inline constexpr std::uint16_t kFa30 = 0xFA30;

// --- Monitors ---
inline constexpr std::uint16_t kFb05 = 0xFB05;  // inverter model (capacity) code
inline constexpr std::uint16_t kFe08 = 0xFE08;  // CPU1 version
inline constexpr std::uint16_t kFc90 = 0xFC90;  // trip code in force
inline constexpr std::uint16_t kFc91 = 0xFC91;  // alarm bits
inline constexpr std::uint16_t kFd00 = 0xFD00;  // output frequency, 0.01 Hz
inline constexpr std::uint16_t kFd01 = 0xFD01;  // status word 1
inline constexpr std::uint16_t kFe02 = 0xFE02;  // frequency command in force, 0.01 Hz (held at a trip)
inline constexpr std::uint16_t kFe14 = 0xFE14;  // cumulative run time, hours

// Trip codes (FC90) the card causes or reports.
inline constexpr std::uint16_t kErr8TripCode = 27;   // 0x1B network error stop
inline constexpr std::uint16_t kE23TripCode = 55;    // 0x37 option fault

// FA06 (and FA00) bits, seed 000 §3.2.4.2.
namespace command_bit {
inline constexpr std::uint16_t kPresetMask = 0x000F;
inline constexpr std::uint16_t kThr2 = 1u << 4;
inline constexpr std::uint16_t kPidOff = 1u << 5;
inline constexpr std::uint16_t kAd2 = 1u << 6;
inline constexpr std::uint16_t kDcBraking = 1u << 7;
inline constexpr std::uint16_t kJog = 1u << 8;
inline constexpr std::uint16_t kReverse = 1u << 9;
inline constexpr std::uint16_t kRun = 1u << 10;
inline constexpr std::uint16_t kCoastStop = 1u << 11;
inline constexpr std::uint16_t kEmergencyStop = 1u << 12;
inline constexpr std::uint16_t kFaultReset = 1u << 13;
inline constexpr std::uint16_t kFrequencyPriority = 1u << 14;
inline constexpr std::uint16_t kCommandPriority = 1u << 15;
}  // namespace command_bit

// An FA06 word that does not run the drive: neither run (bit 10) nor jog (bit 8). With command priority
// (bit 15) the option stops it; without, cmod/fmod decide (what c101 = 0 writes, seed 000 §3.2.3).
constexpr bool IsStopCommand(std::uint16_t fa06) {
  return (fa06 & (command_bit::kRun | command_bit::kJog)) == 0;
}

// FD01 bits, seed 000 §3.2.4.7.
namespace status_bit {
inline constexpr std::uint16_t kFailureFl = 1u << 0;
inline constexpr std::uint16_t kTripped = 1u << 1;
inline constexpr std::uint16_t kAlarm = 1u << 2;
inline constexpr std::uint16_t kRunning = 1u << 10;
inline constexpr std::uint16_t kStOff = 1u << 11;
inline constexpr std::uint16_t kEmergencyStopped = 1u << 12;
inline constexpr std::uint16_t kReadyStRun = 1u << 13;
inline constexpr std::uint16_t kReady = 1u << 14;
}  // namespace status_bit

// Communication numbers whose last hex digit is A-F do not exist on VF-MB1/S15 (seed 000 §8.9 (5)):
// titles count in decimal, so 0009 (acc) is followed by 0010 (dec).
constexpr bool HasDecimalLastDigit(std::uint16_t number) { return (number & 0x000F) <= 9; }

// The communication number of the c-parameter titled cNNN: titles count in decimal and the number
// shows the title's digits (c096 -> 0xC096, c510 -> 0xC510; seed 000 §3.1).
constexpr std::uint16_t CParameter(unsigned title) {
  return static_cast<std::uint16_t>(0xC000 | ((title / 100 % 10) << 8) | ((title / 10 % 10) << 4) | (title % 10));
}

// FCxx-FExx: monitors, read-only by nature. The card refuses writes to them without asking the inverter.
constexpr bool IsMonitorNumber(std::uint16_t number) { return number >= 0xFC00 && number <= 0xFEFF; }

// Control registers (docs/security.md "Control registers"): writing one commands the drive (the
// communication command area FA00-FAFF: run, direction, frequency, outputs), chooses where its commands
// come from (cmod, fmod, f207) or resets the option and the drive (f899). While a master holds the drive
// (a Modbus IO scanning master c600-c603, an EtherNet/IP exclusive owner), the front ends refuse writes
// to these from anybody else.
constexpr bool IsControlRegister(std::uint16_t number) {
  return (number >= 0xFA00 && number <= 0xFAFF) || number == kCmod || number == kFmod || number == kF207 ||
         number == kF899;
}

}  // namespace drive_link::reg
