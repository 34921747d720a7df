// Codecs of the I/O assemblies of seed 000 §5 (docs/drive-profile.md has every bit map):
//
//   output (O->T, consumed)                  input (T->O, produced)
//   20  CIP basic speed control      4 B     70  CIP basic speed control      4 B
//   21  CIP extended speed control   4 B     71  CIP extended speed control   4 B
//   100 native drive (FA06, FA07, c001-c006)  150 native drive (FD01, FD00, c021-c026)
//         4-16 B, even                              4-16 B, even
//   101 speed control + parameter    8 B     151 speed status + parameter     8 B
//   102 scanner words c001-c006     12 B     152 scanner words c021-c026     12 B
//   105 parameter + c001-c006       18 B     155 parameter + c021-c026       18 B
//
// Sizes. Every instance has one size except 100/150 ("2 to 8 words"): there the size is what the
// connection asks for, i.e. the O->T (100) or T->O (150) connection size of the Forward_Open, less the
// 32-bit run/idle header when the O->T format has one. A Logix Generic Ethernet Module sends exactly the
// sizes typed in its dialog, so a 100/150 connection of 2..8 INTs is accepted at that size: words 1-2
// are FA06/FA07 (FD01/FD00), words 3..n the first n-2 scanner words. Explicit messages see the largest
// size (16 bytes). An odd size, or one outside the instance's range, is refused (IsValidSize false; the
// Connection Manager answers 0x0127 / 0x0128, invalid O->T / T->O size).
//
// Words are little-endian (low byte first), like everything in CIP. Bits that §5 marks "-" are ignored
// when decoding and sent as 0.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "cip/drive/drive_profile.h"

namespace cip::drive {

inline constexpr std::uint16_t kBasicSpeedOutput = 20;
inline constexpr std::uint16_t kExtendedSpeedOutput = 21;
inline constexpr std::uint16_t kNativeOutput = 100;
inline constexpr std::uint16_t kNativeParameterOutput = 101;
inline constexpr std::uint16_t kScannerOutput = 102;
inline constexpr std::uint16_t kToshibaOutput = 105;
inline constexpr std::uint16_t kBasicSpeedInput = 70;
inline constexpr std::uint16_t kExtendedSpeedInput = 71;
inline constexpr std::uint16_t kNativeInput = 150;
inline constexpr std::uint16_t kNativeParameterInput = 151;
inline constexpr std::uint16_t kScannerInput = 152;
inline constexpr std::uint16_t kToshibaInput = 155;

inline constexpr std::array<std::uint16_t, 6> kOutputInstances{20, 21, 100, 101, 102, 105};
inline constexpr std::array<std::uint16_t, 6> kInputInstances{70, 71, 150, 151, 152, 155};

// Connection points beyond §5 (docs/drive-profile.md "Connection points"), all of size 0:
inline constexpr std::uint16_t kConfigurationInstance = 1;     // a Generic Ethernet Module's config path
inline constexpr std::uint16_t kListenOnlyHeartbeat = 198;     // O->T point of a listen-only connection
inline constexpr std::uint16_t kInputOnlyHeartbeat = 199;      // O->T point of an input-only connection

// The largest assembly (105/155), for buffers.
inline constexpr std::size_t kMaxAssemblySize = 18;

bool IsOutputInstance(std::uint32_t instance);
bool IsInputInstance(std::uint32_t instance);
// Whether `bytes` is a size the instance can be exchanged at (connections and explicit writes).
bool IsValidSize(std::uint32_t instance, std::size_t bytes);
// The size of attribute 4 and of explicit access: the largest valid size. 0 for other instances.
std::size_t AssemblySize(std::uint32_t instance);
// The input instance §5 pairs with an output instance (20 -> 70 ... 105 -> 155), 0 for others. A
// connection may pair any output with any input; this is the documented pair.
std::uint16_t PairedInput(std::uint32_t output_instance);

// Decodes a consumed output assembly. False (and `command` untouched) for an instance that is not an
// output or a size IsValidSize refuses.
bool DecodeOutput(std::uint32_t instance, std::span<const std::uint8_t> data, DriveCommand& command);

// Encodes a produced input assembly into all of `out` (out.size() must be a valid size). False (and
// nothing written) for an instance that is not an input or an invalid size.
bool EncodeInput(std::uint32_t instance, const DriveFeedback& feedback, std::span<std::uint8_t> out);

}  // namespace cip::drive
