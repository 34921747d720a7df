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
    TextLine line;
    DescribeLedChange(led, color, change.at, line);
    sink_(line.view());
  }
}

std::string LoggingLeds::Describe() const {
  TextLine line;
  DescribeLeds(current_, line);
  return std::string(line.view());
}

}  // namespace hal::host
