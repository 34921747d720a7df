// libFuzzer target for the QoS object 0x48 and the 802.1Q priority tag (cip/qos_object.h).
// Input: 8 bytes of QoS values (any, also out of range), one byte of spare room after the frame, one byte
// of attribute and a length byte with that many bytes of Set_Attribute_Single data, then the frame.
// Oracles: nothing is read or written outside the buffers (ASan); a tagged frame is the input with
// 81 00, the priority of its DSCP and VLAN ID 0 after the MAC addresses; an untagged one is unchanged;
// whatever Set_Attribute_Single is given, the stored values stay in range and a success stored them.
#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "cip/qos_object.h"
#include "cip_fakes.h"

namespace {

void Require(bool condition) {
  if (!condition) __builtin_trap();
}

void CheckTag(const cip::QosSettings& settings, std::span<const std::uint8_t> frame, std::size_t spare) {
  std::vector<std::uint8_t> buffer(frame.begin(), frame.end());
  buffer.resize(frame.size() + spare, 0xA5);
  const std::size_t length = cip::InsertPriorityTag(settings, buffer, frame.size());
  if (length == frame.size()) {
    Require(std::equal(frame.begin(), frame.end(), buffer.begin()));
    return;
  }
  Require(length == frame.size() + cip::kVlanTagBytes && settings.tag_enabled());
  const int priority = cip::PriorityOfDscp(settings, static_cast<std::uint8_t>(frame[15] >> 2));
  Require(priority >= 0 && priority <= 7);
  Require(std::equal(frame.begin(), frame.begin() + 12, buffer.begin()));
  Require(buffer[12] == 0x81 && buffer[13] == 0x00 && buffer[14] == (priority << 5) && buffer[15] == 0x00);
  Require(std::equal(frame.begin() + 12, frame.end(), buffer.begin() + 16));
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 11) return 0;
  cip::QosSettings settings;
  std::copy(data, data + cip::kQosAttributes, settings.values.begin());
  const std::size_t spare = data[8] % 8;
  const std::uint8_t attribute = data[9];
  const std::size_t set_length = std::min<std::size_t>(data[10], size - 11);
  const std::span<const std::uint8_t> set_data(data + 11, set_length);
  CheckTag(settings, std::span<const std::uint8_t>(data + 11 + set_length, size - 11 - set_length), spare);

  cip::test::FakeCard card;
  cip::test::FakeQos qos;
  cip::QosObject object(qos);
  Require(card.cip.objects().Register(object.object()).ok());
  const cip::test::Bytes request = cip::test::Concat({0x10, 0x03, 0x20, 0x48, 0x24, 0x01, 0x30, attribute},
                                                     cip::test::Bytes(set_data.begin(), set_data.end()));
  const cip::test::Bytes reply = card.Ask(request);
  Require(reply.size() >= 4 && reply[0] == 0x90);
  Require(qos.stored.values[0] <= 1);
  Require(std::all_of(qos.stored.values.begin() + 1, qos.stored.values.end(), [](std::uint8_t v) { return v <= 63; }));
  if (reply[2] == 0x00) Require(attribute >= 1 && attribute <= 8 && qos.stored.values[attribute - 1U] == set_data[0]);
  return 0;
}
