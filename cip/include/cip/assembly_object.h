// Assembly object 0x04 (manual §4.3) and the registry of assembly instances.
//
//   class attributes  1 revision 2, 2 max instance (highest registered), 3 instances (how many are
//                     registered), 6 max class attribute 7, 7 max instance attribute 4
//   class services    Get_Attribute_Single 0x0E
//   instance          3 data (settable only on output assemblies), 4 size in bytes (UINT)
//   instance services Get_Attribute_Single 0x0E, Set_Attribute_Single 0x10
//
// The assemblies themselves (20/21/100/101/102/105 out, 70/71/150/151/152/155 in, §5) are registered by
// the I/O issue; §4.3's "199 / 13" are what the class attributes read once its 13 instances are there.
// A registration names memory the registrant owns and keeps alive. Set_Attribute_Single on data needs
// exactly the assembly's size (0x13 shorter, 0x15 longer); the registrant's handler may refuse a write
// (an exclusive-owner connection owns the output: 0x10) or take it (apply it to the drive), and only
// then is it copied into the assembly.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "base/status.h"
#include "cip/object_model.h"

namespace cip {

inline constexpr std::size_t kMaxAssemblies = 16;

enum class AssemblyDirection : std::uint8_t {
  kInput,   // produced by the card (T->O): read-only to explicit messages
  kOutput,  // consumed by the card (O->T): attribute 3 settable
};

class AssemblyWriteHandler {
 public:
  virtual ~AssemblyWriteHandler() = default;
  // An explicit write of `data` (exactly the assembly's size) to output assembly `instance`. Returns
  // success to let it be stored, or the error to answer (e.g. kDeviceStateConflict).
  virtual ServiceStatus OnExplicitWrite(std::uint32_t instance, std::span<const std::uint8_t> data) = 0;
};

class AssemblyInputSource {
 public:
  virtual ~AssemblyInputSource() = default;
  // Brings input assembly `instance`'s memory up to date just before an explicit read of its data:
  // the registrant fills it when it is read (and when it produces), not on every pass of the loop.
  virtual void RefreshInput(std::uint32_t instance, std::span<std::uint8_t> data) = 0;
};

class AssemblyObject final : public AttributeHandler {
 public:
  AssemblyObject();

  CipObject& object() { return object_; }
  // kInvalidArgument: instance 0, already registered, or larger than 0xFFFF bytes; kResourceExhausted:
  // kMaxAssemblies reached.
  base::Status Register(std::uint32_t instance, AssemblyDirection direction, std::span<std::uint8_t> data,
                        AssemblyWriteHandler* handler = nullptr);
  // An input assembly whose memory `source` refreshes before each explicit read.
  base::Status RegisterInput(std::uint32_t instance, std::span<std::uint8_t> data, AssemblyInputSource& source);
  // The registered memory, empty when there is no such instance.
  std::span<std::uint8_t> Data(std::uint32_t instance) const;

  std::uint32_t MaxInstance() const override;
  std::uint32_t InstanceCount() const override { return static_cast<std::uint32_t>(count_); }
  bool HasInstanceNumber(std::uint32_t instance) const override { return Find(instance) != nullptr; }
  std::span<const AttributeSpec> InstanceAttributes(std::uint32_t instance) const override;
  void GetInstanceAttribute(std::uint32_t instance, std::uint16_t id, base::ByteWriter& out) override;
  ServiceStatus SetInstanceAttribute(std::uint32_t instance, std::uint16_t id, base::ByteReader& value) override;

 private:
  struct Entry {
    std::uint32_t instance = 0;
    AssemblyDirection direction = AssemblyDirection::kInput;
    std::span<std::uint8_t> data;
    AssemblyWriteHandler* handler = nullptr;
    AssemblyInputSource* source = nullptr;
  };
  const Entry* Find(std::uint32_t instance) const;

  std::array<Entry, kMaxAssemblies> entries_{};
  std::size_t count_ = 0;
  AttributeObject object_;
};

}  // namespace cip
