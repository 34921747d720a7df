#include "host_random.h"

#include <sys/random.h>

#include <cerrno>
#include <cstdlib>

namespace hal::host {

void HostRandom::Fill(std::span<std::uint8_t> out) {
  std::size_t done = 0;
  while (done < out.size()) {
    const ssize_t n = getrandom(out.data() + done, out.size() - done, 0);
    if (n < 0) {
      if (errno == EINTR) continue;
      std::abort();  // no entropy source on a Linux >= 3.17 host is not a state we can run in
    }
    done += static_cast<std::size_t>(n);
  }
}

}  // namespace hal::host
