// Reaching a card for parameter access, and the interrupt flag of the long-running commands.
#include <csignal>

#include "cip/cip_status.h"
#include "cip/identity_object.h"
#include "commands.h"
#include "failure.h"

namespace ipe {
namespace {

volatile std::sig_atomic_t interrupted = 0;

void OnInterrupt(int) { interrupted = 1; }

}  // namespace

std::optional<Model> ModelFromProductCode(std::uint16_t product_code) {
  if (product_code == cip::kProductCodeVfMb1) return Model::kVfMb1;
  if (product_code == cip::kProductCodeVfS15) return Model::kVfS15;
  return std::nullopt;
}

Card ConnectCard(const Options& options, const std::string& host) {
  Card card;
  card.host = host;
  const int timeout = static_cast<int>(options.timeout_ms);
  if (options.modbus) {
    auto access = std::make_unique<ModbusDriveAccess>(host, DefaultPort(options), options.unit, timeout);
    card.product = access->ProductName();
    const std::optional<Model> model = ModelFromName(card.product);
    if (!model) Fail(kExitRefused, host + ": the card names no VF-MB1/VF-S15 drive (product name '" + card.product + "')");
    card.model = *model;
    card.access = std::move(access);
    return card;
  }
  try {
    card.eip = std::make_unique<EipSession>(host, DefaultPort(options), timeout);
  } catch (const Failure& failure) {
    // A card on Modbus TCP (c500 = 0) has its EtherNet/IP port closed: say so.
    if (failure.code != kExitUnreachable || failure.message.find("Connection refused") == std::string::npos) throw;
    Fail(failure.code, failure.message + " (is the card on EtherNet/IP, c500 = 1? --modbus reaches a Modbus card)");
  }
  const CipReply reply = card.eip->Request(cip::kServiceGetAttributesAll, {cip::kClassIdentity, 1, std::nullopt});
  if (!reply.ok()) Fail(kExitRefused, host + ": Identity refused: " + FormatCipStatus(reply));
  const std::optional<cip::IdentityItem> identity = DecodeIdentityAttributes(reply.data);
  if (!identity) Fail(kExitUnreachable, host + ": the Identity reply does not decode");
  const std::optional<Model> model = ModelFromProductCode(identity->product_code);
  if (!model) Fail(kExitRefused, host + ": product code " + std::to_string(identity->product_code) + " is no VF-MB1/VF-S15 card");
  card.model = *model;
  card.product = ProductNameOf(*identity);
  card.access = std::make_unique<EipDriveAccess>(*card.eip);
  return card;
}

void InstallInterruptHandler() {
  struct sigaction action {};
  action.sa_handler = OnInterrupt;
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

bool Interrupted() { return interrupted != 0; }

}  // namespace ipe
