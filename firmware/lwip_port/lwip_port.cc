#include "lwip_port.h"

#include <cstdarg>
#include <cstdio>
#include <cstdlib>

#include "lwip/arch.h"
#include "lwip/sys.h"

namespace firmware {
namespace {

// The only file-scope state of the firmware: lwIP's C callbacks have no context pointer.
const hal::Clock* g_clock = nullptr;
hal::RandomSource* g_random = nullptr;

}  // namespace

void BindLwipPlatform(const hal::Clock& clock, hal::RandomSource& random) {
  g_clock = &clock;
  g_random = &random;
}

}  // namespace firmware

extern "C" {

u32_t sys_now(void) {
  // lwIP compares times with wrap-around arithmetic, so truncating to 32 bits is what it expects.
  return static_cast<u32_t>(firmware::g_clock->NowMicros() / hal::kMicrosPerMilli);
}

u32_t ipe_lwip_rand(void) { return firmware::g_random->NextU32(); }

void ipe_lwip_diag(const char* format, ...) {
  va_list args;
  va_start(args, format);
  std::vfprintf(stderr, format, args);
  va_end(args);
}

void ipe_lwip_assert(const char* message, const char* file, int line) {
  std::fprintf(stderr, "lwIP assertion \"%s\" failed at %s:%d\n", message, file, line);
  std::abort();
}

}  // extern "C"
