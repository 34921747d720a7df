// libFuzzer target for the Modbus TCP server core (modbus/): arbitrary byte streams on two connections,
// with the drive's completions, time, answer draining, closes and drive faults steered by the input.
//
// Input: byte 0 is the configuration (bit 0 c604 IO scanning, bit 1 a master address, bit 2 c523 on,
// bit 3 the second client is the master); then operations, each an opcode byte and its operands:
//   0,1  feed up to 64 stream bytes to connection 0/1 (operand: length)
//   2    the drive completes every access started        3  time advances (operand x 10 ms)
//   4,5  connection 0/1 hands over answers (operand: how many bytes)
//   6    connection 0/1 closes and reopens (operand bit 0)
//   7    drive faults (operand: busy, link down, an error on 0009)
// Oracle: answers are whole ADUs with protocol id 0, in request order, each echoing its request's
// transaction id and unit id, no more answers than requests; exception codes are 01-04 or 0A;
// buffers never exceed their bounds; a connection that must close serves nothing more.
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "modbus/mbap.h"
#include "modbus_fakes.h"

namespace {

using modbus::test::Bytes;

void Require(bool condition) {
  if (!condition) __builtin_trap();
}

// The headers of the whole ADUs in a stream, up to the first header that cannot be framed.
std::vector<modbus::MbapHeader> Frames(std::span<const std::uint8_t> stream, std::vector<Bytes>* pdus) {
  std::vector<modbus::MbapHeader> headers;
  while (true) {
    const modbus::FrameResult frame = modbus::FindFrame(stream);
    if (frame.check != modbus::FrameCheck::kComplete) break;
    headers.push_back(frame.header);
    if (pdus != nullptr) {
      const auto pdu = modbus::PduOf(stream.first(frame.adu_length));
      pdus->emplace_back(pdu.begin(), pdu.end());
    }
    stream = stream.subspan(frame.adu_length);
  }
  return headers;
}

struct Client {
  modbus::ConnectionId id = 0xFF;
  Bytes taken;     // every byte the server took
  Bytes answered;  // every answer byte handed over
};

void Check(const Client& client) {
  const std::vector<modbus::MbapHeader> requests = Frames(client.taken, nullptr);
  std::vector<Bytes> pdus;
  const std::vector<modbus::MbapHeader> answers = Frames(client.answered, &pdus);
  Require(answers.size() <= requests.size());
  // Every answer byte belongs to a whole answer.
  std::size_t answer_bytes = 0;
  for (const modbus::MbapHeader& header : answers) answer_bytes += 6 + header.length;
  Require(answer_bytes == client.answered.size());
  for (std::size_t i = 0; i < answers.size(); ++i) {
    Require(answers[i].protocol_id == 0);
    Require(answers[i].transaction_id == requests[i].transaction_id);
    Require(answers[i].unit_id == requests[i].unit_id);
    const Bytes& pdu = pdus[i];
    Require(!pdu.empty());
    if ((pdu[0] & 0x80) != 0) {
      Require(pdu.size() == 2);
      Require((pdu[1] >= 0x01 && pdu[1] <= 0x04) || pdu[1] == 0x0A);
    }
  }
}

class Run {
 public:
  explicit Run(std::uint8_t configuration) {
    config::CardConfig config;
    config.io_scanning = (configuration & 0x01) != 0;
    if ((configuration & 0x02) != 0) config.modbus_master = modbus::test::kOtherAddress;
    config.timeout_tenths = (configuration & 0x04) != 0 ? 5 : 0;
    h_.server.Configure(config);
    h_.drive.registers = {{0x0009, 100}, {0x0010, 200}, {0xFA06, 0}, {0xFA07, 0}, {0xFD01, 0x4000}};
    h_.scanner.targets = {0xFA06};
    peers_[0] = modbus::test::kClientAddress;
    peers_[1] = (configuration & 0x08) != 0 ? modbus::test::kOtherAddress : modbus::test::kClientAddress;
    for (std::size_t i = 0; i < clients_.size(); ++i) Open(i);
  }

