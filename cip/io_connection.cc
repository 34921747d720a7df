#include "cip/io_connection.h"

#include "cip/cpf.h"

namespace cip {

base::Result<ReceivedIoDatagram> ParseIoDatagram(std::span<const std::uint8_t> bytes) {
  const base::Result<CpfPacket> packet = DecodeCpf(bytes);
  if (!packet.ok()) return packet.status();
  if (packet->count != 2) return base::InvalidArgument();
  const CpfItem& address = packet->items[0];
  const CpfItem& data = packet->items[1];
  if (address.type != static_cast<std::uint16_t>(CpfItemType::kSequencedAddress) || address.data.size() != 8 ||
      data.type != static_cast<std::uint16_t>(CpfItemType::kConnectedData)) {
    return base::InvalidArgument();
  }
  base::ByteReader in(address.data);
  ReceivedIoDatagram datagram;
  datagram.connection_id = in.U32Le();
  datagram.encapsulation_sequence = in.U32Le();
  datagram.data = data.data;
  return datagram;
}

void EncodeIoDatagram(std::uint32_t connection_id, std::uint32_t encapsulation_sequence, std::uint16_t sequence_count,
                      std::span<const std::uint8_t> data, base::ByteWriter& out) {
  out.U16Le(2);  // item count
  const std::size_t address_at = BeginCpfItem(out, CpfItemType::kSequencedAddress);
  out.U32Le(connection_id);
  out.U32Le(encapsulation_sequence);
  FinishCpfItem(out, address_at);
  const std::size_t data_at = BeginCpfItem(out, CpfItemType::kConnectedData);
  out.U16Le(sequence_count);
  out.Bytes(data);
  FinishCpfItem(out, data_at);
}

hal::Micros NextProductionSlot(hal::Micros due, hal::Micros api, hal::Micros now, std::uint32_t& missed) {
  if (api == 0) return now + 1;  // cannot happen: an API is at least the RPI floor
  hal::Micros next = due + api;
  if (next > now) return next;
  // Late by at least one period: skip the slots that already passed (one packet now, none of them).
  const hal::Micros skipped = (now - next) / api + 1;
  missed += static_cast<std::uint32_t>(skipped);
  return next + skipped * api;
}

}  // namespace cip
