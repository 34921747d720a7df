// The simulated inverter as a process runs it: the behaviour model, its Toshiba-protocol server on the
// inverter end of the serial line, and its EEPROM image kept in the state dir, so the drive keeps its
// parameters across runs and restarts like a real one. ipe002z-host runs one in-process on a socket pair
// (docs/simulator.md "In ipe002z-host"); ipe002z-inverter runs one on its own, on a listening socket
// (docs/simulator.md "ipe002z-inverter").
//
// The EEPROM file is `<state dir>/inverter/<model>.eeprom` (vf-mb1.eeprom, vf-s15.eeprom): the model's
// text image (InverterModel::SerializeEeprom) followed by one line `check <crc>`, the CRC-32 of every
// byte before that line in 8 lowercase hex digits. One file per model, so one state dir can stand for a
// card that was moved between a VF-MB1 and a VF-S15; --model picks the drive. A file whose check line
// is missing or wrong (cut short, damaged, written before the check line existed) is not used: it is
// moved aside and the inverter starts from its factory defaults, never from part of an image
// (docs/robustness.md "Power loss").
//
// When it is stored (always whole, atomically: hal/host/atomic_file.h, temp file, fsync, rename, fsync
// of the directory):
// - at start, when the inverter is new (no usable file): defaults plus the --param presets;
// - within kSaveCheckInterval of a change of a register value, a write counter or the trip history;
// - when only the cumulative counters moved (run and powered time, energy): at most every
//   kCounterSaveInterval, so an idle card does not write every second;
// - at exit and before a restart (power-cycle), whatever changed.
#pragma once

#include <cstdint>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "atomic_file.h"
#include "hal/clock.h"
#include "hal/serial_port.h"
#include "inverter_options.h"
#include "poll_waiter.h"
#include "sim/inverter_model.h"
#include "sim/protocol_server.h"

namespace sim {

struct SimInverterConfig {
  Model model = Model::kVfMb1;
  std::string directory;             // where the EEPROM file lives: <state dir>/inverter
  std::vector<ParamPreset> presets;  // applied to a new inverter only
  ServerConfig server;
  std::string program;               // who warns: "ipe002z-host: warning: ..."
};

// The file for an image (the image and its check line), and the image in a file whose check line is
// there and matches (nothing otherwise).
std::string EepromFileContents(std::string_view image);
std::optional<std::string_view> EepromImageOf(std::string_view file);

class SimulatedInverter final {
 public:
  static constexpr hal::Micros kSaveCheckInterval = hal::kMicrosPerSecond;
  static constexpr hal::Micros kCounterSaveInterval = 60 * hal::kMicrosPerSecond;

  // Loads the model's EEPROM file, or starts a new inverter: table defaults, then the presets written
  // as W (RAM and EEPROM) in order, then the image is stored at once. A file that cannot be used
  // (unreadable, malformed, another model's image) is renamed to `<file>.bad` and a new inverter
  // starts, with a warning on `log`. A state dir that cannot be written gives a warning, not a failure
  // (the drive then forgets on exit). Null with `error` only when a preset is refused by the model.
  static std::unique_ptr<SimulatedInverter> Create(const SimInverterConfig& config, hal::SerialPort& line,
                                                   const hal::Clock& clock, std::FILE* log,
                                                   std::string& error);

  SimulatedInverter(const SimulatedInverter&) = delete;
  SimulatedInverter& operator=(const SimulatedInverter&) = delete;

  InverterModel& model() { return model_; }
  InverterProtocolServer& server() { return server_; }
  const InverterProtocolServer& server() const { return server_; }
  // Register with the PollWaiter (the server's timers); the line's own PollSource (SocketSerialPort,
  // ListeningSerialPort) wakes it on bytes.
  hal::host::PollSource& poll_source() { return poll_source_; }
  const hal::Clock& clock() const { return clock_; }

  // Moves the model's time to the clock's now; every control command starts with it.
  void AdvanceToNow() { model_.Advance(clock_.NowMicros()); }

  // The store check, run like a service of an event loop (the host card adds it to the card's loop):
  // every kSaveCheckInterval, moves the model's time and stores the image when due.
  void Poll(hal::Micros now);
  hal::Micros NextDeadline() const { return next_check_; }

  // Power off and on (InverterModel::PowerCycle: RAM-only registers back to defaults, trips cleared),
  // then stores the image.
  void PowerCycle();
  // Moves the model's time to now and stores the image when it differs from the stored one; false
  // (with a warning on the log, once per run of failures) when the file cannot be written.
  bool SaveIfChanged();

  const std::string& file_path() const { return path_; }
  bool started_new() const { return started_new_; }  // no usable file was found: presets applied
  std::uint64_t saves() const { return saves_; }     // images written, for tests
  // Test hook, one shot: the next store loses power at `cut` (hal::host::PowerCut) and fails; the
  // inverter must not be used afterwards. A test then creates a new one on the same directory.
  void CutPowerDuringNextSaveForTest(const hal::host::PowerCut& cut) { power_cut_ = cut; }

 private:
  SimulatedInverter(const SimInverterConfig& config, hal::SerialPort& line, const hal::Clock& clock,
                    std::FILE* log);
  void Warn(const std::string& text);

  const hal::Clock& clock_;
  std::FILE* log_;
  std::string program_;
  std::string path_;
  InverterModel model_;
  InverterProtocolServer server_;
  ProtocolServerPollSource poll_source_{server_};

  bool started_new_ = false;
  std::string saved_image_;  // what the file holds (empty: nothing stored yet)
  std::uint64_t saved_generation_ = 0;
  hal::Micros saved_at_ = 0;
  hal::Micros next_check_ = 0;
  bool save_failing_ = false;  // warn once per run of failures, not every second
  std::uint64_t saves_ = 0;
  std::optional<hal::host::PowerCut> power_cut_;
};

}  // namespace sim
