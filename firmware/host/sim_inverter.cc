#include "sim_inverter.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace host {
namespace {

using hal::host::sim::InverterModel;
using hal::host::sim::ModelName;

std::string ErrnoText(const std::string& what) { return what + ": " + std::strerror(errno); }

bool WriteAll(int fd, const std::string& text) {
  std::size_t done = 0;
  while (done < text.size()) {
    const ssize_t n = write(fd, text.data() + done, text.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    done += static_cast<std::size_t>(n);
  }
  return true;
}

// Temp file, fsync, rename over the live file, fsync of the directory: a cut at any moment leaves the
// old image or the new one, never a mix (as FileNvStore does for the card's records).
bool WriteFileAtomically(const std::string& path, const std::string& text, std::string& error) {
  const std::string temp = path + ".tmp";
  const int fd = open(temp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) {
    error = ErrnoText(temp);
    return false;
  }
  const bool written = WriteAll(fd, text) && fsync(fd) == 0;
  if (!written) error = ErrnoText(temp);
  close(fd);
  if (!written) return false;
  if (std::rename(temp.c_str(), path.c_str()) != 0) {
    error = ErrnoText(path);
    return false;
  }
  const std::string directory = std::filesystem::path(path).parent_path().string();
  const int dir_fd = open(directory.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dir_fd < 0 || fsync(dir_fd) != 0) {
    error = ErrnoText(directory);
    if (dir_fd >= 0) close(dir_fd);
    return false;
  }
  close(dir_fd);
  return true;
}

enum class FileState { kMissing, kRead, kUnreadable };

FileState ReadFile(const std::string& path, std::string& text) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) return ec ? FileState::kUnreadable : FileState::kMissing;
  std::ifstream in(path, std::ios::binary);
  if (!in) return FileState::kUnreadable;
  std::ostringstream content;
  content << in.rdbuf();
  if (in.bad()) return FileState::kUnreadable;
  text = content.str();
  return FileState::kRead;
}

// Why LoadEeprom refused `text`, in words: the one case worth naming is another model's image.
std::string RefusalReason(const std::string& text, hal::host::sim::Model model) {
  std::istringstream lines(text);
  std::string line;
  while (std::getline(lines, line)) {
    if (line.rfind("model ", 0) == 0 && line.substr(6) != ModelName(model)) {
      return "it holds a " + line.substr(6) + " image, not " + ModelName(model);
    }
  }
  return "it is not a valid EEPROM image";
}

}  // namespace

hal::host::sim::ServerConfig ServerConfigFromOptions(const HostOptions& options) {
  hal::host::sim::ServerConfig config =
      options.rs485_profile ? hal::host::sim::Rs485Profile() : hal::host::sim::ServerConfig{};
  if (options.sim_processing_ms >= 0) {
    config.processing_delay = static_cast<hal::Micros>(options.sim_processing_ms) * hal::kMicrosPerMilli;
  }
  return config;
}

SimulatedInverter::SimulatedInverter(const SimInverterConfig& config, hal::SerialPort& line,
                                     const hal::Clock& clock, std::FILE* log)
    : clock_(clock),
      log_(log),
      path_(config.directory + "/" + ModelName(config.model) + ".eeprom"),
      model_(config.model),
      server_(model_, line, clock, config.server) {}

std::unique_ptr<SimulatedInverter> SimulatedInverter::Create(const SimInverterConfig& config,
                                                             hal::SerialPort& line, const hal::Clock& clock,
                                                             std::FILE* log, std::string& error) {
  std::unique_ptr<SimulatedInverter> inverter(new SimulatedInverter(config, line, clock, log));
  SimulatedInverter& self = *inverter;
  std::error_code ec;
  std::filesystem::create_directories(config.directory, ec);  // a failure shows when storing

  std::string text;
  const FileState state = ReadFile(self.path_, text);
  if (state == FileState::kRead && self.model_.LoadEeprom(text)) {
    self.saved_image_ = text;  // stored as it is; rewritten only when something changes
  } else {
    if (state != FileState::kMissing) {
      const std::string reason = state == FileState::kUnreadable ? std::string("it cannot be read")
                                                                 : RefusalReason(text, config.model);
      const std::string aside = self.path_ + ".bad";
      const bool moved = std::rename(self.path_.c_str(), aside.c_str()) == 0;
      self.Warn(self.path_ + " is not usable (" + reason + ")" + (moved ? "; moved to " + aside : "") +
                "; the inverter starts from its factory defaults");
    }
    self.started_new_ = true;
    for (const ParamPreset& preset : config.presets) {
      const hal::host::sim::RegisterInfo* info = hal::host::sim::FindRegister(preset.number, config.model);
      const hal::host::sim::WriteResult result =
          info == nullptr ? hal::host::sim::WriteResult{hal::host::sim::WriteOutcome::kNoSuchRegister, false}
                          : self.model_.Write(preset.number, info->ToWord(preset.value),
                                              hal::host::sim::WriteTarget::kRamAndEeprom);
      if (!result.ok()) {
        error = "--param " + preset.text + ": refused by the inverter (" +
                hal::host::sim::WriteOutcomeName(result.outcome) + ")";
        return nullptr;
      }
    }
    self.SaveIfChanged();
  }
  self.saved_generation_ = self.model_.eeprom_generation();
  self.saved_at_ = clock.NowMicros();
  self.next_check_ = self.saved_at_ + kSaveCheckInterval;
  return inverter;
}

void SimulatedInverter::Poll(hal::Micros now) {
  if (now < next_check_) return;
  // Keep the base time (docs/architecture.md); after a long stall, skip the checks that were missed.
  while (next_check_ <= now) next_check_ += kSaveCheckInterval;
  model_.Advance(now);
  if (model_.eeprom_generation() != saved_generation_ || now - saved_at_ >= kCounterSaveInterval) {
    SaveIfChanged();
  }
}

void SimulatedInverter::PowerCycle() {
  AdvanceToNow();  // the drive was on until now
  model_.PowerCycle();
  SaveIfChanged();
}

bool SimulatedInverter::SaveIfChanged() {
  AdvanceToNow();  // the image as of now: hours and energy up to this moment
  const std::string image = model_.SerializeEeprom();
  const std::uint64_t generation = model_.eeprom_generation();
  const hal::Micros now = clock_.NowMicros();
  if (image != saved_image_) {
    std::string error;
    if (!WriteFileAtomically(path_, image, error)) {
      if (!save_failing_) Warn("cannot store the inverter's EEPROM (" + error + "); retrying");
      save_failing_ = true;
      return false;
    }
    save_failing_ = false;
    saved_image_ = image;
    ++saves_;
  }
  saved_generation_ = generation;
  saved_at_ = now;
  return true;
}

void SimulatedInverter::Warn(const std::string& text) {
  if (log_ == nullptr) return;
  std::fprintf(log_, "ipe002z-host: warning: %s\n", text.c_str());
  std::fflush(log_);
}

}  // namespace host
