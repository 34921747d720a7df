#include "stderr_console.h"

#include <cstdio>
#include <cstdlib>

namespace hal::host {

void StderrConsole::Write(std::string_view text) { std::fwrite(text.data(), 1, text.size(), stderr); }

void StderrConsole::Fatal(std::string_view message) {
  std::fwrite(message.data(), 1, message.size(), stderr);
  std::fputc('\n', stderr);
  std::abort();
}

}  // namespace hal::host
