// Connection Manager wire formats (CIP Vol. 1 §3-5.5): Forward_Open 0x54, Large_Forward_Open 0x5B and
// Forward_Close 0x4E request data, their replies, and the connection path of a Forward_Open.
//
//   Forward_Open request data (Large_Forward_Open: the two network connection parameters are 32-bit):
//     0  priority/time tick          1  timeout ticks
//     2  O->T connection ID (4)      6  T->O connection ID (4)
//    10  connection serial (2)      12  originator vendor ID (2)     14  originator serial (4)
//    18  timeout multiplier         19  reserved (3)
//    22  O->T RPI µs (4)            26  O->T network connection parameters (2 | 4)
//        T->O RPI µs (4)                T->O network connection parameters (2 | 4)
//        transport class/trigger        connection path size (words)     connection path
//   success reply data: O->T ID, T->O ID, serial, vendor, originator serial, O->T API, T->O API,
//     application reply size (words) = 0, reserved
//   failure reply data: serial, vendor, originator serial, remaining path size, reserved; the
//     additional status is the extended status, followed for some codes by the acceptable value
//   Forward_Close request data: priority/tick, timeout ticks, serial, vendor, originator serial, path
//     size (words), reserved, path; success reply: the triad, application reply size 0, reserved;
//     failure reply: the triad, remaining path size, reserved
//
// Network connection parameters: 16-bit = redundant owner bit 15, type bits 14-13 (0 null, 1
// multicast, 2 point-to-point), priority bits 11-10, variable bit 9, size bits 8-0 (bytes); 32-bit =
// the same fields at bits 31, 30-29, 27-26, 25 and a 16-bit size in bits 15-0.
// Transport class/trigger: bit 7 direction (1 server), bits 6-4 production trigger (0 cyclic, 1 change
// of state, 2 application object), bits 3-0 transport class.
//
// Every decoder reads through base::ByteReader / EpathReader and never reads outside the request.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>

#include "base/byte_reader.h"
#include "base/byte_writer.h"
#include "cip/cip_status.h"
#include "cip/epath.h"

namespace cip {

inline constexpr std::uint8_t kServiceLargeForwardOpen = 0x5B;

// Extended status codes of General Status 0x01 the connection manager sends (0x0311, 0x0312 and 0x0315
// are in cip_status.h).
inline constexpr std::uint16_t kExtendedDuplicateForwardOpen = 0x0100;
inline constexpr std::uint16_t kExtendedTransportTrigger = 0x0103;
inline constexpr std::uint16_t kExtendedOwnershipConflict = 0x0106;
inline constexpr std::uint16_t kExtendedConnectionNotFound = 0x0107;
inline constexpr std::uint16_t kExtendedRpiNotSupported = 0x0111;
inline constexpr std::uint16_t kExtendedRpiNotAcceptable = 0x0112;
inline constexpr std::uint16_t kExtendedOutOfConnections = 0x0113;
inline constexpr std::uint16_t kExtendedVendorOrProductCode = 0x0114;
inline constexpr std::uint16_t kExtendedDeviceType = 0x0115;
inline constexpr std::uint16_t kExtendedRevision = 0x0116;
inline constexpr std::uint16_t kExtendedNoNonListenOnly = 0x0119;
inline constexpr std::uint16_t kExtendedTargetOutOfConnections = 0x011A;
inline constexpr std::uint16_t kExtendedOtoTConnectionType = 0x0123;
inline constexpr std::uint16_t kExtendedTtoOConnectionType = 0x0124;
inline constexpr std::uint16_t kExtendedRedundantOwner = 0x0125;
inline constexpr std::uint16_t kExtendedConfigurationSize = 0x0126;
inline constexpr std::uint16_t kExtendedOtoTSize = 0x0127;
inline constexpr std::uint16_t kExtendedTtoOSize = 0x0128;
inline constexpr std::uint16_t kExtendedConfigurationPath = 0x0129;
inline constexpr std::uint16_t kExtendedConsumingPath = 0x012A;
inline constexpr std::uint16_t kExtendedProducingPath = 0x012B;
inline constexpr std::uint16_t kExtendedInconsistentPaths = 0x012F;
inline constexpr std::uint16_t kExtendedNullForwardOpen = 0x0132;
inline constexpr std::uint16_t kExtendedTimeoutMultiplier = 0x0133;

enum class ConnectionType : std::uint8_t { kNull = 0, kMulticast = 1, kPointToPoint = 2, kReserved = 3 };
enum class ConnectionPriority : std::uint8_t { kLow = 0, kHigh = 1, kScheduled = 2, kUrgent = 3 };

struct NetworkConnectionParameters {
  std::uint16_t size = 0;  // bytes, as the originator counts them (class 1: with sequence and header)
  bool variable = false;
  ConnectionPriority priority = ConnectionPriority::kLow;
  ConnectionType type = ConnectionType::kNull;
  bool redundant_owner = false;

