#include "host_card.h"

#include <array>
#include <cstdio>
#include <memory>
#include <optional>
#include <string_view>

#include "capturing_frame_port.h"
#include "card_addressing.h"
#include "card_indicators.h"
#include "card_netif.h"
#include "card_records.h"
#include "card_report.h"
#include "card_status_publisher.h"
#include "control_server.h"
#include "drive_link/drive_registers.h"
#include "drive_link/register_proxy.h"
#include "ethernet_ip_card.h"
#include "event_loop.h"
#include "file_nv_store.h"
#include "host_clock.h"
#include "host_random.h"
#include "logging_leds.h"
#include "lwip/init.h"
#include "lwip_port.h"
#include "modbus/server.h"
#include "modbus_tcp_service.h"
#include "network_report.h"
#include "parameter_writer.h"
#include "pcap_writer.h"
#include "poll_waiter.h"
#include "polled_service.h"
#include "signal_source.h"
#include "sim_inverter.h"
#include "slirp_frame_port.h"
#include "socket_serial_port.h"
#include "tap_frame_port.h"
#include "led_mirror.h"
#include "web/access_control.h"
#include "web/http_server.h"
#include "web/password_store.h"
#include "web_application.h"
#include "web_card_status.h"
#include "web_service.h"

namespace host {
namespace {

// The card's firmware version as FC 43 and unit 251 show it ("0106": V1.06, the version of the card
// this one imitates, seed 000 §8.8).
constexpr std::uint16_t kFirmwareVersion = 0x0106;

// How long a requested reset waits for queued parameter writes (32 writes take well under a second).
constexpr hal::Micros kResetDrainLimit = 3 * hal::kMicrosPerSecond;

std::string FormatMac(const hal::MacAddress& mac) {
  char text[18];
  std::snprintf(text, sizeof text, "%02x:%02x:%02x:%02x:%02x:%02x", mac[0], mac[1], mac[2], mac[3],
                mac[4], mac[5]);
  return text;
}

// --ip: the address plan keyed into the inverter before power-up, at every start: c504 = 0 (manual) and
// c505-c516 (one octet per parameter; communication numbers C505-C509, C510-C516).
bool ForceManualAddress(const HostOptions& options, SimulatedInverter& inverter, std::string& error) {
  std::array<std::uint16_t, 13> values{0};
  for (unsigned i = 0; i < 4; ++i) {
    const unsigned shift = 24 - 8 * i;
    values[1 + i] = static_cast<std::uint16_t>((options.ip >> shift) & 0xFF);
    values[5 + i] = static_cast<std::uint16_t>((options.netmask >> shift) & 0xFF);
    values[9 + i] = static_cast<std::uint16_t>((options.gateway >> shift) & 0xFF);
  }
  for (unsigned i = 0; i < values.size(); ++i) {
    const hal::host::sim::WriteResult result =
        inverter.model().Write(drive_link::reg::CParameter(504 + i), values[i], hal::host::sim::WriteTarget::kRamAndEeprom);
    if (!result.ok()) {
      error = "--ip: the inverter refused c" + std::to_string(504 + i) + " (" +
              hal::host::sim::WriteOutcomeName(result.outcome) + ")";
      return false;
    }
  }
  inverter.SaveIfChanged();
  return true;
}

// Prints "address ..." on stdout whenever the address in use changes (tests and users wait for it).
class AddressAnnouncer {
 public:
  explicit AddressAnnouncer(const NetworkReport& report) : report_(report) {}
  void Check() {
    const firmware::Ipv4Config now = report_.addressing.active();
    if (printed_ && now == last_) return;
    if (!printed_ && now.address == 0) return;
    printed_ = true;
    last_ = now;
    std::printf("address %s\n", DescribeAddress(report_).c_str());
    std::fflush(stdout);
  }

 private:
  const NetworkReport& report_;
  firmware::Ipv4Config last_;
  bool printed_ = false;
};

class ResetRequest final : public hal::ResetControl {
 public:
  void RequestReset(hal::ResetKind kind) override { kind_ = kind; }
  const std::optional<hal::ResetKind>& pending() const { return kind_; }

