#include "logging_leds.h"

#include <utility>

namespace hal::host {

LoggingLeds::LoggingLeds(const Clock& clock, LineSink sink) : clock_(clock), sink_(std::move(sink)) {
  current_.fill(LedColor::kOff);
}

LoggingLeds::LineSink LoggingLeds::FileSink(std::FILE* file) {
  if (file == nullptr) return LineSink();
  return [file](std::string_view line) {
    std::fwrite(line.data(), 1, line.size(), file);
    std::fputc('\n', file);
    std::fflush(file);
  };
}

void LoggingLeds::Set(Led led, LedColor color) {
  if (LedIndex(led) >= kLedCount || current_[LedIndex(led)] == color) return;
  current_[LedIndex(led)] = color;
  const LedChange change{.at = clock_.NowMicros(), .led = led, .color = color};
  if (history_.size() == kHistoryCapacity) history_.pop_front();
  history_.push_back(change);
  if (sink_) {
    sink_(std::string("led ") + LedName(led) + " " + LedColorName(color) +
          " t=" + std::to_string(change.at));
  }
}

std::string LoggingLeds::Describe() const {
  std::string text;
  for (std::size_t i = 0; i < kLedCount; ++i) {
    if (i != 0) text += ' ';
    text += LedName(static_cast<Led>(i));
    text += '=';
    text += LedColorName(current_[i]);
  }
  return text;
}

}  // namespace hal::host
