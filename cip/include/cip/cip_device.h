// The card's EtherNet/IP side in one object: the standard objects of the manual's chapter 4 (Identity,
// Message Router, Assembly, Port, TCP/IP Interface, Ethernet Link), their registry, the message router
// and the encapsulation server, wired to the providers the firmware implements.
//
// The firmware builds one CipDevice and then:
// - binds encapsulation() to lwIP (TCP and UDP 44818, see encapsulation_server.h);
// - registers further classes in objects() (Connection Manager 0x06, Motor Data 0x28, Control
//   Supervisor 0x29, AC/DC Drive 0x2A, Parameter 0x0F/0x64/0x65) and assembly instances in assemblies();
// - gives the connection manager to encapsulation().set_connected_handler() and its connection count
//   to message_router_object().set_connection_counter().
#pragma once

#include "cip/assembly_object.h"
#include "cip/encapsulation_server.h"
#include "cip/ethernet_link_object.h"
#include "cip/identity_object.h"
#include "cip/message_router.h"
#include "cip/message_router_object.h"
#include "cip/object_model.h"
#include "cip/port_object.h"
#include "cip/providers.h"
#include "cip/tcpip_interface_object.h"
#include "hal/random.h"
#include "hal/reset.h"

namespace cip {

struct DeviceProviders {
  const DeviceInfoProvider& device;
  TcpIpProvider& tcpip;
  EthernetLinkProvider& links;
  hal::ResetControl& reset;
  hal::RandomSource& random;
};

class CipDevice final : public DiscoverySource {
 public:
  explicit CipDevice(const DeviceProviders& providers);
  CipDevice(const CipDevice&) = delete;
  CipDevice& operator=(const CipDevice&) = delete;

  EncapsulationServer& encapsulation() { return encapsulation_; }
  const EncapsulationServer& encapsulation() const { return encapsulation_; }
  MessageRouter& router() { return router_; }
  ObjectRegistry& objects() { return objects_; }
  AssemblyObject& assemblies() { return assemblies_; }
  MessageRouterObject& message_router_object() { return message_router_object_; }

  // ListIdentity: the Identity object's data with the IP address in use and TCP port 44818.
  IdentityItem ListIdentity() const override;

 private:
  const TcpIpProvider& tcpip_;
  IdentityObject identity_;
  MessageRouterObject message_router_object_;
  AssemblyObject assemblies_;
  PortObject port_;
  TcpIpInterfaceObject tcpip_object_;
  EthernetLinkObject ethernet_link_;
  ObjectRegistry objects_;
  MessageRouter router_;
  EncapsulationServer encapsulation_;
};

}  // namespace cip