  constexpr bool operator==(const NetworkConnectionParameters&) const = default;
};
NetworkConnectionParameters DecodeNetworkParameters16(std::uint16_t word);
NetworkConnectionParameters DecodeNetworkParameters32(std::uint32_t word);
std::uint16_t EncodeNetworkParameters16(const NetworkConnectionParameters& parameters);  // size cut to 9 bits
std::uint32_t EncodeNetworkParameters32(const NetworkConnectionParameters& parameters);

inline constexpr std::uint8_t kTriggerCyclic = 0;
inline constexpr std::uint8_t kTriggerChangeOfState = 1;
inline constexpr std::uint8_t kTriggerApplicationObject = 2;

struct TransportClassTrigger {
  bool server = false;               // bit 7
  std::uint8_t trigger = 0;          // bits 6-4
  std::uint8_t transport_class = 0;  // bits 3-0

  constexpr bool operator==(const TransportClassTrigger&) const = default;
};
TransportClassTrigger DecodeTransportClassTrigger(std::uint8_t byte);
std::uint8_t EncodeTransportClassTrigger(const TransportClassTrigger& transport);

// What identifies a connection to its originator (and a duplicate Forward_Open).
struct ConnectionTriad {
  std::uint16_t connection_serial = 0;
  std::uint16_t originator_vendor = 0;
  std::uint32_t originator_serial = 0;

