// What the CIP objects need from the rest of the card, as small interfaces the firmware implements:
// identity data and device status, the TCP/IP configuration (live and stored), the two Ethernet ports,
// the stored QoS values and the number of open CIP connections. A reset request goes to
// hal::ResetControl directly.
//
// Stored settings take effect at the next reset, as every (*3) parameter of the manual (§3.1, §3.2.2):
// a Set_Attribute_Single stores, a Get of a setting reads the stored value back, and the live values
// (IP address in use, link state) come from the "active" accessors.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "base/status.h"
#include "cip/wire_types.h"

namespace cip {

// ---- Identity (§4.1) ------------------------------------------------------------------------------

enum class DriveModel : std::uint8_t { kVfMb1, kVfS15 };

// Identity status word bits 4-7 (§4.1 "Attribute 5 State Descriptions").
enum class ExtendedDeviceStatus : std::uint8_t {
  kSelfTestingOrUnknown = 0x0,
  kFirmwareUpdate = 0x1,
  kFaultedIoConnection = 0x2,
  kNoIoConnections = 0x3,
  kNonVolatileConfigurationBad = 0x4,
  kMajorFault = 0x5,
  kIoConnectionInRunMode = 0x6,
  kIoConnectionsIdle = 0x7,
};

struct DeviceStatus {
  bool configured = false;  // bit 2: the application differs from the out-of-box default
  ExtendedDeviceStatus extended = ExtendedDeviceStatus::kNoIoConnections;
  bool minor_recoverable_fault = false;    // bit 8
  bool minor_unrecoverable_fault = false;  // bit 9
  bool major_recoverable_fault = false;    // bit 10
  bool major_unrecoverable_fault = false;  // bit 11
};

class DeviceInfoProvider {
 public:
  virtual ~DeviceInfoProvider() = default;
  virtual base::MacAddress Mac() const = 0;
  // The inverter the card is plugged into (product code and name follow it).
  virtual DriveModel Model() const = 0;
  virtual DeviceStatus Status() const = 0;
};

// ---- TCP/IP Interface (§4.11, §3.2.2) ------------------------------------------------------------

// Configuration Control bits 0-3 (attribute 3); the same numbers as c504 (0 manual, 1 BOOTP, 2 DHCP).
enum class StartupConfiguration : std::uint8_t { kStored = 0, kBootp = 1, kDhcp = 2 };

inline constexpr std::size_t kMaxDomainName = 48;  // CIP limit of attribute 5's domain name
inline constexpr std::size_t kMaxHostName = 16;    // c081-c096: one character per parameter

// Attribute 5. Addresses are host-order integers (192.168.0.10 = 0xC0A8000A).
struct InterfaceConfiguration {
  std::uint32_t ip_address = 0;
  std::uint32_t network_mask = 0;
  std::uint32_t gateway = 0;
  std::uint32_t name_server = 0;
  std::uint32_t name_server_2 = 0;
  FixedString<kMaxDomainName> domain_name;

  bool operator==(const InterfaceConfiguration&) const = default;
};

// Attribute 9.
struct MulticastConfiguration {
  std::uint8_t allocation_control = 0;  // 0: default algorithm, 1: num_mcast from start_address
  std::uint16_t num_mcast = 0;
  std::uint32_t start_address = 0;

  bool operator==(const MulticastConfiguration&) const = default;
};

// Attribute 11.
struct AcdConflict {
  std::uint8_t acd_activity = 0;
  base::MacAddress remote_mac{};
  std::array<std::uint8_t, 28> arp_pdu{};
};

// Everything settable through the TCP/IP object; stored, effective after a reset.
struct TcpIpSettings {
  StartupConfiguration startup = StartupConfiguration::kStored;  // attr 3 -> c504
  InterfaceConfiguration static_configuration;                   // attr 5 -> c505-c516 (+ card store)
  FixedString<kMaxHostName> host_name;                           // attr 6 -> c081-c096
  std::uint8_t ttl = 1;                                          // attr 8 (card store)
  MulticastConfiguration multicast;                              // attr 9 (card store)
  bool select_acd = true;                                        // attr 10 (card store)

