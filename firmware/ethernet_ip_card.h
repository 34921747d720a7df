// The card's whole EtherNet/IP side, assembled (docs/ethernetip.md "In the firmware"): the CIP objects
// on the card's providers, the Connection Manager with the drive profile's assemblies, the drive
// objects 0x0F/0x28/0x29/0x2A/0x64/0x65 on the deferred-reply journal, the File object 0x37 with the
// card's EDS, the QoS object 0x48 (its values in force mark the I/O and explicit traffic and tag frames),
// the encapsulation server on TCP/UDP 44818 and class 1 I/O on UDP 2222. Device-path code:
// the host and a board build it the same way, from the HAL devices, the netif, the register proxy and the
// parameter writer they already have.
//
// The composition root then:
//   - gives front_ends() to the CardStatusPublisher (each configuration load: c500 opens or closes the
//     ports, the TCP/IP and Ethernet Link objects and the drive profile take the c-parameters), and
//     identity_sink() for FB05/FE08;
//   - adds services() to the event loop.
#pragma once

#include <array>
#include <span>

#include "base/status.h"
#include "card_netif.h"
#include "cip/cip_device.h"
#include "cip/connection_manager.h"
#include "cip/dlr_object.h"
#include "cip/drive/ac_dc_drive_object.h"
#include "cip/drive/cip_parameter_object.h"
#include "cip/drive/control_lock.h"
#include "cip/drive/control_supervisor_object.h"
#include "cip/drive/drive_access_journal.h"
#include "cip/drive/drive_assemblies.h"
#include "cip/drive/drive_profile_runtime.h"
#include "cip/drive/motor_data_object.h"
#include "cip/drive/parameter_object.h"
#include "cip/eds/eds_file.h"
#include "cip/file_object.h"
#include "card_qos.h"
#include "cip/qos_object.h"
#include "cip_connection_supervisor.h"
#include "cip_providers.h"
#include "configurable_service.h"
#include "drive_link/register_proxy.h"
#include "eip_service.h"
#include "event_loop.h"
#include "hal/clock.h"
#include "hal/frame_port.h"
#include "hal/nv_store.h"
#include "hal/random.h"
#include "hal/reset.h"
#include "io_service.h"
#include "parameter_writer.h"
#include "polled_service.h"
#include "tcp_keepalive.h"

namespace firmware {

struct EtherNetIpCardDevices {
  hal::FramePort& port;
  CardNetif& netif;
  CardAddressing& addressing;
  drive_link::RegisterProxy& proxy;
  ParameterWriter& writer;
  hal::NvStore& store;
  hal::ResetControl& reset;
  hal::RandomSource& random;
  const hal::Clock& clock;
  const cip::DlrProvider& ring;  // the DLR object's values (CardRing)
};

struct EtherNetIpCardOptions {
  TcpKeepalive keepalive;
  cip::ConnectionManagerOptions connections;
  // Another file than the card's own EDS for instance 0xC8 and GET /api/eds, outliving the card: the
  // host's --eds, for tests. Null: the EDS generated from the card's tables (docs/eds.md).
  const cip::ServedFile* eds_override = nullptr;
};

class EtherNetIpCard final : private DriveControlListener {
 public:
  EtherNetIpCard(const EtherNetIpCardDevices& devices, const EtherNetIpCardOptions& options);
  EtherNetIpCard(const EtherNetIpCard&) = delete;
  EtherNetIpCard& operator=(const EtherNetIpCard&) = delete;

  // Registers the classes and assemblies. Fails only on a wiring mistake (a class registered twice).
  base::Status Start();

  std::span<ConfigurableService* const> front_ends() { return front_ends_; }
  std::span<Service* const> services() { return services_; }
  // The one of services() whose poll only sends due I/O productions (nothing else follows it).
  const Service* production_service() const { return &io_; }
  DriveIdentitySink& identity_sink() { return identity_; }

  // For the control socket's `stats` and the web page.
  cip::CipDevice& device() { return device_; }
  const cip::EncapsulationServer& encapsulation() const { return device_.encapsulation(); }
  const EipService& eip_service() const { return eip_; }
  const IoService& io_service() const { return io_; }
  const cip::ConnectionManager& connections() const { return connections_; }
  const CardTcpIp& tcpip() const { return tcpip_; }
  const CipConnectionSupervisor& supervisor() const { return supervisor_; }
  const cip::drive::DriveAccessJournal& journal() const { return journal_; }
  const cip::drive::DriveAssemblies& assemblies() const { return assemblies_; }
  const cip::drive::ControlLock& control_lock() const { return control_lock_; }
  // What the File object 0x37 instance 0xC8 and GET /api/eds serve: the EDS of the inverter model the
  // card has detected (docs/eds.md "Serving"), or the options' override.
  const cip::ServedFile& served_eds() const { return served_eds_; }

 private:
  // The drive status the Control Supervisor follows: FD01 from the cyclic exchange, unknown while the
  // configuration is not loaded or the link is in e-23.
  class ProxyDriveStatus final : public cip::drive::DriveStatusSource {
   public:
    explicit ProxyDriveStatus(const drive_link::RegisterProxy& proxy) : proxy_(proxy) {}
    cip::drive::DriveStatus CurrentDriveStatus() const override;

   private:
    const drive_link::RegisterProxy& proxy_;
  };
  // The drive profile takes f856, cmod, fmod and c001-c006 from each configuration load.
  class DriveProfileConfig final : public ConfigurableService {
   public:
    explicit DriveProfileConfig(cip::drive::DriveProfileRuntime& runtime) : runtime_(runtime) {}
    base::Status Configure(const config::CardConfig& config) override {
      runtime_.SetCardConfig(config);
      return base::OkStatus();
    }

   private:
    cip::drive::DriveProfileRuntime& runtime_;
  };

  // DriveControlListener
  void OnDriveControlLost() override {}
  void OnConnectionsChanged() override { assemblies_.OnConnectionsChanged(); }

  CardIdentity identity_;
  CardTcpIp tcpip_;
  CardEthernetLinks links_;
  cip::DlrObject dlr_;
  CardQos qos_;                   // the values in force mark class 1, explicit traffic and tags
  cip::QosObject qos_object_;
  cip::CipDevice device_;
  cip::ConnectionManager connections_;
  CipConnectionSupervisor supervisor_;
  cip::drive::ConnectionManagerOwnership ownership_;
  cip::drive::ControlLock control_lock_;  // the exclusive-owner write lock (docs/security.md)
  ProxyDriveStatus drive_status_;
  cip::drive::DriveAccessJournal journal_;
  cip::drive::DriveProfileRuntime runtime_;
  cip::drive::DriveAssemblies assemblies_;
  cip::drive::ControlSupervisorObject control_supervisor_;
  cip::drive::AcDcDriveObject ac_dc_drive_;
  cip::drive::MotorDataObject motor_data_;
  cip::drive::ParameterObject parameters_64_;
  cip::drive::ParameterObject parameters_65_;
  cip::drive::CipParameterObject parameters_0f_;  // the parameter table (docs/eds.md)
  cip::eds::DetectedModelEds eds_;                 // generated from the tables, never stored
  const cip::ServedFile served_eds_;
  cip::FileObject file_;
  DriveProfileConfig drive_profile_config_;
  EipService eip_;
  IoService io_;
  PolledService<cip::drive::DriveAssemblies> assemblies_service_;
  std::array<ConfigurableService*, 5> front_ends_;
  std::array<Service*, 3> services_;
};

}  // namespace firmware
