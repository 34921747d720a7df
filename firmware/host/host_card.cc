#include "host_card.h"

#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include <cstring>

#include <cstdio>
#include <fstream>
#include <iterator>
#include <memory>
#include <optional>
#include <string_view>

#include "address_plan.h"
#include "capturing_frame_port.h"
#include "card.h"
#include "card_control.h"
#include "card_lines.h"
#include "card_records.h"
#include "cip/byte_span_file.h"
#include "control_server.h"
#include "file_nv_store.h"
#include "host_clock.h"
#include "host_random.h"
#include "logging_leds.h"
#include "pcap_writer.h"
#include "poll_waiter.h"
#include "signal_source.h"
#include "sim_inverter.h"
#include "slirp_frame_port.h"
#include "socket_serial_port.h"
#include "stderr_console.h"
#include "tap_frame_port.h"

namespace host {
namespace {

// The simulated inverter's EEPROM store check, polled by the card's loop like the card's own services.
class InverterStoreCheck final : public firmware::Service {
 public:
  explicit InverterStoreCheck(sim::SimulatedInverter& inverter) : inverter_(inverter) {}
  void Poll(hal::Micros now) override { inverter_.Poll(now); }
  hal::Micros NextDeadline() const override { return inverter_.NextDeadline(); }

 private:
  sim::SimulatedInverter& inverter_;
};

// The network port as built from --net, with what the control socket and the ready line need.
struct NetworkPort {
  std::unique_ptr<hal::FramePort> device;
  hal::host::PollSource* poll_source = nullptr;
  std::function<base::Status(hal::PortId, bool)> set_plugged;
  std::string endpoints;  // "modbus=... enip=... io=... http=..." (loopback; TAP: from the address in use)
};

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

bool OpenNetworkPort(const HostOptions& options, const base::MacAddress& mac, const hal::Clock& clock,
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

// A connected stream socket to the inverter's serial line at `path`; -1 when nothing listens there.
int ConnectUnixStream(const std::string& path) {
  sockaddr_un address{};
  address.sun_family = AF_UNIX;
  if (path.size() >= sizeof(address.sun_path)) return -1;
  std::memcpy(address.sun_path, path.data(), path.size());
  const int fd = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
  if (fd < 0) return -1;
  if (::connect(fd, reinterpret_cast<const sockaddr*>(&address), sizeof(address)) != 0) {
    ::close(fd);
    return -1;
  }
  return fd;
}

}  // namespace

CardExit RunHostCard(const HostOptions& options, std::string& error) {
  hal::host::HostClock clock;
  hal::host::HostRandom random;
  hal::host::PollWaiter waiter(clock);

  auto store = hal::host::FileNvStore::Open(options.state_dir + "/card", &error);
  if (!store.ok()) return CardExit::kFailed;
  const base::MacAddress mac = firmware::LoadOrCreateMac(*store.value(), random);

  // The serial line to the inverter: with --drive, a connection to an inverter in another process;
  // otherwise a socket pair, the card's UART on one end and the simulated inverter on the other
  // (docs/simulator.md "In ipe002z-host").
  std::unique_ptr<hal::host::SocketSerialPort> inverter_serial;
  // The card's end of the line, for the drive link. Registered with the waiter so reply bytes wake
  // the loop; whoever holds this end must read them, or poll() would report them forever.
  std::unique_ptr<hal::host::SocketSerialPort> card_serial;
  std::unique_ptr<sim::SimulatedInverter> inverter;
  if (!options.drive_socket.empty()) {
    const int fd = ConnectUnixStream(options.drive_socket);
    if (fd < 0) {
      error = "cannot connect to the inverter at unix:" + options.drive_socket;
      return CardExit::kFailed;
    }
    card_serial = std::make_unique<hal::host::SocketSerialPort>(fd);
  } else {
    auto line = hal::host::SocketSerialPort::CreatePair();
    if (!line.ok()) {
      error = "cannot create the serial line to the simulated inverter";
      return CardExit::kFailed;
    }
    inverter_serial = std::move(line.value().inverter);
    card_serial = std::move(line.value().card);

    sim::SimInverterConfig inverter_config;
    inverter_config.model = options.model;
    inverter_config.directory = options.state_dir + "/inverter";
    inverter_config.presets = options.params;
    inverter_config.server = sim::ServerConfigFromOptions(options);
    inverter_config.program = "ipe002z-host";
    inverter = sim::SimulatedInverter::Create(inverter_config, *inverter_serial, clock, stderr, error);
    if (!inverter) return CardExit::kFailed;
    // --ip: the address plan keyed into the inverter before power-up, at every start.
    if (options.ip_given &&
        !sim::KeyManualAddress(*inverter, {options.ip, options.netmask, options.gateway}, error)) {
      return CardExit::kFailed;
    }
    waiter.Register(*inverter_serial);         // request bytes wake the inverter
    waiter.Register(inverter->poll_source());  // its reply and receive timers
  }
  waiter.Register(*card_serial);  // reply bytes wake the card

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
  hal::host::StderrConsole console;

  // --eds: the file's bytes, read once (host code may allocate at start-up).
  std::vector<std::uint8_t> eds_bytes;
  std::optional<cip::ByteSpanFile> eds_content;
  std::string eds_name;
  std::optional<cip::ServedFile> eds;
  if (!options.eds_path.empty()) {
    std::ifstream in(options.eds_path, std::ios::binary);
    if (!in) {
      error = "--eds: cannot read " + options.eds_path;
      return CardExit::kFailed;
    }
    eds_bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    eds_content.emplace(eds_bytes);
    eds_name = options.eds_path.substr(options.eds_path.find_last_of('/') + 1);
    eds = cip::ServedFile{&*eds_content, eds_name, 1, 0};
  }

  // The card itself: the same composition a board builds (firmware/card/card.h).
  auto card = std::make_unique<firmware::Card>(
      firmware::CardDevices{.clock = clock,
                            .waiter = waiter,
                            .port = *port,
                            .drive_serial = *card_serial,
                            .store = *store.value(),
                            .leds = logged_leds,
                            .random = random,
                            .diagnostics = console,
                            .fatal = console,
                            .watchdog = nullptr},
      firmware::CardOptions{.keepalive = options.tcp_keepalive, .eds = eds ? &*eds : nullptr});
  std::optional<InverterStoreCheck> store_check;
  if (inverter) {
    store_check.emplace(*inverter);
    card->AddService(*store_check, firmware::PollWhen::kDueOnly).IgnoreError();  // stores the inverter's EEPROM image when due
  }
  if (base::Status started = card->Start(); !started.ok()) {
    error = std::string(card->failed_part()) + ": " + base::StatusName(started);
    return CardExit::kFailed;
  }
  if (!card->passwords_stored()) {
    std::fprintf(stderr, "web: cannot store the default passwords; they are in force anyway\n");
  }

  hal::host::SignalSource signals;
  waiter.Register(signals);

  CardReport report{card->netif(), card->loop(), logged_leds, waiter, card.get()};
  std::unique_ptr<hal::host::ControlServer> control;
  if (!options.sim_control_path.empty()) {
    control = std::make_unique<hal::host::ControlServer>(
        options.sim_control_path, [&](std::string_view command, std::string& reply) {
          HandleControlCommand(command, reply, report, network.set_plugged, card->reset_control(), inverter.get());
        });
    if (!control->Start(error)) return CardExit::kFailed;
    waiter.Register(*control);
  }

  bool ready_printed = false;
  std::optional<hal::ResetKind> reset;
  while (!signals.stop_requested() && !reset.has_value()) {
    reset = card->RunOnce();
    if (card->TakeAddressChange()) {
      firmware::TextLine address;
      firmware::DescribeAddress(card->addressing(), address);
      std::printf("address %.*s\n", static_cast<int>(address.view().size()), address.view().data());
      std::fflush(stdout);
    }
    if (!ready_printed && card->Readiness().ready()) {
      firmware::TextLine identity;
      firmware::DescribeIdentity(*card, identity);
      std::string endpoints = network.endpoints;
      if (options.net == NetKind::kTap) {
        firmware::TextLine text;
        firmware::DescribeEndpoints(card->addressing().active().address, text);
        endpoints = std::string(text.view());
      }
      std::printf("ready %.*s net=%s %s control=%s state=%s drive=%s\n", static_cast<int>(identity.view().size()),
                  identity.view().data(), options.net == NetKind::kTap ? "tap" : "loopback", endpoints.c_str(),
                  options.sim_control_path.empty() ? "-" : options.sim_control_path.c_str(),
                  options.state_dir.c_str(), drive_link::LinkStateName(card->proxy().link().state()));
      std::fflush(stdout);
      ready_printed = true;
    }
  }
  if (inverter) inverter->SaveIfChanged();  // at exit and before a restart: the drive keeps what it was told
  if (reset.has_value()) {
    // Let the control socket deliver its answer before the process image is replaced.
    waiter.WaitUntil(clock.NowMicros());
    return CardExit::kRestart;
  }
  return CardExit::kStopped;
}

}  // namespace host
