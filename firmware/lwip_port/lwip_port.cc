#include "lwip_port.h"

#include <array>
#include <cstdarg>
#include <span>

#include "diag_format.h"
#include "hal/text_line.h"
#include "lwip/arch.h"
#include "lwip/sys.h"

namespace firmware {
namespace {

// The only file-scope state of the firmware: lwIP's C callbacks have no context pointer.
const hal::Clock* g_clock = nullptr;
hal::RandomSource* g_random = nullptr;
hal::ConsoleOutput* g_diagnostics = nullptr;
hal::FatalHandler* g_fatal = nullptr;

// lwIP's diagnostics are single lines; a longer one is cut here.
constexpr std::size_t kDiagnosticBytes = 160;

}  // namespace

void BindLwipPlatform(const hal::Clock& clock, hal::RandomSource& random, hal::ConsoleOutput& diagnostics,
                      hal::FatalHandler& fatal) {
  g_clock = &clock;
  g_random = &random;
  g_diagnostics = &diagnostics;
  g_fatal = &fatal;
}

}  // namespace firmware

extern "C" {

u32_t sys_now(void) {
  // lwIP compares times with wrap-around arithmetic, so truncating to 32 bits is what it expects.
  return static_cast<u32_t>(firmware::g_clock->NowMicros() / hal::kMicrosPerMilli);
}

u32_t ipe_lwip_rand(void) { return firmware::g_random->NextU32(); }

void ipe_lwip_diag(const char* format, ...) {
  std::array<char, firmware::kDiagnosticBytes> text;
  va_list args;
  va_start(args, format);
  const std::size_t length = firmware::FormatDiagnostic(text, format, args);
  va_end(args);
  firmware::g_diagnostics->Write(std::string_view(text.data(), length));
}

void ipe_lwip_assert(const char* message, const char* file, int line) {
  hal::TextLine text;
  text.Text("lwIP assertion \"").Text(message).Text("\" failed at ").Text(file).Text(":");
  text.Unsigned(static_cast<std::uint64_t>(line < 0 ? 0 : line));
  firmware::g_fatal->Fatal(text.view());
  // Fatal() does not return ([[noreturn]]), but a call through the vtable does not tell the compiler so.
  __builtin_trap();
}

}  // extern "C"
