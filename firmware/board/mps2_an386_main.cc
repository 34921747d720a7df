// ipe002z-board: the card's firmware on the mps2-an386 board (Cortex-M4F, QEMU). The board's
// composition root: it builds the board HAL (hal/mps2_an386), the MAC, a firmware::Card (the one device
// composition, wired there and nowhere else), the console service, and runs the loop; it prints the
// same "ready" and "address" lines as the host card and performs the reset the card asks for.
//
// Every object lives in static storage (function-local statics, built in this order, never destroyed),
// so the linker counts all of it against the RAM budget. docs/board.md describes the board.
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>

#include "board_console.h"
#include "board_random.h"
#include "card.h"
#include "card_lines.h"
#include "card_records.h"
#include "cmsdk_uart.h"
#include "cmsdk_watchdog.h"
#include "cortex_m.h"
#include "drive_link/link_client.h"
#include "fpgaio_leds.h"
#include "hal/flash_nv_store.h"
#include "hal/text_line.h"
#include "lan9118_frame_port.h"
#include "mps2_an386.h"
#include "panic.h"
#include "ram_nv_store.h"
#include "semihosting_flash.h"
#include "system_clock.h"
#include "timer_waiter.h"
#include "uart_console.h"

namespace {

using hal::mps2::Irq;
namespace address = hal::mps2::address;

// The watchdog warns after this long without a feed and resets after twice this; the waiter wakes the
// loop at least twice per timeout, so an idle card always feeds it in time.
constexpr hal::Micros kWatchdogTimeout = hal::kMicrosPerSecond;
constexpr hal::Micros kLongestSleep = kWatchdogTimeout / 2;

// The drive link's UART: Toshiba frames are short; the loop reads them every pass.
using DriveUart = hal::mps2::CmsdkUart<256, 256>;

void Say(hal::ConsoleOutput& console, const hal::TextLine& line) {
  console.Write(line.view());
  console.Write("\n");
}

// The NV flash area: the file named by `flash=PATH` on the semihosting command line.
void OpenFlash(hal::mps2::SemihostingFlash& flash, hal::ConsoleOutput& console) {
  char path[160];  // the host opens the file by name; the flash keeps its handle, not the name
  hal::TextLine line;
  const base::Result<std::string_view> argument = hal::mps2::SemihostingArgument("flash", path);
  if (!argument.ok()) {
    line.Text("flash: none (").Text(argument.status() == base::NotFound() ? "no flash=PATH on the semihosting command line"
                                                                          : "no semihosting")
        .Text("): settings are not kept");
    Say(console, line);
    return;
  }
  const base::Status opened = flash.Open(std::string_view(path, argument->size() + 1));
  if (!opened.ok()) {
    line.Text("flash: cannot open ").Text(argument.value()).Text(" (").Text(base::StatusName(opened)).Text(")");
    Say(console, line);
    return;
  }
  line.Text("flash: file=").Text(argument.value()).Text(" sectors=").Unsigned(flash.SectorCount());
  line.Text("x").Unsigned(flash.SectorSize()).Text(" unit=").Unsigned(flash.ProgramUnit());
  Say(console, line);
}

// The card's records: on the flash when there is one (hal::FlashNvStore), else in RAM for this run
// only (QEMU without semihosting or without flash=PATH), which the console line says.
hal::NvStore& MountStore(hal::mps2::SemihostingFlash& flash, hal::FlashNvStore& flash_store,
                         firmware::board::RamNvStore& ram_store, hal::ConsoleOutput& console) {
  hal::TextLine line;
  if (!flash.open()) {
    line.Text("nv: no flash: the card's records are kept in RAM until the next reset");
    Say(console, line);
    return ram_store;
  }
  if (const base::Status mounted = flash_store.Mount(); !mounted.ok()) {
    line.Text("nv: the flash store does not mount (").Text(base::StatusName(mounted));
    line.Text("): the card's records are kept in RAM until the next reset");
    Say(console, line);
    return ram_store;
  }
  const hal::FlashNvStore::Usage usage = flash_store.usage();
  line.Text("nv: flash store mounted, ");
  if (usage.has_active) {
    line.Text("generation=").Unsigned(usage.generation).Text(" active_sector=").Unsigned(usage.active_sector);
  } else {
    line.Text("empty");
  }
  Say(console, line);
  return flash_store;
}

void SayReady(firmware::Card& card, hal::ConsoleOutput& console) {
  hal::TextLine line;
  line.Text("ready ");
  firmware::DescribeIdentity(card, line);
  line.Text(" net=board ");
  firmware::DescribeEndpoints(card.addressing().active().address, line);
  line.Text(" drive=").Text(drive_link::LinkStateName(card.proxy().link().state()));
  Say(console, line);
}

[[noreturn]] void PerformReset(hal::ResetKind kind, hal::mps2::UartConsole& console,
                               const hal::mps2::ConsoleUart& console_uart, const hal::Clock& clock) {
  hal::TextLine line;
  line.Text("reset: ").Text(kind == hal::ResetKind::kFactoryDefaults ? "factory defaults" : "restart");
  Say(console, line);
  // Let the console say so before the UART is reset with everything else (bounded: 100 ms).
  const hal::Micros until = clock.NowMicros() + 100 * hal::kMicrosPerMilli;
  while (console_uart.transmit_pending() != 0 && clock.NowMicros() < until) {
  }
  hal::mps2::SystemReset();
}

}  // namespace

