#include "cip/cip_device.h"

namespace cip {

CipDevice::CipDevice(const DeviceProviders& providers)
    : tcpip_(providers.tcpip),
      identity_(providers.device, providers.reset),
      message_router_object_(nullptr),
      port_(providers.tcpip),
      tcpip_object_(providers.tcpip),
      ethernet_link_(providers.device, providers.links),
      router_(objects_),
      encapsulation_(router_, *this, providers.random) {
  // Six distinct classes in a registry of kMaxObjectClasses: registration cannot fail.
  for (CipObject* object : {&identity_.object(), &message_router_object_.object(), &assemblies_.object(),
                            &port_.object(), &tcpip_object_.object(), &ethernet_link_.object()}) {
    objects_.Register(*object).IgnoreError();
  }
}

IdentityItem CipDevice::ListIdentity() const {
  const SocketAddress address{SocketAddress::kAfInet, kEncapsulationPort, tcpip_.ActiveConfiguration().ip_address};
  return identity_.ListIdentityItem(address);
}

}  // namespace cip
