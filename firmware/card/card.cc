#include "card.h"

#include "lwip/init.h"
#include "lwip_port.h"

namespace firmware {
namespace {

// What LLDP's System Description TLV says (docs/network.md "LLDP").
constexpr std::string_view kLldpSystemDescription =
    "IPE002Z EtherNet/IP + Modbus TCP option card, firmware V1.06";
static_assert(kFirmwareVersion == 0x0106, "kLldpSystemDescription names the firmware version");

}  // namespace

Card::LwipStart::LwipStart(const CardDevices& devices) {
  BindLwipPlatform(devices.clock, devices.random, devices.diagnostics, devices.fatal);
  lwip_init();
}

Card::Card(const CardDevices& devices, const CardOptions& options)
    : clock_(devices.clock),
      port_(devices.port),
      store_(devices.store),
      watchdog_(devices.watchdog),
      lwip_(devices),
      netif_(devices.port),
      ring_(netif_, devices.clock),
      addressing_(netif_, devices.clock, devices.random),
      lldp_(netif_, addressing_, devices.clock, kLldpSystemDescription),
      loop_(devices.clock, devices.waiter, netif_),
      proxy_(devices.drive_serial, drive_link::LinkConfig{}, drive_link::ProxyConfig{}),
      proxy_service_(proxy_),
      drive_events_(proxy_),
      modbus_server_(proxy_, proxy_, proxy_),
      modbus_service_(modbus_server_, devices.clock, {.port = 502, .keepalive = options.keepalive}),
      parameter_writer_(proxy_),
      eip_card_({devices.port, netif_, addressing_, proxy_, parameter_writer_, devices.store, reset_,
                 devices.random, devices.clock, ring_},
                {.keepalive = options.keepalive, .connections = {}, .eds_override = options.eds}),
      leds_(devices.leds),
      // MS, NS and LNK from one model; the power-up test runs from here.
      indicators_({devices.port, proxy_, addressing_, &eip_card_.connections()}, leds_,
                  devices.clock.NowMicros()),
      // The web server's passwords are the card's own (NV store), not the inverter's.
      passwords_(devices.store, kNvWebPasswords, devices.random),
      access_(passwords_, devices.random),
      // Every configuration read from the inverter goes to the front ends (c500 picks the protocol
      // whose ports open, c554 the web server's): the Modbus service first, the rest in Start().
      publisher_(proxy_, modbus_server_, {}, netif_, kFirmwareVersion, &eip_card_.identity_sink()),
      web_status_({proxy_, publisher_, netif_, leds_, eip_card_.connections(), ring_}),
      web_application_({access_, proxy_, proxy_, proxy_, web_status_, eip_card_.served_eds()}),
      http_server_(web_application_),
      web_service_(http_server_, devices.clock, {.port = 80, .keepalive = options.keepalive}) {
  // The netif starts without an address: the addressing installs one once the configuration is read
  // from the inverter (c504-c516, c081-c096) and ACD has checked it (docs/network.md "Addressing").
  netif_.Start(Ipv4Config{}, nullptr);
  netif_.SetObserver(&addressing_);
  netif_.SetSwitchProtocol(&ring_);
  netif_.SetPortFrameHandler(&lldp_);
  web_status_.SetWebCounters(http_server_, web_service_);
  web_status_.SetLldp(lldp_.agent());
}

base::Status Card::Start() {
  failed_part_ = "EtherNet/IP";
  if (base::Status started = eip_card_.Start(); !started.ok()) return started;
  // TCP/IP attribute 10 as stored in the card (a change applies at the next reset).
  addressing_.SetAcdEnabled(eip_card_.tcpip().StoredSettings().select_acd);
  // A failing write leaves the default passwords in force; the next change tries the store again.
  passwords_stored_ = passwords_.Load().ok();

  // Each configuration load reaches the front ends in this order.
  if (base::Status added = publisher_.AddFrontEnd(modbus_service_); !added.ok()) return added;
  for (ConfigurableService* front_end : eip_card_.front_ends()) {
    if (base::Status added = publisher_.AddFrontEnd(*front_end); !added.ok()) return added;
  }
  for (ConfigurableService* front_end : {static_cast<ConfigurableService*>(&web_service_),
                                         static_cast<ConfigurableService*>(&addressing_),
                                         static_cast<ConfigurableService*>(&lldp_),
                                         static_cast<ConfigurableService*>(&indicators_)}) {
    if (base::Status added = publisher_.AddFrontEnd(*front_end); !added.ok()) return added;
  }
  proxy_.SetConfigListener(&publisher_);

  failed_part_ = "drive link";
  if (base::Status started = proxy_.Start(clock_.NowMicros()); !started.ok()) return started;

  failed_part_ = "event loop";
  // The loop polls the services in this order (event_loop.h "Which services a pass polls"): the drive
  // link on every pass (its bytes), the I/O productions at their slots only, the rest when due or
  // after an event.
  const auto add = [this](Service& service, PollWhen when) { return loop_.AddService(service, when); };
  if (base::Status added = add(proxy_service_, PollWhen::kEveryPass); !added.ok()) return added;
  if (base::Status added = add(modbus_service_, PollWhen::kDueOrEvent); !added.ok()) return added;
  for (Service* service : eip_card_.services()) {
    const PollWhen when = service == eip_card_.production_service() ? PollWhen::kDueOnly : PollWhen::kDueOrEvent;
    if (base::Status added = add(*service, when); !added.ok()) return added;
  }
  for (Service* service : {static_cast<Service*>(&parameter_writer_), static_cast<Service*>(&web_application_),
                           static_cast<Service*>(&web_service_), static_cast<Service*>(&publisher_),
                           static_cast<Service*>(&addressing_), static_cast<Service*>(&lldp_),
                           static_cast<Service*>(&indicators_), static_cast<Service*>(&ring_)}) {
    if (base::Status added = add(*service, PollWhen::kDueOrEvent); !added.ok()) return added;
  }
  loop_.SetEventProbe(&drive_events_);
  indicators_.RestartPowerUpTest(clock_.NowMicros());
  failed_part_ = "";
  return base::OkStatus();
}

std::optional<hal::ResetKind> Card::RunOnce() {
  if (watchdog_ != nullptr) watchdog_->Feed();
  if (reset_.pending().has_value()) {
    // A reset waits, boundedly, for settings still on their way into the inverter's EEPROM (a
    // Set_Attribute_Single followed by the Identity Reset must not lose the setting).
    const hal::Micros now = clock_.NowMicros();
    if (reset_deadline_ == hal::kNever) reset_deadline_ = now + kResetDrainLimit;
    if (parameter_writer_.pending() == 0 || now >= reset_deadline_) {
      if (*reset_.pending() == hal::ResetKind::kFactoryDefaults) {
        // Identity Reset type 1: the card's own settings go back to the out-of-box defaults. The
        // factory data (MAC) stays; the configuration in the inverter (c-parameters) is the drive's.
        store_.Erase(kNvTcpIpExtras).IgnoreError();
        store_.Erase(kNvQos).IgnoreError();
      }
      return reset_.pending();
    }
  }
  loop_.RunOnce();
  return std::nullopt;
}

Card::DriveLinkEvents::Picture Card::DriveLinkEvents::Take() const {
  const drive_link::ProxyCounters& counters = proxy_.counters();
  Picture now;
  now.link = proxy_.link().state();
  now.config_loaded = proxy_.config_loaded();
  now.drive_status_known = proxy_.drive_status_known();
  now.drive_command_taken = proxy_.drive_command_taken();
  now.loss_action_active = proxy_.loss_action_active();
  now.drive_status = proxy_.drive_status();
  now.config_loads = counters.config_loads;
  now.monitor_words = proxy_.MonitorWords();
  const drive_link::DriveFeedbackWords feedback = proxy_.DriveFeedback();
  now.feedback_fd00 = feedback.fd00;
  now.feedback_fe02 = feedback.fe02;
  now.feedback_known = feedback.known;
  now.accesses_done = counters.accesses_ok;
  for (std::uint32_t errors : counters.access_errors) now.accesses_done += errors;
  now.writes_done = counters.command_writes + counters.command_errors + counters.owned_writes +
                    counters.owned_errors + counters.loss_action_writes + counters.loss_action_errors;
  return now;
}

bool Card::DriveLinkEvents::TakeEvent() {
  const Activity activity{proxy_.link().counters().completed, proxy_.counters().accesses,
                          proxy_.counters().pool_full, proxy_.link().state(), proxy_.loss_action_active()};
  if (activity == activity_) return false;
  activity_ = activity;
  const Picture now = Take();
  if (now == seen_) return false;
  seen_ = now;
  return true;
}

CardReadiness Card::Readiness() const {
  CardReadiness readiness;
  readiness.link_up = netif_.link_up();
  // The drive link has given up (e-23): the card runs without a drive.
  const bool link_fault = proxy_.link().state() == drive_link::LinkState::kFault;
  readiness.drive_settled = proxy_.config_loaded() || link_fault;
  readiness.address_settled =
      addressing_.phase() != AddressPhase::kProbing && (addressing_.configured() || link_fault);
  return readiness;
}

bool Card::TakeAddressChange() {
  const Ipv4Config now = addressing_.active();
  if (address_announced_ && now == announced_) return false;
  if (!address_announced_ && now.address.IsUnspecified()) return false;
  address_announced_ = true;
  announced_ = now;
  return true;
}

}  // namespace firmware