int main() {
  static hal::mps2::ConsoleUart console_uart(address::kUart0, Irq::kUart0Receive, Irq::kUart0Transmit,
                                             hal::mps2::UartLine::kWire);
  static_cast<void>(console_uart.Configure({.baud = hal::mps2::kConsoleBaud, .parity = hal::Parity::kNone,
                                            .stop_bits = 1}));
  static hal::mps2::UartConsole console(console_uart);
  console.Write("\nipe002z-board: mps2-an386 (Cortex-M4F), starting\n");

  static hal::mps2::SystemClock clock;
  clock.Start();

  static hal::mps2::SemihostingFlash flash;
  OpenFlash(flash, console);
  static hal::FlashNvStore flash_store(flash);
  static firmware::board::RamNvStore ram_store;
  hal::NvStore& store = MountStore(flash, flash_store, ram_store, console);

  static hal::mps2::BoardRandom random;
  const hal::mps2::RandomSeeding seeding = random.Seed(store, firmware::kNvRandomSeed, clock);
  const base::MacAddress mac = firmware::LoadOrCreateMac(store, random);
  random.Mix(mac);
  {
    hal::TextLine line;
    line.Text("random: chacha20 seed=").Text(seeding.stored_seed ? "stored" : "new");
    line.Text(" renewed=").Text(seeding.seed_renewed ? "yes" : "no").Text(" jitter_samples=");
    line.Unsigned(seeding.jitter_samples).Text(" (no TRNG on this board: docs/board.md)");
    Say(console, line);
  }

  static hal::mps2::Lan9118FramePort ethernet;
  {
    const base::Status started = ethernet.Start(mac);
    hal::TextLine line;
    line.Text("ethernet: LAN9118 id_rev=");
    hal::mps2::AppendHex32(line, ethernet.chip_id());
    line.Text(" mac=").Mac(mac);
    if (!started.ok()) line.Text(" not usable (").Text(base::StatusName(started)).Text("): no network");
    Say(console, line);
  }

  // Under QEMU the drive UART ends in a character device: the drive link's 8E1 is accepted as bytes
  // (cmsdk_uart.h; docs/board.md "Parity").
  static DriveUart drive_uart(address::kUart1, Irq::kUart1Receive, Irq::kUart1Transmit,
                              hal::mps2::UartLine::kEmulatedByteStream);
  static hal::mps2::FpgaioLeds leds(clock, console);
  static hal::mps2::CmsdkWatchdog watchdog(kWatchdogTimeout);
  static hal::mps2::TimerWaiter waiter(clock, kLongestSleep);
  waiter.Start();

  static firmware::Card card(firmware::CardDevices{.clock = clock,
                                                   .waiter = waiter,
                                                   .port = ethernet,
                                                   .drive_serial = drive_uart,
                                                   .store = store,
                                                   .leds = leds,
                                                   .random = random,
                                                   .diagnostics = console,
                                                   .fatal = console,
                                                   .watchdog = &watchdog},
                             firmware::CardOptions{});
  static firmware::board::BoardConsole console_service(firmware::board::BoardConsoleDevices{
      .input = console_uart, .output = console, .card = card, .leds = leds, .waiter = waiter, .console = console});
  if (base::Status added = card.AddService(console_service); !added.ok()) console.Fatal("start: console service");
  if (base::Status started = card.Start(); !started.ok()) {
    hal::TextLine line;
    line.Text("start: ").Text(card.failed_part()).Text(" failed (").Text(base::StatusName(started)).Text(")");
    console.Fatal(line.view());
  }
  if (!card.passwords_stored()) console.Write("web: cannot store the default passwords; they are in force anyway\n");

  // From here on a loop that stops feeding is reset (the boot above, PBKDF2 of the default web
  // passwords included, is not covered).
  watchdog.Start();
  bool ready_printed = false;
  for (;;) {
    if (const std::optional<hal::ResetKind> reset = card.RunOnce()) PerformReset(*reset, console, console_uart, clock);
    if (card.TakeAddressChange()) {
      hal::TextLine line;
      line.Text("address ");
      firmware::DescribeAddress(card.addressing(), line);
      Say(console, line);
    }
    if (!ready_printed && card.Readiness().ready()) {
      SayReady(card, console);
      ready_printed = true;
    }
  }
}
