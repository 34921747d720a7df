#include "card_records.h"

namespace firmware {

base::MacAddress LoadOrCreateMac(hal::NvStore& store, hal::RandomSource& random) {
  base::MacAddress::Octets mac{};
  const base::Result<std::size_t> read = store.Read(kNvFactoryMac, mac);
  if (read.ok() && *read == mac.size()) return base::MacAddress(mac);
  random.Fill(mac);
  mac[0] = static_cast<std::uint8_t>((mac[0] & 0xFC) | 0x02);  // unicast, locally administered
  store.Write(kNvFactoryMac, mac).IgnoreError();
  return base::MacAddress(mac);
}

}  // namespace firmware