  bool operator==(const TcpIpSettings&) const = default;
};

class TcpIpProvider {
 public:
  virtual ~TcpIpProvider() = default;
  // The configuration the stack runs with now (c524-c535); its IP address is the one ListIdentity and
  // the Port object report.
  virtual InterfaceConfiguration ActiveConfiguration() const = 0;
  // Status bits 0-3 = 1: the active configuration is valid (an address was set or obtained).
  virtual bool ConfigurationValid() const = 0;
  // Status bit 6 and attribute 11 (address conflict detection, NET-4).
  virtual bool AddressConflictDetected() const = 0;
  virtual AcdConflict LastConflict() const = 0;
  virtual void ClearLastConflict() = 0;
  virtual TcpIpSettings StoredSettings() const = 0;
  // Stores all settings at once. kInvalidArgument: a value the store cannot hold (answered 0x09);
  // any other failure (the inverter unreachable, the store broken) is answered 0x19.
  virtual base::Status StoreSettings(const TcpIpSettings& settings) = 0;
};

// ---- Ethernet Link (§4.12) ------------------------------------------------------------------------

enum class LinkPort : std::uint8_t { kLeft = 0, kRight = 1 };  // instance 1 and 2

// Interface Flags bits 2-4.
enum class NegotiationStatus : std::uint8_t {
  kInProgress = 0,
  kFailed = 1,
  kFailedSpeedDetected = 2,
  kNegotiated = 3,
  kForced = 4,
};

struct LinkState {
  bool up = false;
  bool full_duplex = false;
  std::uint32_t speed_mbps = 0;  // 0 (no link), 10 or 100
  NegotiationStatus negotiation = NegotiationStatus::kInProgress;
  bool hardware_fault = false;
};

struct InterfaceCounters {
  std::uint32_t in_octets = 0;
  std::uint32_t in_ucast_packets = 0;
  std::uint32_t in_nucast_packets = 0;
  std::uint32_t in_discards = 0;
  std::uint32_t in_errors = 0;
  std::uint32_t in_unknown_protos = 0;
  std::uint32_t out_octets = 0;
  std::uint32_t out_ucast_packets = 0;
  std::uint32_t out_nucast_packets = 0;
  std::uint32_t out_discards = 0;
  std::uint32_t out_errors = 0;
};

struct MediaCounters {
  std::uint32_t alignment_errors = 0;
  std::uint32_t fcs_errors = 0;
  std::uint32_t single_collisions = 0;
  std::uint32_t multiple_collisions = 0;
  std::uint32_t sqe_test_errors = 0;
  std::uint32_t deferred_transmissions = 0;
  std::uint32_t late_collisions = 0;
  std::uint32_t excessive_collisions = 0;
  std::uint32_t mac_transmit_errors = 0;
  std::uint32_t carrier_sense_errors = 0;
  std::uint32_t frame_too_long = 0;
  std::uint32_t mac_receive_errors = 0;
};

// c501 rate setting, one for both ports (attribute 6 of either instance reads and writes it).
enum class LinkSetting : std::uint8_t { kAuto = 0, k10Full = 1, k10Half = 2, k100Full = 3, k100Half = 4 };

class EthernetLinkProvider {
 public:
  virtual ~EthernetLinkProvider() = default;
  virtual LinkState State(LinkPort port) const = 0;
  virtual InterfaceCounters Counters(LinkPort port) const = 0;
  virtual MediaCounters Media(LinkPort port) const = 0;
  virtual void ClearCounters(LinkPort port) = 0;
  virtual void ClearMedia(LinkPort port) = 0;
  virtual LinkSetting StoredSetting() const = 0;
  // kInvalidArgument -> 0x09, other failures -> 0x19, as TcpIpProvider::StoreSettings.
  virtual base::Status StoreSetting(LinkSetting setting) = 0;
};

// ---- QoS (CIP Vol. 2 §5-7) -------------------------------------------------------------------------

// The QoS object's instance attributes, in attribute order.
enum class QosAttribute : std::uint8_t {
  kTagEnable = 1,
  kDscpPtpEvent,
  kDscpPtpGeneral,
  kDscpUrgent,
  kDscpScheduled,
  kDscpHigh,
  kDscpLow,
  kDscpExplicit,
};
inline constexpr std::size_t kQosAttributes = 8;

// The values of attributes 1-8 (the defaults of the CIP specification).
struct QosSettings {
  std::array<std::uint8_t, kQosAttributes> values{0, 59, 47, 55, 47, 43, 31, 27};

  std::uint8_t operator[](QosAttribute attribute) const { return values[static_cast<std::size_t>(attribute) - 1]; }
  bool tag_enabled() const { return (*this)[QosAttribute::kTagEnable] != 0; }
  bool operator==(const QosSettings&) const = default;
};

class QosProvider {
 public:
  virtual ~QosProvider() = default;
  virtual QosSettings StoredQos() const = 0;
  // kInvalidArgument -> 0x09, other failures -> 0x19, as TcpIpProvider::StoreSettings.
  virtual base::Status StoreQos(const QosSettings& settings) = 0;
};

// ---- Message Router (§4.2) -------------------------------------------------------------------------

class ConnectionCountProvider {
 public:
  virtual ~ConnectionCountProvider() = default;
  // Message Router attribute 3: CIP connections currently open (class 1 and class 3).
  virtual std::uint16_t ActiveConnections() const = 0;
};

}  // namespace cip
