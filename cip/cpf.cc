#include "cip/cpf.h"

namespace cip {
namespace {

constexpr std::uint16_t Type(CpfItemType type) { return static_cast<std::uint16_t>(type); }

}  // namespace

base::Result<CpfPacket> DecodeCpf(std::span<const std::uint8_t> bytes) {
  base::ByteReader in(bytes);
  const std::uint16_t count = in.U16Le();
  if (!in.ok()) return base::OutOfRange();
  // Each item needs at least its 4-byte header: a count that cannot fit is refused before looping.
  if (count > kMaxCpfItems) return base::InvalidArgument();
  CpfPacket packet;
  for (std::size_t i = 0; i < count; ++i) {
    CpfItem& item = packet.items[i];
    item.type = in.U16Le();
    const std::uint16_t length = in.U16Le();
    item.data = in.Bytes(length);
    if (!in.ok()) return base::OutOfRange();
  }
  if (!in.empty()) return base::InvalidArgument();
  packet.count = count;
  return packet;
}

base::Result<SendDataCommand> DecodeSendDataCommand(std::span<const std::uint8_t> bytes) {
  base::ByteReader in(bytes);
  SendDataCommand command;
  command.interface_handle = in.U32Le();
  command.timeout = in.U16Le();
  if (!in.ok()) return base::OutOfRange();
  const base::Result<CpfPacket> packet = DecodeCpf(in.Rest());
  if (!packet.ok()) return packet.status();
  command.packet = *packet;
  return command;
}

base::Result<UnconnectedMessage> ParseUnconnectedMessage(const CpfPacket& packet) {
  if (packet.count < 2) return base::InvalidArgument();
  const CpfItem& address = packet.items[0];
  const CpfItem& data = packet.items[1];
  if (address.type != Type(CpfItemType::kNullAddress) || !address.data.empty()) return base::InvalidArgument();
  if (data.type != Type(CpfItemType::kUnconnectedData)) return base::InvalidArgument();
  UnconnectedMessage message;
  message.request = data.data;
  for (std::size_t i = 2; i < packet.count; ++i) {
    const CpfItem& item = packet.items[i];
    if (item.data.size() != SocketAddress::kWireSize) return base::InvalidArgument();
    base::ByteReader in(item.data);
    const SocketAddress address_info = DecodeSocketAddress(in);
    if (item.type == Type(CpfItemType::kSockaddrOtoT) && !message.o_to_t) {
      message.o_to_t = address_info;
    } else if (item.type == Type(CpfItemType::kSockaddrTtoO) && !message.t_to_o) {
      message.t_to_o = address_info;
    } else {
      return base::InvalidArgument();  // another item type, or the same direction twice
    }
  }
  return message;
}

base::Result<ConnectedMessage> ParseConnectedMessage(const CpfPacket& packet) {
  if (packet.count != 2) return base::InvalidArgument();
  const CpfItem& address = packet.items[0];
  const CpfItem& data = packet.items[1];
  if (address.type != Type(CpfItemType::kConnectedAddress) || address.data.size() != 4) {
    return base::InvalidArgument();
  }
  if (data.type != Type(CpfItemType::kConnectedData) || data.data.size() < 2) return base::InvalidArgument();
  base::ByteReader address_in(address.data);
  base::ByteReader data_in(data.data);
  ConnectedMessage message;
  message.connection_id = address_in.U32Le();
  message.sequence_count = data_in.U16Le();
  message.request = data_in.Rest();
  return message;
}

std::size_t BeginCpfItem(base::ByteWriter& out, CpfItemType type) {
  out.U16Le(Type(type));
  const std::size_t length_at = out.size();
  out.U16Le(0);
  return length_at;
}

void FinishCpfItem(base::ByteWriter& out, std::size_t length_at) {
  // The writer's capacity is far below 64 KiB, so the length always fits 16 bits.
  out.PatchU16Le(length_at, static_cast<std::uint16_t>(out.size() - length_at - 2));
}

void EncodeSockaddrItem(base::ByteWriter& out, CpfItemType type, const SocketAddress& address) {
  out.U16Le(Type(type));
  out.U16Le(static_cast<std::uint16_t>(SocketAddress::kWireSize));
  EncodeSocketAddress(address, out);
}

}  // namespace cip
