#include "cip/assembly_object.h"

#include <algorithm>

namespace cip {
namespace {

constexpr std::array<std::uint16_t, 5> kClassAttributes = {1, 2, 3, 6, 7};
constexpr std::array<std::uint8_t, 1> kClassServices = {kServiceGetAttributeSingle};
constexpr std::array<std::uint8_t, 2> kInstanceServices = {kServiceGetAttributeSingle, kServiceSetAttributeSingle};
constexpr ClassSpec kAssemblyClass = {
    kClassAssembly, 2, kClassAttributes, {}, {}, 7, 4, kClassServices, kInstanceServices,
};
constexpr std::uint16_t kAttributeData = 3;
constexpr std::uint16_t kAttributeSize = 4;
constexpr std::array<AttributeSpec, 2> kInputAttributes = {{
    {kAttributeData, Access::kGet, true},
    {kAttributeSize, Access::kGet, true},
}};
constexpr std::array<AttributeSpec, 2> kOutputAttributes = {{
    {kAttributeData, Access::kGetSet, true},
    {kAttributeSize, Access::kGet, true},
}};

}  // namespace

AssemblyObject::AssemblyObject() : object_(kAssemblyClass, *this) {}

base::Status AssemblyObject::Register(std::uint32_t instance, AssemblyDirection direction,
                                      std::span<std::uint8_t> data, AssemblyWriteHandler* handler) {
  if (instance == 0 || Find(instance) != nullptr || data.size() > 0xFFFF) return base::InvalidArgument();
  if (count_ == entries_.size()) return base::ResourceExhausted();
  entries_[count_++] = Entry{instance, direction, data, handler};
  return base::OkStatus();
}

base::Status AssemblyObject::RegisterInput(std::uint32_t instance, std::span<std::uint8_t> data,
                                           AssemblyInputSource& source) {
  const base::Status registered = Register(instance, AssemblyDirection::kInput, data);
  if (registered.ok()) entries_[count_ - 1].source = &source;
  return registered;
}

const AssemblyObject::Entry* AssemblyObject::Find(std::uint32_t instance) const {
  for (std::size_t i = 0; i < count_; ++i) {
    if (entries_[i].instance == instance) return &entries_[i];
  }
  return nullptr;
}

std::span<std::uint8_t> AssemblyObject::Data(std::uint32_t instance) const {
  const Entry* entry = Find(instance);
  return entry != nullptr ? entry->data : std::span<std::uint8_t>();
}

std::uint32_t AssemblyObject::MaxInstance() const {
  std::uint32_t highest = 0;
  for (std::size_t i = 0; i < count_; ++i) highest = std::max(highest, entries_[i].instance);
  return highest;
}

std::span<const AttributeSpec> AssemblyObject::InstanceAttributes(std::uint32_t instance) const {
  const Entry* entry = Find(instance);
  if (entry == nullptr) return {};
  return entry->direction == AssemblyDirection::kOutput ? std::span<const AttributeSpec>(kOutputAttributes)
                                                        : std::span<const AttributeSpec>(kInputAttributes);
}

void AssemblyObject::GetInstanceAttribute(std::uint32_t instance, std::uint16_t id, base::ByteWriter& out) {
  const Entry* entry = Find(instance);
  if (entry == nullptr) return;
  if (id == kAttributeData) {
    if (entry->source != nullptr) entry->source->RefreshInput(instance, entry->data);
    out.Bytes(entry->data);
  }
  if (id == kAttributeSize) out.U16Le(static_cast<std::uint16_t>(entry->data.size()));
}

ServiceStatus AssemblyObject::SetInstanceAttribute(std::uint32_t instance, std::uint16_t id, base::ByteReader& value) {
  const Entry* entry = Find(instance);
  if (entry == nullptr || id != kAttributeData) return Error(GeneralStatus::kAttributeNotSettable);
  const ServiceStatus size = ExpectSize(value, entry->data.size());
  if (!size.ok()) return size;
  const std::span<const std::uint8_t> data = value.Rest();
  if (entry->handler != nullptr) {
    const ServiceStatus accepted = entry->handler->OnExplicitWrite(instance, data);
    if (!accepted.ok()) return accepted;
  }
  std::copy(data.begin(), data.end(), entry->data.begin());
  return Success();
}

}  // namespace cip