  void Feed(std::size_t which, std::span<const std::uint8_t> bytes) {
    Client& client = clients_[which];
    const bool closing = h_.server.MustClose(client.id);
    const std::size_t before = h_.server.PendingOutput(client.id).size();
    const std::size_t taken = h_.server.Receive(client.id, bytes, h_.now);
    Require(taken <= bytes.size());
    if (closing) Require(h_.server.PendingOutput(client.id).size() == before);
    client.taken.insert(client.taken.end(), bytes.begin(), bytes.begin() + static_cast<std::ptrdiff_t>(taken));
    Bounds(client);
  }

  void Drain(std::size_t which, std::size_t count) {
    Client& client = clients_[which];
    const std::span<const std::uint8_t> out = h_.server.PendingOutput(client.id);
    count = count < out.size() ? count : out.size();
    client.answered.insert(client.answered.end(), out.begin(), out.begin() + static_cast<std::ptrdiff_t>(count));
    h_.server.ConsumeOutput(client.id, count, h_.now);
    Bounds(client);
  }

  void CompleteDrive() {
    h_.drive.Poll();
    for (const Client& client : clients_) Bounds(client);
  }

  void Advance(hal::Micros delta) {
    h_.now += delta;
    h_.server.Poll(h_.now);
    // Whatever was due has been done: the loop never has to come back at once (no spinning).
    Require(h_.server.NextDeadline() > h_.now);
  }

  void Reopen(std::size_t which) {
    Finish(which);
    h_.server.Close(clients_[which].id);
    Open(which);
  }

  void Faults(std::uint8_t operand) {
    h_.drive.busy_next = operand & 0x03;
    h_.drive.link_down = (operand & 0x04) != 0;
    if ((operand & 0x08) != 0) {
      h_.drive.errors[0x0009] = static_cast<drive_link::AccessError>((operand >> 4) % 9);
    } else {
      h_.drive.errors.clear();
    }
  }

  void Finish(std::size_t which) {
    Drain(which, modbus::kAnswerBufferBytes);
    Check(clients_[which]);
  }

  std::size_t client_count() const { return clients_.size(); }

 private:
  void Open(std::size_t which) {
    const base::Result<modbus::ConnectionId> id = h_.server.Open(peers_[which], h_.now);
    Require(id.ok());
    clients_[which] = Client{*id, {}, {}};
  }

  void Bounds(const Client& client) {
    Require(h_.server.PendingOutput(client.id).size() <= modbus::kAnswerBufferBytes);
    Require(h_.server.open_connections() == clients_.size());
  }

  modbus::test::ServerHarness h_;
  std::array<base::Ipv4Address, 2> peers_{};
  std::array<Client, 2> clients_{};
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  Run run(data[0]);
  std::span<const std::uint8_t> input(data + 1, size - 1);
  auto next = [&input]() -> std::uint8_t {
    if (input.empty()) return 0;
    const std::uint8_t byte = input[0];
    input = input.subspan(1);
    return byte;
  };
  while (!input.empty()) {
    const std::uint8_t opcode = next() % 8;
    const std::uint8_t operand = next();
    switch (opcode) {
      case 0:
      case 1: {
        const std::size_t length = operand % 65;
        const std::span<const std::uint8_t> bytes = input.first(length < input.size() ? length : input.size());
        input = input.subspan(bytes.size());
        run.Feed(opcode, bytes);
        break;
      }
      case 2:
        run.CompleteDrive();
        break;
      case 3:
        run.Advance(static_cast<hal::Micros>(operand) * 10 * hal::kMicrosPerMilli);
        break;
      case 4:
      case 5:
        run.Drain(opcode - 4u, operand);
        break;
      case 6:
        run.Reopen(operand & 0x01);
        break;
      default:
        run.Faults(operand);
        break;
    }
  }
  for (std::size_t i = 0; i < run.client_count(); ++i) run.Finish(i);
  return 0;
}
