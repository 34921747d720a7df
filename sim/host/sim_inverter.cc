#include "sim_inverter.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "atomic_file.h"
#include "base/crc32.h"

namespace sim {
namespace {

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

// "check <crc>" for `image`, without the line end.
std::string CheckLineFor(std::string_view image) {
  const std::uint32_t crc = base::Crc32(std::span(reinterpret_cast<const std::uint8_t*>(image.data()), image.size()));
  char line[32];
  std::snprintf(line, sizeof line, "check %08x", static_cast<unsigned>(crc));
  return line;
}

// Why the file was refused, in words: a failed check, or another model's image.
std::string RefusalReason(const std::string& file, Model model) {
  const std::optional<std::string_view> image = EepromImageOf(file);
  if (!image) return "its check line is missing or does not match (cut short, damaged, or from an older version)";
  std::istringstream lines{std::string(*image)};
  std::string line;
  while (std::getline(lines, line)) {
    if (line.rfind("model ", 0) == 0 && line.substr(6) != ModelName(model)) {
      return "it holds a " + line.substr(6) + " image, not " + ModelName(model);
    }
  }
  return "it is not a valid EEPROM image";
}

// Replaces the file atomically (hal/host/atomic_file.h); `cut` is the tests' power cut.
bool StoreFile(const std::string& path, const std::string& contents, std::string& error,
               const std::optional<hal::host::PowerCut>& cut) {
  const std::filesystem::path file(path);
  const std::string directory = file.parent_path().string();
  const int dir_fd = open(directory.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dir_fd < 0) {
    error = directory + ": " + std::strerror(errno);
    return false;
  }
  const base::Status stored = hal::host::ReplaceFileAtomically(
      dir_fd, file.filename().string(),
      std::span(reinterpret_cast<const std::uint8_t*>(contents.data()), contents.size()), &error, cut);
  close(dir_fd);
  if (!stored.ok() && error.empty()) error = "power cut (test)";
  return stored.ok();
}

}  // namespace

std::string EepromFileContents(std::string_view image) {
  std::string file(image);
  file += CheckLineFor(image);
  file += '\n';
  return file;
}

std::optional<std::string_view> EepromImageOf(std::string_view file) {
  if (file.empty() || file.back() != '\n') return std::nullopt;
  const std::size_t previous_end = file.size() < 2 ? std::string_view::npos : file.rfind('\n', file.size() - 2);
  const std::size_t last_line = previous_end == std::string_view::npos ? 0 : previous_end + 1;
  const std::string_view image = file.substr(0, last_line);
  if (file.substr(last_line, file.size() - 1 - last_line) != CheckLineFor(image)) return std::nullopt;
  return image;
}

SimulatedInverter::SimulatedInverter(const SimInverterConfig& config, hal::SerialPort& line,
                                     const hal::Clock& clock, std::FILE* log)
    : clock_(clock),
      log_(log),
      program_(config.program),
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

  // A save the last run did not finish (a power cut, a kill) left a temp file; the live file is whole.
  if (const int dir_fd = open(config.directory.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC); dir_fd >= 0) {
    hal::host::RemoveTempFiles(dir_fd, config.directory, std::filesystem::path(self.path_).filename().string());
    close(dir_fd);
  }
  std::string text;
  const FileState state = ReadFile(self.path_, text);
  const std::optional<std::string_view> image =
      state == FileState::kRead ? EepromImageOf(text) : std::optional<std::string_view>();
  if (image && self.model_.LoadEeprom(*image)) {
    self.saved_image_ = std::string(*image);  // rewritten only when something changes
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
      const RegisterInfo* info = FindRegister(preset.number, config.model);
      const WriteResult result =
          info == nullptr ? WriteResult{WriteOutcome::kNoSuchRegister, false}
                          : self.model_.Write(preset.number, info->ToWord(preset.value),
                                              WriteTarget::kRamAndEeprom);
      if (!result.ok()) {
        error = "--param " + preset.text + ": refused by the inverter (" +
                WriteOutcomeName(result.outcome) + ")";
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
    const std::optional<hal::host::PowerCut> cut = power_cut_;
    power_cut_.reset();
    if (!StoreFile(path_, EepromFileContents(image), error, cut)) {
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
  std::fprintf(log_, "%s%swarning: %s\n", program_.c_str(), program_.empty() ? "" : ": ", text.c_str());
  std::fflush(log_);
}

}  // namespace sim
