// Reading and writing one drive register by communication number, over EtherNet/IP (the card's
// Parameter objects, docs/drive-objects.md) or Modbus TCP (units 0-248 address the inverter by
// communication number, docs/modbus.md). The commands above do not care which.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "eip_client.h"
#include "socket_io.h"

namespace ipe {

struct AccessResult {
  bool ok = false;
  std::uint16_t word = 0;  // the value read (or written)
  std::string refusal;     // !ok: the card's status ("general status 0x0E (...)", "Modbus exception 02 (...)")
};

class DriveAccess {
 public:
  virtual ~DriveAccess() = default;
  virtual AccessResult Read(std::uint16_t number) = 0;
  virtual AccessResult Write(std::uint16_t number, std::uint16_t word) = 0;
};

class EipDriveAccess final : public DriveAccess {
 public:
  explicit EipDriveAccess(EipSession& session) : session_(session) {}
  AccessResult Read(std::uint16_t number) override;
  AccessResult Write(std::uint16_t number, std::uint16_t word) override;

 private:
  EipSession& session_;
};

class ModbusDriveAccess final : public DriveAccess {
 public:
  ModbusDriveAccess(const std::string& host, std::uint16_t port, std::uint8_t unit, int timeout_ms);
  AccessResult Read(std::uint16_t number) override;
  AccessResult Write(std::uint16_t number, std::uint16_t word) override;
  // The drive's product name (Read Device Identification object 04), "" when the card has none yet.
  std::string ProductName();

 private:
  std::vector<std::uint8_t> Exchange(const std::vector<std::uint8_t>& request);

  TcpConnection tcp_;
  std::uint8_t unit_;
  std::uint16_t transaction_ = 0;
};

}  // namespace ipe
