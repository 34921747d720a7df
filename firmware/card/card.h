// The card: the one device composition. It owns every device object of the firmware (the netif and
// its switch, the addressing, the drive link and its register proxy, the Modbus TCP and EtherNet/IP
// front ends, the web server, the indicators, the event loop) and wires them once, from the HAL
// devices a main hands it. The host main (firmware/host) and the board main (firmware/board) each
// build their HAL backends and a Card; neither repeats any wiring.
//
// Life cycle:
//   Card card(devices, options);   // binds lwIP to the clock and random source, runs lwip_init()
//   card.AddService(extra);        // optional: services of the main (the host's simulated inverter)
//   card.Start();                  // registers the objects, starts the drive link
//   for (;;) if (auto reset = card.RunOnce()) { perform *reset; }
//
// A Card is large (every buffer and pool of the firmware is inside it) and must be built once per
// start of the firmware: lwIP's state is global and lwip_init() runs in the constructor. A board
// keeps it in static storage, so the linker counts it against the RAM budget (docs/board.md).
#pragma once

#include <array>
#include <cstdint>
#include <optional>

#include "base/status.h"
#include "card_addressing.h"
#include "card_indicators.h"
#include "card_lldp.h"
#include "card_netif.h"
#include "card_records.h"
#include "card_ring.h"
#include "card_status_publisher.h"
#include "cip/file_object.h"
#include "drive_link/register_proxy.h"
#include "ethernet_ip_card.h"
#include "event_loop.h"
#include "hal/clock.h"
#include "hal/console.h"
#include "hal/frame_port.h"
#include "hal/leds.h"
#include "hal/nv_store.h"
#include "hal/random.h"
#include "hal/reset.h"
#include "hal/serial_port.h"
#include "hal/waiter.h"
#include "hal/watchdog.h"
#include "led_mirror.h"
#include "modbus/server.h"
#include "modbus_tcp_service.h"
#include "parameter_writer.h"
#include "polled_service.h"
#include "tcp_keepalive.h"
#include "web/access_control.h"
#include "web/http_server.h"
#include "web/password_store.h"
#include "web_application.h"
#include "web_card_status.h"
#include "web_service.h"

namespace firmware {

// The card's firmware version as FC 43 and unit 251 show it ("0106": V1.06, the version of the card
// this one imitates, seed 000 §8.8).
inline constexpr std::uint16_t kFirmwareVersion = 0x0106;

// How long a requested reset waits for queued parameter writes (32 writes take well under a second).
inline constexpr hal::Micros kResetDrainLimit = 3 * hal::kMicrosPerSecond;

// The HAL devices a card is built from; all outlive the card.
struct CardDevices {
  const hal::Clock& clock;
  hal::Waiter& waiter;
  hal::FramePort& port;          // the MAC behind the two-port switch; Mac() is the card's address
  hal::SerialPort& drive_serial;  // the serial line to the inverter
  hal::NvStore& store;            // the card's own records (card_records.h)
  hal::Leds& leds;
  hal::RandomSource& random;
  hal::ConsoleOutput& diagnostics;  // lwIP's diagnostics (host: stderr; board: the console UART)
  hal::FatalHandler& fatal;         // a failed lwIP assertion (host: abort; board: console line, reset)
  hal::Watchdog* watchdog = nullptr;  // fed once per pass of the loop; null: none
};

struct CardOptions {
  TcpKeepalive keepalive;  // of every TCP connection the card accepts
  // Another EDS than the card's own (card.cc), outliving the card: the host's --eds, for tests.
  const cip::ServedFile* eds = nullptr;
};

// Where the card is on its way up (the "ready" line is printed once this says so).
struct CardReadiness {
  bool link_up = false;
  bool drive_settled = false;    // configuration read from the inverter, or the link gave up (e-23)
  bool address_settled = false;  // an address in use, BOOTP/DHCP running, a conflict, or none usable

  bool ready() const { return link_up && drive_settled && address_settled; }
};

class Card {
 public:
  Card(const CardDevices& devices, const CardOptions& options);
  Card(const Card&) = delete;
  Card& operator=(const Card&) = delete;

  // A service of the main, polled by the card's loop (before Start()). kResourceExhausted when the
  // loop is full.
  base::Status AddService(Service& service, PollWhen when = PollWhen::kEveryPass) {
    return loop_.AddService(service, when);
  }

  // Registers the CIP classes and assemblies, loads the web passwords and starts the drive link.
  // Fails only on a wiring mistake or a drive link that cannot start; failed_part() names the part.
  base::Status Start();
  const char* failed_part() const { return failed_part_; }

  // One pass of the event loop (it may sleep in the waiter until something is due). Feeds the
  // watchdog. Returns the reset to perform now, once a requested reset has waited (at most
  // kResetDrainLimit) for queued parameter writes; for a factory-defaults reset the card's own
  // settings are already erased. The caller performs it (host: re-exec; board: system reset).
  std::optional<hal::ResetKind> RunOnce();

