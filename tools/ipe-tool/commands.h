// The subcommands of tools/ipe. Each returns its exit code (failure.h) or throws a Failure.
#pragma once

#include <memory>
#include <string>

#include "cli.h"
#include "drive_access.h"
#include "eip_client.h"
#include "parameter_table.h"

namespace ipe {

int RunDiscover(const Options& options);
int RunIdentity(const Options& options);
int RunGet(const Options& options);
int RunSet(const Options& options);
int RunWatch(const Options& options);
int RunBackup(const Options& options);
int RunRestore(const Options& options);
int RunIo(const Options& options);
int RunEds(const Options& options);

// A card reached for parameter access, its model known (EtherNet/IP: Identity product code; Modbus:
// Read Device Identification's product name).
struct Card {
  std::string host;
  Model model = Model::kVfMb1;
  std::string product;
  std::unique_ptr<EipSession> eip;        // EtherNet/IP only
  std::unique_ptr<DriveAccess> access;
};
Card ConnectCard(const Options& options, const std::string& host);

// The model of an Identity product code (cip/identity_object.h: 32000 VF-MB1, 32001 VF-S15).
std::optional<Model> ModelFromProductCode(std::uint16_t product_code);

// SIGINT/SIGTERM end watch and io cleanly: the handler only sets a flag the loops poll.
void InstallInterruptHandler();
bool Interrupted();

}  // namespace ipe
