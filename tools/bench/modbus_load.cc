// Modbus TCP load generator for tools/bench/modbus: N libmodbus clients, each on its own connection and
// thread, send one kind of request back to back for a fixed time, then the run prints transactions/s and
// the latency distribution. The same binary loads the card and the libmodbus reference server, so the
// figures compare servers, not clients.
//
// usage: ipe_bench_modbus_load --host ADDR --port N [--clients N] [--seconds S] [--mode io|drive]
//   io:    FC 23 on unit 255: write scanner words 0-6, read words 0-6 (IO scanning, seed 000 §9.2)
//   drive: FC 03 on unit 0: 10 registers from 0xFD00 (drive monitors; each costs drive-link round trips)
// Prints one line: "mode=io clients=N seconds=S transactions=T errors=E tps=X p50_us=A p99_us=B max_us=C".
// Bounded: stops after --seconds (at most 60) whatever happens; a failed connection ends that client.
#include <modbus/modbus.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <thread>
#include <vector>

namespace {

using Clock = std::chrono::steady_clock;

struct Options {
  std::string host = "127.0.0.1";
  int port = 502;
  int clients = 4;
  double seconds = 5;
  bool io = true;
};

struct ClientResult {
  std::vector<std::uint32_t> latencies_us;
  std::uint64_t errors = 0;
  std::string failure;
};

void RunClient(const Options& options, Clock::time_point end, ClientResult& result) {
  modbus_t* ctx = modbus_new_tcp(options.host.c_str(), options.port);
  if (ctx == nullptr) {
    result.failure = "modbus_new_tcp failed";
    return;
  }
  modbus_set_response_timeout(ctx, 2, 0);
  if (modbus_connect(ctx) != 0) {
    result.failure = std::string("connect: ") + modbus_strerror(errno);
    modbus_free(ctx);
    return;
  }
  modbus_set_slave(ctx, options.io ? 255 : 0);
  std::uint16_t out[7] = {0, 0xC400, 0x1770, 0, 0, 0, 0};
  std::uint16_t in[10] = {};
  std::uint16_t counter = 0;
  while (Clock::now() < end) {
    const Clock::time_point start = Clock::now();
    int rc;
    if (options.io) {
      out[2] = static_cast<std::uint16_t>(0x1770 - (counter++ & 0xFF));  // a changing frequency command
      rc = modbus_write_and_read_registers(ctx, 0, 7, out, 0, 7, in);
    } else {
      rc = modbus_read_registers(ctx, 0xFD00, 10, in);
    }
    const auto us = std::chrono::duration_cast<std::chrono::microseconds>(Clock::now() - start).count();
    if (rc < 0) {
      ++result.errors;
      if (errno == EBADF || errno == ECONNRESET || errno == EPIPE) {
        result.failure = std::string("connection lost: ") + modbus_strerror(errno);
        break;
      }
      continue;
    }
    result.latencies_us.push_back(static_cast<std::uint32_t>(us));
  }
  modbus_close(ctx);
  modbus_free(ctx);
}

std::uint32_t Percentile(const std::vector<std::uint32_t>& sorted, double p) {
  if (sorted.empty()) return 0;
  const std::size_t index = std::min(sorted.size() - 1, static_cast<std::size_t>(p * static_cast<double>(sorted.size() - 1) + 0.5));
  return sorted[index];
}

int Usage() {
  std::fprintf(stderr,
               "usage: ipe_bench_modbus_load --host ADDR --port N [--clients N] [--seconds S] "
               "[--mode io|drive]\n");
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  Options options;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (i + 1 >= argc) return Usage();
    const char* value = argv[++i];
    if (arg == "--host") options.host = value;
    else if (arg == "--port") options.port = std::atoi(value);
    else if (arg == "--clients") options.clients = std::atoi(value);
    else if (arg == "--seconds") options.seconds = std::atof(value);
    else if (arg == "--mode") options.io = std::string(value) != "drive";
    else return Usage();
  }
  if (options.clients < 1 || options.clients > 64 || options.seconds <= 0 || options.seconds > 60) {
    return Usage();
  }
  const Clock::time_point end =
      Clock::now() + std::chrono::milliseconds(static_cast<long>(options.seconds * 1000));
  std::vector<ClientResult> results(static_cast<std::size_t>(options.clients));
  std::vector<std::thread> threads;
  for (auto& result : results) threads.emplace_back(RunClient, std::cref(options), end, std::ref(result));
  for (auto& thread : threads) thread.join();

  std::vector<std::uint32_t> all;
  std::uint64_t errors = 0;
  int failed = 0;
  for (const auto& result : results) {
    all.insert(all.end(), result.latencies_us.begin(), result.latencies_us.end());
    errors += result.errors;
    if (!result.failure.empty()) {
      std::fprintf(stderr, "client: %s\n", result.failure.c_str());
      ++failed;
    }
  }
  std::sort(all.begin(), all.end());
  std::printf("mode=%s clients=%d seconds=%.1f transactions=%zu errors=%llu failed_clients=%d tps=%.0f "
              "p50_us=%u p99_us=%u max_us=%u\n",
              options.io ? "io" : "drive", options.clients, options.seconds, all.size(),
              static_cast<unsigned long long>(errors), failed, static_cast<double>(all.size()) / options.seconds,
              Percentile(all, 0.50), Percentile(all, 0.99), all.empty() ? 0u : all.back());
  return all.empty() ? 1 : 0;
}
