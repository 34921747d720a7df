// CIP vocabulary shared by the message router and the objects: general status codes, the extended
// codes the card sends, service codes, class codes, and ServiceStatus, what a service handler returns.
#pragma once

#include <cstdint>

namespace cip {

// General status of a message router reply (CIP Vol. 1 Appendix B). Only codes the card sends, or that
// tests and the documentation name, are listed.
enum class GeneralStatus : std::uint8_t {
  kSuccess = 0x00,
  kConnectionFailure = 0x01,       // Unconnected_Send routing errors carry an extended code
  kResourceUnavailable = 0x02,     // nesting of Multiple Service Packet / Unconnected_Send too deep
  kPathSegmentError = 0x04,        // path not understood (unknown segment type, bad syntax, truncated)
  kPathDestinationUnknown = 0x05,  // no such class (or member)
  kServiceNotSupported = 0x08,
  kInvalidAttributeValue = 0x09,
  kObjectStateConflict = 0x0C,     // TCP/IP attr 5 set while the startup configuration is not "stored"
  kAttributeNotSettable = 0x0E,
  kDeviceStateConflict = 0x10,     // an assembly owned by an I/O connection refused an explicit write
  kReplyDataTooLarge = 0x11,
  kNotEnoughData = 0x13,
  kAttributeNotSupported = 0x14,
  kTooMuchData = 0x15,
  kObjectDoesNotExist = 0x16,      // no such instance
  kStoreOperationFailure = 0x19,   // the inverter or the card's store refused a setting
  kEmbeddedServiceError = 0x1E,    // Multiple Service Packet: at least one member failed
  kInvalidParameter = 0x20,        // a request parameter (not an attribute value) is invalid
};

// Extended status words of General Status 0x01 for Unconnected_Send routing.
inline constexpr std::uint16_t kExtendedInvalidRoutePort = 0x0311;
inline constexpr std::uint16_t kExtendedInvalidRouteNode = 0x0312;
inline constexpr std::uint16_t kExtendedInvalidRouteSegment = 0x0315;

// Service codes.
inline constexpr std::uint8_t kServiceGetAttributesAll = 0x01;
inline constexpr std::uint8_t kServiceGetAttributeList = 0x03;
inline constexpr std::uint8_t kServiceReset = 0x05;
inline constexpr std::uint8_t kServiceMultipleServicePacket = 0x0A;
inline constexpr std::uint8_t kServiceGetAttributeSingle = 0x0E;
inline constexpr std::uint8_t kServiceSetAttributeSingle = 0x10;
inline constexpr std::uint8_t kServiceGetAndClear = 0x4C;
inline constexpr std::uint8_t kServiceForwardClose = 0x4E;
inline constexpr std::uint8_t kServiceUnconnectedSend = 0x52;
inline constexpr std::uint8_t kServiceForwardOpen = 0x54;
inline constexpr std::uint8_t kReplyServiceBit = 0x80;

// Class codes of the objects in chapter 4 of the manual.
inline constexpr std::uint16_t kClassIdentity = 0x01;
inline constexpr std::uint16_t kClassMessageRouter = 0x02;
inline constexpr std::uint16_t kClassAssembly = 0x04;
inline constexpr std::uint16_t kClassConnectionManager = 0x06;
inline constexpr std::uint16_t kClassPort = 0xF4;
inline constexpr std::uint16_t kClassTcpIpInterface = 0xF5;
inline constexpr std::uint16_t kClassEthernetLink = 0xF6;

// The outcome of one service: a general status, at most one extended status word (all the card ever
// sends), and whether the reply data written so far is kept. An error reply carries no data, except the
// member replies of a Multiple Service Packet that answers 0x1E.
struct ServiceStatus {
  GeneralStatus general = GeneralStatus::kSuccess;
  bool has_extended = false;
  std::uint16_t extended = 0;
  bool keep_reply_data = false;
  // With keep_reply_data and no has_extended: the reply data begins with this many additional status
  // words the service wrote itself (a refused Forward_Open: the extended status and, for some codes,
  // the acceptable value), followed by its error reply data.
  std::uint8_t additional_words_in_data = 0;

  constexpr bool ok() const { return general == GeneralStatus::kSuccess; }
  constexpr bool operator==(const ServiceStatus&) const = default;
};

constexpr ServiceStatus Success() { return ServiceStatus{}; }
constexpr ServiceStatus Error(GeneralStatus general) { return ServiceStatus{general, false, 0, false}; }
constexpr ServiceStatus ErrorWithExtended(GeneralStatus general, std::uint16_t extended) {
  return ServiceStatus{general, true, extended, false};
}

}  // namespace cip
