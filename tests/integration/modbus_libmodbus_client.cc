// A libmodbus client against the card: the checks of libmodbus's own unit-test client that apply to
// a drive (tests/unit-test-client.c upstream: illegal data address, too many registers, an unknown
// function), each asserting the exception libmodbus reports, plus a write/read round trip.
//
// usage: ipe_it_modbus_client HOST PORT; exit 0 when every check passed.
#include <modbus/modbus.h>

#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstdlib>

namespace {

int failures = 0;

void Check(bool condition, const char* what) {
  std::printf("%s: %s (errno %d: %s)\n", condition ? "ok" : "FAIL", what, errno, modbus_strerror(errno));
  if (!condition) ++failures;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: ipe_it_modbus_client HOST PORT\n");
    return 2;
  }
  modbus_t* ctx = modbus_new_tcp(argv[1], std::atoi(argv[2]));
  if (ctx == nullptr || modbus_connect(ctx) != 0) {
    std::fprintf(stderr, "connect: %s\n", modbus_strerror(errno));
    return 1;
  }
  modbus_set_response_timeout(ctx, 3, 0);
  std::uint16_t regs[64] = {};

  modbus_set_slave(ctx, 0);
  Check(modbus_write_register(ctx, 0x0010, 90) == 1, "FC 06 dec = 90");
  Check(modbus_read_registers(ctx, 0x0010, 1, regs) == 1 && regs[0] == 90, "FC 03 dec reads 90");

  // Too many registers: 64 > the 63 of seed 000 §8.3 -> illegal data value (03).
  Check(modbus_read_registers(ctx, 0x0009, 64, regs) == -1 && errno == EMBXILVAL, "FC 03 x64 -> 03");
  // Illegal data address: a monitor is not writable; no communication number past FFF9 (02).
  Check(modbus_write_register(ctx, 0xFD01, 1) == -1 && errno == EMBXILADD, "FC 06 FD01 -> 02");
  Check(modbus_read_registers(ctx, 0xFFF9, 2, regs) == -1 && errno == EMBXILADD, "FC 03 FFF9 x2 -> 02");
  // Unsupported functions -> illegal function (01): Report Server ID (0x11), as libmodbus's own client
  // probes it. (libmodbus 3.1.6 cannot address unit 251: modbus_set_slave takes 0-247 and 255 only.)
  std::uint8_t id[MODBUS_MAX_PDU_LENGTH];
  Check(modbus_report_slave_id(ctx, sizeof id, id) == -1 && errno == EMBXILFUN, "FC 0x11 -> 01");
  // FC 01 (read coils) is not supported -> 01.
  std::uint8_t bits[8];
  Check(modbus_read_bits(ctx, 0, 1, bits) == -1 && errno == EMBXILFUN, "FC 01 -> 01");

  modbus_close(ctx);
  modbus_free(ctx);
  return failures == 0 ? 0 : 1;
}
