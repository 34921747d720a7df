// The class 1 data of `ipe io`: output assembly 21 (ODVA extended speed control) as the originator sends
// it, input assembly 71 as the card produces it (seed 000 §5, docs/drive-profile.md "Assemblies"), and
// the O->T datagram (run/idle header) around it. The card's own codec (cip/drive/assembly_codec.h)
// decodes 21 and encodes 71; these are the other directions. Pure functions.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace ipe {

struct SpeedCommand {
  bool run_forward = false;
  bool run_reverse = false;
  bool fault_reset = false;
  bool net_ctrl = false;
  bool net_ref = false;
  std::int16_t speed_rpm = 0;
};
// 4 bytes: byte 0 bit 0 Run Fwd, 1 Run Rev, 2 Fault Reset, 5 NetCtrl, 6 NetRef; byte 1 0; INT speed.
std::array<std::uint8_t, 4> EncodeAssembly21(const SpeedCommand& command);

struct SpeedStatus {
  bool faulted = false, warning = false, running_forward = false, running_reverse = false;
  bool ready = false, ctrl_from_net = false, ref_from_net = false, at_reference = false;
  std::uint8_t state = 0;  // Control Supervisor state (1 startup ... 7 fault stop)
  std::int16_t speed_rpm = 0;
};
// Exactly 4 bytes.
std::optional<SpeedStatus> DecodeAssembly71(std::span<const std::uint8_t> data);

// "running-fwd at-ref net-ctrl net-ref state=4 (enabled) speed=900 rpm (30.00 Hz)"; hz_centi computed
// by the caller from f856.
std::string FormatSpeedStatus(const SpeedStatus& status, std::uint16_t centi_hz);

// The O->T datagram: CPF sequenced address + connected data (CIP sequence count, 32-bit run/idle
// header, the assembly), with the card's own datagram codec (cip/io_connection.h).
std::vector<std::uint8_t> EncodeOutputDatagram(std::uint32_t connection_id, std::uint32_t encapsulation_sequence,
                                               std::uint16_t cip_sequence, bool run,
                                               std::span<const std::uint8_t> assembly);
// A T->O datagram of `connection_id`: the assembly after the CIP sequence count. Nothing otherwise.
std::optional<std::vector<std::uint8_t>> DecodeInputDatagram(std::span<const std::uint8_t> datagram,
                                                             std::uint32_t connection_id);

}  // namespace ipe