  CardReadiness Readiness() const;
  // True once per change of the address in use (after the first address), for an "address" line.
  bool TakeAddressChange();

  base::MacAddress mac() const { return port_.Mac(); }
  hal::ResetControl& reset_control() { return reset_; }
  // False when the default web passwords could not be written at start (they are in force anyway).
  bool passwords_stored() const { return passwords_stored_; }

  // The card's objects, for the host's control socket and reports and for tests.
  CardNetif& netif() { return netif_; }
  const CardNetif& netif() const { return netif_; }
  const hal::Clock& clock() const { return clock_; }
  const CardAddressing& addressing() const { return addressing_; }
  const CardRing& ring() const { return ring_; }
  const CardLldp& lldp() const { return lldp_; }
  EventLoop& loop() { return loop_; }
  const drive_link::RegisterProxy& proxy() const { return proxy_; }
  const modbus::Server& modbus_server() const { return modbus_server_; }
  const ModbusTcpService& modbus_service() const { return modbus_service_; }
  const EtherNetIpCard& eip() const { return eip_card_; }
  const ParameterWriter& parameter_writer() const { return parameter_writer_; }
  const CardIndicators& indicators() const { return indicators_; }
  const WebService& web_service() const { return web_service_; }
  const web::HttpServer& http_server() const { return http_server_; }
  const web::AccessControl& access() const { return access_; }
  const cip::ServedFile& eds() const { return eip_card_.served_eds(); }

 private:
  // Binds lwIP's platform functions and runs lwip_init() before any member that uses lwIP is built.
  struct LwipStart {
    explicit LwipStart(const CardDevices& devices);
  };
  // The drive link's events for the loop: what the front ends wait for changed. The link state, the
  // configuration load, the drive status word, the monitor words, the drive feedback, an on-demand
  // access or a command write finished, the loss action. Not every serial transaction or exchange
  // cycle: the cyclic reads of an idle drive return what they returned before, and polling every
  // front end for each of them was most of the card's idle work.
  class DriveLinkEvents final : public EventProbe {
   public:
    explicit DriveLinkEvents(const drive_link::RegisterProxy& proxy) : proxy_(proxy) {}
    bool TakeEvent() override;

   private:
    struct Picture {
      drive_link::LinkState link{};
      bool config_loaded = false;
      bool drive_status_known = false;
      bool drive_command_taken = false;
      bool loss_action_active = false;
      std::uint16_t drive_status = 0;
      std::uint32_t config_loads = 0;
      drive_link::ScannerWords monitor_words{};
      std::uint16_t feedback_fd00 = 0;
      std::uint16_t feedback_fe02 = 0;
      bool feedback_known = false;
      std::uint32_t accesses_done = 0;
      std::uint32_t writes_done = 0;
      bool operator==(const Picture&) const = default;
    };
    // What moves whenever the picture may have changed: a transaction finished, the link state, an
    // access accepted (a local refusal finishes without the link), the loss action. Compared first,
    // so that a pass without drive-link activity costs a few loads.
    struct Activity {
      std::uint32_t completed = 0;
      std::uint32_t accesses = 0;
      std::uint32_t pool_full = 0;
      drive_link::LinkState link{};
      bool loss_action_active = false;
      bool operator==(const Activity&) const = default;
    };
    Picture Take() const;

    const drive_link::RegisterProxy& proxy_;
    Activity activity_;
    Picture seen_;
  };
  class ResetLatch final : public hal::ResetControl {
   public:
    void RequestReset(hal::ResetKind kind) override { kind_ = kind; }
    const std::optional<hal::ResetKind>& pending() const { return kind_; }

   private:
    std::optional<hal::ResetKind> kind_;
  };

  const hal::Clock& clock_;
  hal::FramePort& port_;
  hal::NvStore& store_;
  hal::Watchdog* watchdog_;
  LwipStart lwip_;
  CardNetif netif_;
  CardRing ring_;
  CardAddressing addressing_;
  CardLldp lldp_;
  EventLoop loop_;
  ResetLatch reset_;
  drive_link::RegisterProxy proxy_;
  PolledService<drive_link::RegisterProxy> proxy_service_;
  DriveLinkEvents drive_events_;
  modbus::Server modbus_server_;
  ModbusTcpService modbus_service_;
  ParameterWriter parameter_writer_;
  EtherNetIpCard eip_card_;
  LedMirror leds_;
  CardIndicators indicators_;
  web::PasswordStore passwords_;
  web::AccessControl access_;
  CardStatusPublisher publisher_;
  CardWebStatus web_status_;
  WebApplication web_application_;
  web::HttpServer http_server_;
  WebService web_service_;

  const char* failed_part_ = "";
  bool passwords_stored_ = false;
  hal::Micros reset_deadline_ = hal::kNever;
  Ipv4Config announced_;
  bool address_announced_ = false;
};

}  // namespace firmware
