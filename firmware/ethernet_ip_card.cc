#include "ethernet_ip_card.h"

#include "cip/identity_object.h"

namespace firmware {
namespace {

// One name for either model's EDS (its [Device] ProdCode and ProdName say which; docs/eds.md "Serving"):
// the File object's attribute 4 is fixed when the card starts, before the model is read from FB05.
constexpr std::string_view kEdsFileName = "IPE002Z.eds";

}  // namespace

cip::drive::DriveStatus EtherNetIpCard::ProxyDriveStatus::CurrentDriveStatus() const {
  cip::drive::DriveStatus status;
  status.known = proxy_.drive_status_known() && proxy_.link().state() != drive_link::LinkState::kFault;
  status.fd01 = proxy_.drive_status();
  return status;
}

EtherNetIpCard::EtherNetIpCard(const EtherNetIpCardDevices& devices, const EtherNetIpCardOptions& options)
    : identity_(devices.port, devices.proxy),
      tcpip_(devices.netif, devices.addressing, devices.writer, devices.store),
      links_(devices.netif, devices.writer),
      dlr_(devices.ring),
      qos_(devices.store),
      qos_object_(qos_),
      device_({identity_, tcpip_, links_, devices.reset, devices.random}),
      connections_(device_.router(), identity_, devices.random, options.connections),
      supervisor_(connections_, devices.proxy, devices.clock),
      ownership_(connections_),
      control_lock_(connections_),
      drive_status_(devices.proxy),
      journal_(devices.proxy),
      runtime_({devices.proxy, devices.proxy, devices.proxy, drive_status_, ownership_}),
      assemblies_(runtime_),
      control_supervisor_(runtime_),
      ac_dc_drive_(runtime_, journal_),
      motor_data_(journal_),
      parameters_64_(cip::drive::ParameterClass::k64, journal_),
      parameters_65_(cip::drive::ParameterClass::k65, journal_),
      parameters_0f_(journal_, identity_),
      eds_(identity_),
      served_eds_(options.eds_override != nullptr
                      ? *options.eds_override
                      : cip::ServedFile{&eds_, kEdsFileName, cip::kMajorRevision, cip::kMinorRevision}),
      file_(served_eds_),
      drive_profile_config_(runtime_),
      eip_(device_.encapsulation(), devices.clock,
           {.keepalive = options.keepalive, .tos = cip::TosOfDscp(qos_.active()[cip::QosAttribute::kDscpExplicit])}),
      io_(connections_, devices.clock, tcpip_),
      assemblies_service_(assemblies_),
      front_ends_{&eip_, &io_, &tcpip_, &links_, &drive_profile_config_},
      services_{&eip_, &io_, &assemblies_service_} {
  io_.set_qos(&qos_.active());
  devices.netif.SetQosTagging(&qos_.active());
}

base::Status EtherNetIpCard::Start() {
  if (base::Status status = cip::AttachConnectionManager(device_, connections_); !status.ok()) return status;
  if (base::Status status = assemblies_.Register(device_.assemblies()); !status.ok()) return status;
  for (cip::CipObject* object : {&control_supervisor_.object(), &ac_dc_drive_.object(), &motor_data_.object(),
                                 &parameters_64_.object(), &parameters_65_.object(), &parameters_0f_.object(),
                                 &file_.object(), &dlr_.object(),
                                 &qos_object_.object()}) {
    if (base::Status status = device_.objects().Register(*object); !status.ok()) return status;
  }
  device_.encapsulation().set_request_lifecycle(&journal_);
  device_.router().set_guard(&control_lock_);
  connections_.set_io_application(&assemblies_);
  connections_.set_multicast_provider(&tcpip_);
  connections_.set_events(&supervisor_);
  supervisor_.set_listener(this);
  identity_.set_connections(&connections_);
  return base::OkStatus();
}

}  // namespace firmware
