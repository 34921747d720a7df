// The register proxy's configuration load: the card's c-parameters (config::kConfigNumbers), then the
// block read selections F875-F879, then FD01, one R each; validated into the configuration in force
// (docs/drive-link.md, "Configuration at start-up and reset"). It knows which number comes next and
// what the reads mean, not the link: the scheduler sends its reads and hands back their completions.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "config/card_config.h"
#include "drive_link/own_job.h"
#include "drive_link/register_access.h"

namespace drive_link {

// F875-F879: the block read selections (seed 003 §4).
inline constexpr std::size_t kBlockReadSelections = 5;

// The configuration load reads kConfigNumbers, then F875-F879, then FD01.
inline constexpr std::size_t kConfigLoadReads = config::kConfigNumberCount + kBlockReadSelections + 1;

class ConfigLoader {
 public:
  // Starts a load from its first number; the configuration in force stays until the load ends.
  void Begin();
  // e-23 cut the load: it starts again from the beginning when the link is back (Begin).
  void Abandon() { loading_ = false; }

  // The next read of a load in progress; false when none is due.
  bool NextRead(OwnJob& job) const;
  // The completion of the read NextRead gave. True when it was the last one: the load has ended and the
  // configuration in force is the new one.
  bool OnRead(std::uint8_t index, const Completion& completion);

  bool loading() const { return loading_; }
  bool loaded() const { return loaded_; }
  // The configuration in force: factory defaults until the first load.
  const config::CardConfig& config() const { return parsed_.config; }
  const config::ParsedConfig& parsed() const { return parsed_; }
  // F875-F879 as read at the last load (0 where unread or out of range).
  const std::array<std::uint16_t, kBlockReadSelections>& block_selections() const { return block_selections_; }
  // FD01 as read at the end of the last load.
  const AccessResult& drive_status_read() const { return reads_[kConfigLoadReads - 1]; }

 private:
  void Finish();

  bool loaded_ = false;
  bool loading_ = false;
  std::uint8_t index_ = 0;
  std::array<AccessResult, kConfigLoadReads> reads_{};
  config::ParsedConfig parsed_{};
  std::array<std::uint16_t, kBlockReadSelections> block_selections_{};
};

}  // namespace drive_link