 private:
  std::optional<hal::ResetKind> kind_;
};

// The network port as built from --net, with what the control socket and the ready line need.
struct NetworkPort {
  std::unique_ptr<hal::FramePort> device;
  hal::host::PollSource* poll_source = nullptr;
  std::function<base::Status(hal::PortId, bool)> set_plugged;
  std::string endpoints;  // "modbus=... enip=... io=... http=..." (loopback; TAP: from the address in use)
};

std::string TapEndpoints(const std::string& ip) {
  return "modbus=" + ip + ":502 enip=" + ip + ":44818 enip-udp=" + ip + ":44818 io=" + ip +
         ":2222 http=" + ip + ":80";
}

std::string SlirpEndpoints(const hal::host::SlirpFramePort& port) {
  std::string tcp44818, udp44818, modbus, io, http;
  for (const hal::host::ActiveForward& f : port.ActiveForwards()) {
    const std::string endpoint = f.host_address + ":" + std::to_string(f.host_port);
    const bool tcp = f.transport == hal::host::Transport::kTcp;
    if (f.guest_port == 502) modbus = endpoint;
    if (f.guest_port == 44818) (tcp ? tcp44818 : udp44818) = endpoint;
    if (f.guest_port == 2222) io = endpoint;
    if (f.guest_port == 80) http = endpoint;
  }
  return "modbus=" + modbus + " enip=" + tcp44818 + " enip-udp=" + udp44818 + " io=" + io +
         " http=" + http;
}

bool OpenNetworkPort(const HostOptions& options, const hal::MacAddress& mac, const hal::Clock& clock,
                     NetworkPort& out, std::string& error) {
  if (options.net == NetKind::kTap) {
    auto tap = hal::host::TapFramePort::Open(options.tap_interfaces, mac, &error);
    if (!tap.ok()) return false;
    hal::host::TapFramePort* raw = tap.value().get();
    out.poll_source = raw;
    out.set_plugged = [raw](hal::PortId p, bool plugged) { return raw->SetPlugged(p, plugged); };
    out.device = std::move(tap.value());
    return true;
  }
  hal::host::SlirpPortConfig config;
  config.mac = mac;
  config.guest_address = FormatIpv4(options.ip);
  config.netmask = FormatIpv4(options.netmask);
  config.network = FormatIpv4(options.ip & options.netmask);
  config.gateway = FormatIpv4(options.gateway);
  config.host_address = options.host_address;
  auto slirp = hal::host::SlirpFramePort::Create(config, clock, &error);
  if (!slirp.ok()) return false;
  hal::host::SlirpFramePort* raw = slirp.value().get();
  out.poll_source = raw;
  out.set_plugged = [raw](hal::PortId p, bool plugged) { return raw->SetPlugged(p, plugged); };
  out.endpoints = SlirpEndpoints(*raw);
  out.device = std::move(slirp.value());
  return true;
}

}  // namespace

CardExit RunHostCard(const HostOptions& options, std::string& error) {
  hal::host::HostClock clock;
  hal::host::HostRandom random;
  hal::host::PollWaiter waiter(clock);

  auto store = hal::host::FileNvStore::Open(options.state_dir + "/card", &error);
  if (!store.ok()) return CardExit::kFailed;
  const hal::MacAddress mac = LoadOrCreateMac(*store.value(), random);

  // The serial line to the inverter: a socket pair, the card's UART on one end and the simulated
  // inverter on the other (docs/simulator.md "In ipe002z-host").
  auto line = hal::host::SocketSerialPort::CreatePair();
  if (!line.ok()) {
    error = "cannot create the serial line to the simulated inverter";
    return CardExit::kFailed;
  }
  std::unique_ptr<hal::host::SocketSerialPort> inverter_serial = std::move(line.value().inverter);
  // The card's end of the line, for the drive link (drive_link::LinkClient on this hal::SerialPort,
  // wrapped in a firmware::Service added to the loop below). Registered with the waiter so reply bytes
  // wake the loop; whoever holds this end must read them, or poll() would report them forever.
  std::unique_ptr<hal::host::SocketSerialPort> card_serial = std::move(line.value().card);

  SimInverterConfig inverter_config;
  inverter_config.model = options.model;
  inverter_config.directory = options.state_dir + "/inverter";
  inverter_config.presets = options.params;
  inverter_config.server = ServerConfigFromOptions(options);
  std::unique_ptr<SimulatedInverter> inverter =
      SimulatedInverter::Create(inverter_config, *inverter_serial, clock, stderr, error);
  if (!inverter) return CardExit::kFailed;
  if (options.ip_given && !ForceManualAddress(options, *inverter, error)) return CardExit::kFailed;
  waiter.Register(*inverter_serial);         // request bytes wake the inverter
  waiter.Register(inverter->poll_source());  // its reply and receive timers
  waiter.Register(*card_serial);             // reply bytes wake the card

  NetworkPort network;
  if (!OpenNetworkPort(options, mac, clock, network, error)) return CardExit::kFailed;
  waiter.Register(*network.poll_source);

  // --pcap: every frame in and out, captured at the port boundary (what a tap on the cable would see).
  std::unique_ptr<hal::host::PcapWriter> pcap;
  std::unique_ptr<hal::host::CapturingFramePort> capture;
  hal::FramePort* port = network.device.get();
  if (!options.pcap_path.empty()) {
    auto opened = hal::host::PcapWriter::Open(options.pcap_path, &error);
    if (!opened.ok()) return CardExit::kFailed;
    pcap = std::move(opened.value());
    capture = std::make_unique<hal::host::CapturingFramePort>(*port, *pcap);
    port = capture.get();
  }

  hal::host::LoggingLeds logged_leds(clock, hal::host::LoggingLeds::FileSink(stderr));
  firmware::LedMirror leds(logged_leds);  // what the web page shows
  ResetRequest reset;

  firmware::BindLwipPlatform(clock, random);
  lwip_init();
  // The netif starts without an address: the addressing installs one once the configuration is read
  // from the inverter (c504-c516, c081-c096) and ACD has checked it (docs/network.md "Addressing").
  firmware::CardNetif netif(*port);
  netif.Start(firmware::Ipv4Config{}, nullptr);
  firmware::CardAddressing addressing(netif, clock, random);
  netif.SetObserver(&addressing);

  firmware::EventLoop loop(clock, waiter, netif);
  loop.AddService(*inverter).IgnoreError();  // stores the inverter's EEPROM image when due

  // The drive link and the front ends (docs/drive-link.md, docs/modbus.md). The register proxy owns the
  // link on the card's end of the serial line; the Modbus server reaches the drive only through it; the
  // publisher keeps c502-c536 and the option-board data current and hands each configuration read from
  // the inverter to the Modbus service (c500 opens or closes port 502).
  drive_link::RegisterProxy proxy(*card_serial, drive_link::LinkConfig{}, drive_link::ProxyConfig{});
  firmware::PolledService<drive_link::RegisterProxy> proxy_service(proxy);
  modbus::Server modbus_server(proxy, proxy, proxy);
  firmware::ModbusTcpService modbus_service(modbus_server, clock, {.port = 502, .keepalive = options.tcp_keepalive});

  // The EtherNet/IP side (docs/ethernetip.md "In the firmware"): CIP objects on the card's providers,
  // the encapsulation server on TCP/UDP 44818, class 1 I/O on UDP 2222 with the drive assemblies, the
  // drive objects. Settings the CIP objects store go to the inverter's c-parameters through the
  // parameter writer, or to the card's own store.
  firmware::ParameterWriter parameter_writer(proxy);
  firmware::EtherNetIpCard eip_card({*port, netif, addressing, proxy, parameter_writer, *store.value(), reset, random, clock},
                                    {.keepalive = options.tcp_keepalive, .connections = {}});
  if (base::Status started = eip_card.Start(); !started.ok()) {
    error = std::string("EtherNet/IP: ") + base::StatusName(started);
    return CardExit::kFailed;
  }
  // TCP/IP attribute 10 as stored in the card (a change applies at the next reset).
  addressing.SetAcdEnabled(eip_card.tcpip().StoredSettings().select_acd);
  // MS, NS and LNK from one model; the power-up test runs from here.
  firmware::CardIndicators indicators({*port, proxy, addressing, &eip_card.connections()}, leds, clock.NowMicros());

  // The web server on port 80 (docs/web.md), open while c554 = 1, whatever the protocol. Its passwords
  // are the card's own (NV store), not the inverter's.
  web::PasswordStore passwords(*store.value(), kNvWebPasswords, random);
  if (const auto loaded = passwords.Load(); !loaded.ok()) {
    std::fprintf(stderr, "web: cannot store the default passwords (%s); they are in force anyway\n",
                 base::StatusName(loaded.status()));
  }
  web::AccessControl access(passwords, random);

  // Every configuration read from the inverter goes to these (c500 picks the protocol whose ports open,
  // c554 the web server's).
  std::array<firmware::ConfigurableService*, 6> front_ends{&modbus_service};
  std::copy(eip_card.front_ends().begin(), eip_card.front_ends().end(), front_ends.begin() + 1);
  firmware::CardStatusPublisher publisher(proxy, modbus_server, front_ends, netif, kFirmwareVersion,
                                          &eip_card.identity_sink());
  firmware::CardWebStatus web_status({proxy, publisher, netif, leds, eip_card.connections()});
  firmware::WebApplication web_application({access, proxy, proxy, proxy, web_status});
  web::HttpServer http_server(web_application);
  firmware::WebService web_service(http_server, clock, {.port = 80, .keepalive = options.tcp_keepalive});
  web_status.SetWebCounters(http_server, web_service);
  publisher.AddFrontEnd(web_service).IgnoreError();
  publisher.AddFrontEnd(addressing).IgnoreError();
  publisher.AddFrontEnd(indicators).IgnoreError();
  proxy.SetConfigListener(&publisher);
  if (base::Status started = proxy.Start(clock.NowMicros()); !started.ok()) {
    error = std::string("drive link: ") + base::StatusName(started);
    return CardExit::kFailed;
  }
  loop.AddService(proxy_service).IgnoreError();
  loop.AddService(modbus_service).IgnoreError();
  for (firmware::Service* service : eip_card.services()) loop.AddService(*service).IgnoreError();
  loop.AddService(parameter_writer).IgnoreError();
  loop.AddService(web_application).IgnoreError();
  loop.AddService(web_service).IgnoreError();
  loop.AddService(publisher).IgnoreError();
  loop.AddService(addressing).IgnoreError();
  loop.AddService(indicators).IgnoreError();

  SignalSource signals;
  waiter.Register(signals);

  const DriveReport drive_report{proxy, modbus_server, modbus_service, eip_card, parameter_writer};
  const NetworkReport network_report{netif, addressing, indicators};
  const PoolReport pool_report{modbus_service, modbus_server, eip_card, proxy, parameter_writer,
                               web_service,    http_server,   access,   clock};
  CardReport report{netif, loop, logged_leds, waiter, &drive_report, &network_report, &pool_report};
  AddressAnnouncer announcer(network_report);
  std::unique_ptr<ControlServer> control;
  if (!options.sim_control_path.empty()) {
    control = std::make_unique<ControlServer>(
        options.sim_control_path, [&](std::string_view command, std::string& reply) {
          HandleControlCommand(command, reply, report, network.set_plugged, reset, *inverter);
        });
    if (!control->Start(error)) return CardExit::kFailed;
    waiter.Register(*control);
  }

  bool ready_printed = false;
  hal::Micros reset_deadline = hal::kNever;
  while (!signals.stop_requested()) {
    if (reset.pending().has_value()) {
      // A reset waits, boundedly, for settings still on their way into the inverter's EEPROM (a
      // Set_Attribute_Single followed by the Identity Reset must not lose the setting).
      const hal::Micros now = clock.NowMicros();
      if (reset_deadline == hal::kNever) reset_deadline = now + kResetDrainLimit;
      if (parameter_writer.pending() == 0 || now >= reset_deadline) break;
    }
    loop.RunOnce();
    announcer.Check();
    // Ready once the front ends run with the configuration read from the inverter (or the drive link
    // has given up: e-23, the card runs without a drive) and the addressing is past its checks: an
    // address in use, a BOOTP/DHCP sequence running (its result shows in an "address" line), a conflict,
    // or no usable address configured.
    const bool drive_settled = proxy.config_loaded() || proxy.link().state() == drive_link::LinkState::kFault;
    const bool address_settled = addressing.phase() != firmware::AddressPhase::kProbing &&
                                 (addressing.configured() || proxy.link().state() == drive_link::LinkState::kFault);
    if (!ready_printed && netif.link_up() && drive_settled && address_settled) {
      std::printf("ready ip=%s mac=%s net=%s %s control=%s state=%s drive=%s\n",
                  FormatIpv4(addressing.active().address).c_str(),
                  FormatMac(mac).c_str(), options.net == NetKind::kTap ? "tap" : "loopback",
                  (options.net == NetKind::kTap ? TapEndpoints(FormatIpv4(addressing.active().address))
                                                : network.endpoints).c_str(),
                  options.sim_control_path.empty() ? "-" : options.sim_control_path.c_str(),
                  options.state_dir.c_str(), drive_link::LinkStateName(proxy.link().state()));
      std::fflush(stdout);
      ready_printed = true;
    }
  }
  inverter->SaveIfChanged();  // at exit and before a restart: the drive keeps what it was told
  if (reset.pending() == hal::ResetKind::kFactoryDefaults) {
    // Identity Reset type 1: the card's own settings go back to the out-of-box defaults. The factory
    // data (MAC) stays; the configuration in the inverter (c-parameters) is the drive's, not the card's.
    store.value()->Erase(firmware::kNvTcpIpExtras).IgnoreError();
  }
  if (reset.pending().has_value()) {
    // Let the control socket deliver its answer before the process image is replaced.
    waiter.WaitUntil(clock.NowMicros());
    return CardExit::kRestart;
  }
  return CardExit::kStopped;
}

}  // namespace host