  constexpr bool operator==(const ConnectionTriad&) const = default;
};

struct ForwardOpenRequest {
  bool large = false;  // Large_Forward_Open: 32-bit network connection parameters
  std::uint8_t priority_tick = 0;
  std::uint8_t timeout_ticks = 0;
  std::uint32_t o_to_t_connection_id = 0;
  std::uint32_t t_to_o_connection_id = 0;
  ConnectionTriad triad;
  std::uint8_t timeout_multiplier = 0;
  std::uint32_t o_to_t_rpi = 0;  // µs
  NetworkConnectionParameters o_to_t;
  std::uint32_t t_to_o_rpi = 0;  // µs
  NetworkConnectionParameters t_to_o;
  TransportClassTrigger transport;
  std::span<const std::uint8_t> connection_path;  // padded EPATH
};

struct ForwardCloseRequest {
  std::uint8_t priority_tick = 0;
  std::uint8_t timeout_ticks = 0;
  ConnectionTriad triad;
  std::span<const std::uint8_t> connection_path;
};

// How a request's framing went. Only kOk requests are acted on; kFixedPartShort has no triad to echo
// (answered 0x13 without reply data), kPathShort (0x13) and kExtraData (0x15) have one.
enum class RequestFraming : std::uint8_t { kOk, kFixedPartShort, kPathShort, kExtraData };

inline constexpr std::size_t kForwardOpenFixedSize = 36;  // up to and including the path size
inline constexpr std::size_t kLargeForwardOpenFixedSize = 40;
inline constexpr std::size_t kForwardCloseFixedSize = 12;

template <typename Request>
struct Decoded {
  RequestFraming framing = RequestFraming::kFixedPartShort;
  Request request;
};
Decoded<ForwardOpenRequest> DecodeForwardOpen(std::span<const std::uint8_t> data, bool large);
Decoded<ForwardCloseRequest> DecodeForwardClose(std::span<const std::uint8_t> data);
// Request encoders (tests, fuzz seeds and the documentation's examples).
void EncodeForwardOpen(const ForwardOpenRequest& request, base::ByteWriter& out);
void EncodeForwardClose(const ForwardCloseRequest& request, base::ByteWriter& out);

// ---- Connection path ------------------------------------------------------------------------------

// A connection path as the card understands it (docs/connections.md "Connection path"):
//   [port 1 / link 0 segments] [electronic key] class [instance] [connection point] [connection point]
//   [simple data segment]
// The class segment may be repeated with the same value before each application path. The first
// instance segment names the configuration (class 2: the Message Router instance); the following
// instance or connection point segments name the connection points in the order consumed (O->T), then
// produced (T->O) - at most two.
struct ConnectionPath {
  std::optional<ElectronicKey> key;
  std::uint32_t class_id = 0;
  std::optional<std::uint32_t> instance;  // the first instance segment
  std::array<std::uint32_t, 2> points{};
  std::size_t point_count = 0;
  bool has_data = false;
  std::span<const std::uint8_t> data;  // the simple data segment's bytes (configuration data)
};

struct ParsedConnectionPath {
  std::uint16_t extended = 0;  // 0, or 0x0311 / 0x0312 (a route elsewhere) / 0x0315 (anything else)
  ConnectionPath path;
};
ParsedConnectionPath ParseConnectionPath(std::span<const std::uint8_t> padded_path);

// The identity an electronic key is compared with.
struct DeviceKey {
  std::uint16_t vendor_id = 0;
  std::uint16_t device_type = 0;
  std::uint16_t product_code = 0;
  std::uint8_t major_revision = 0;
  std::uint8_t minor_revision = 0;
};
// 0 when the key matches, else 0x0114 (vendor or product code), 0x0115 (device type) or 0x0116
// (revision). Zero fields match anything. Without the compatibility bit the major revision must match
// (0 matches anything) and the minor must match or be 0; with it, the major must match and the minor
// be 1..the device's minor.
std::uint16_t CheckElectronicKey(const ElectronicKey& key, const DeviceKey& device);

// ---- Replies ---------------------------------------------------------------------------------------

// RPI types of the additional status after 0x0111 / 0x0112.
inline constexpr std::uint8_t kRpiAcceptable = 0;
inline constexpr std::uint8_t kRpiMinimumAcceptable = 2;
inline constexpr std::uint8_t kRpiMaximumAcceptable = 3;
inline constexpr std::uint8_t kRpiRequiredForMismatch = 4;

// A refused Forward_Open / Forward_Close. The additional status is `extended` followed by `extra`
// words: none, the right size (0x0126, 0x0127, 0x0128), or for 0x0111 / 0x0112 the acceptable RPIs
// (O->T type, T->O type as one word, then the O->T and T->O RPI in µs as two words each).
struct ConnectionFailure {
  GeneralStatus general = GeneralStatus::kConnectionFailure;
  std::uint16_t extended = 0;  // 0: no additional status at all (0x13, 0x15)
  std::array<std::uint16_t, 5> extra{};
  std::uint8_t extra_count = 0;
  std::uint8_t remaining_path_words = 0;

  static ConnectionFailure Extended(std::uint16_t extended);
  static ConnectionFailure WithSize(std::uint16_t extended, std::uint16_t size);
  static ConnectionFailure WithRpi(std::uint16_t extended, std::uint8_t o_to_t_type, std::uint32_t o_to_t_rpi,
                                   std::uint8_t t_to_o_type, std::uint32_t t_to_o_rpi);
  static ConnectionFailure General(GeneralStatus general);
  constexpr bool operator==(const ConnectionFailure&) const = default;
};

// Writes the reply data of a refused request into `reply` (the message router's reply, after its
// 4-byte header): the additional status words, then the triad, remaining path size and reserved byte.
// The returned status tells the router that the data begins with those words.
ServiceStatus EncodeConnectionFailure(const ConnectionFailure& failure, const ConnectionTriad& triad,
                                      base::ByteWriter& reply);

struct ForwardOpenSuccess {
  std::uint32_t o_to_t_connection_id = 0;
  std::uint32_t t_to_o_connection_id = 0;
  ConnectionTriad triad;
  std::uint32_t o_to_t_api = 0;  // µs
  std::uint32_t t_to_o_api = 0;
};
void EncodeForwardOpenSuccess(const ForwardOpenSuccess& success, base::ByteWriter& reply);
void EncodeForwardCloseSuccess(const ConnectionTriad& triad, base::ByteWriter& reply);

}  // namespace cip
