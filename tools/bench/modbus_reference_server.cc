// The reference for tools/bench/modbus: a Modbus TCP server built on libmodbus and kernel sockets,
// answering the load generator's requests from a plain register map (no drive behind it). It is the
// "best case" a server on a full OS reaches with the same generator; the card is compared with it.
//
// usage: ipe_bench_modbus_reference --addr ADDR --port N [--seconds S]
// Serves up to 64 clients with select(); exits after --seconds (default 120, at most 600) or on SIGTERM.
#include <modbus/modbus.h>
#include <sys/select.h>
#include <unistd.h>

#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <string>

namespace {
volatile std::sig_atomic_t g_stop = 0;  // host tool: the signal handler's only channel
void OnSignal(int) { g_stop = 1; }
}  // namespace

int main(int argc, char** argv) {
  std::string addr = "127.0.0.1";
  int port = 1502;
  long seconds = 120;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string arg = argv[i];
    if (arg == "--addr") addr = argv[i + 1];
    else if (arg == "--port") port = std::atoi(argv[i + 1]);
    else if (arg == "--seconds") seconds = std::atol(argv[i + 1]);
    else {
      std::fprintf(stderr, "usage: ipe_bench_modbus_reference --addr ADDR --port N [--seconds S]\n");
      return 2;
    }
  }
  if (seconds < 1 || seconds > 600) seconds = 120;
  std::signal(SIGTERM, OnSignal);
  std::signal(SIGINT, OnSignal);

  modbus_t* ctx = modbus_new_tcp(addr.c_str(), port);
  modbus_mapping_t* map = modbus_mapping_new(0, 0, 0x10000, 0);
  if (ctx == nullptr || map == nullptr) return 1;
  const int listener = modbus_tcp_listen(ctx, 64);
  if (listener < 0) {
    std::fprintf(stderr, "listen: %s\n", modbus_strerror(errno));
    return 1;
  }
  std::printf("reference listening %s:%d\n", addr.c_str(), port);
  std::fflush(stdout);

  fd_set all;
  FD_ZERO(&all);
  FD_SET(listener, &all);
  int max_fd = listener;
  const std::time_t end = std::time(nullptr) + seconds;
  std::uint8_t query[MODBUS_TCP_MAX_ADU_LENGTH];
  while (!g_stop && std::time(nullptr) < end) {
    fd_set ready = all;
    timeval tv{0, 200000};
    const int n = select(max_fd + 1, &ready, nullptr, nullptr, &tv);
    if (n <= 0) continue;
    for (int fd = 0; fd <= max_fd; ++fd) {
      if (!FD_ISSET(fd, &ready)) continue;
      if (fd == listener) {
        int s = listener;
        const int client = modbus_tcp_accept(ctx, &s);
        if (client >= 0 && client < FD_SETSIZE) {
          FD_SET(client, &all);
          if (client > max_fd) max_fd = client;
        } else if (client >= 0) {
          close(client);
        }
        continue;
      }
      modbus_set_socket(ctx, fd);
      const int rc = modbus_receive(ctx, query);
      if (rc > 0) {
        modbus_reply(ctx, query, rc, map);
      } else if (rc < 0) {
        close(fd);
        FD_CLR(fd, &all);
      }
    }
  }
  close(listener);
  modbus_mapping_free(map);
  modbus_free(ctx);
  return 0;
}
