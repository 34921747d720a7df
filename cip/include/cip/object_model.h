// The CIP object model: what the message router dispatches to.
//
// CipObject is one object class with its instances. The router checks, in this order, and answers the
// first failure (docs/ethernetip.md, "Error order"):
//   class registered?            else 0x05 path destination unknown
//   HasInstance(instance)?       else 0x16 object does not exist (instance 0, the class, always exists)
//   SupportsService(service)?    else 0x08 service not supported, before any attribute or data check
//   member segment in the path?  then 0x05 (no object of the card has members)
//   Execute()                    attribute and data checks, then the service itself
//
// AttributeObject implements the common services from attribute tables, so an object is a ClassSpec,
// a list of AttributeSpecs and an AttributeHandler with the getters/setters of its values:
//   Get_Attributes_All 0x01      every attribute marked in_get_all, in table order
//   Get_Attribute_Single 0x0E    0x14 unknown attribute; 0x15 if the request carries data
//   Set_Attribute_Single 0x10    0x14 unknown; 0x0E not settable; then the object's setter, which
//                                decodes with the Read* helpers below: 0x13 short, 0x15 long, 0x09 bad value
// and the class level (instance 0) attributes 1-7 from a ClassSpec (revision, max instance, number of
// instances, optional attribute list, optional service list, max class and instance attribute IDs).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "base/status.h"
#include "base/byte_reader.h"
#include "base/byte_writer.h"
#include "cip/cip_status.h"
#include "cip/epath.h"
#include "cip/explicit_messaging.h"

namespace cip {

struct ServiceRequest {
  std::uint8_t service = 0;
  ApplicationPath path;
  std::span<const std::uint8_t> data;
  RequestContext* context = nullptr;
};

class CipObject {
 public:
  virtual ~CipObject() = default;
  virtual std::uint16_t class_id() const = 0;
  virtual bool HasInstance(std::uint32_t instance) const = 0;
  virtual bool SupportsService(std::uint32_t instance, std::uint8_t service) const = 0;
  // Writes the reply data into `reply` (its overflow becomes 0x11 reply data too large).
  virtual ServiceStatus Execute(const ServiceRequest& request, base::ByteWriter& reply) = 0;
};

// The classes the message router knows. Fixed capacity: the manual's chapter 4 lists 12 classes.
inline constexpr std::size_t kMaxObjectClasses = 16;

class ObjectRegistry {
 public:
  // kInvalidArgument when the class is already registered, kResourceExhausted when full.
  base::Status Register(CipObject& object);
  CipObject* Find(std::uint32_t class_id) const;

 private:
  std::array<CipObject*, kMaxObjectClasses> objects_{};
  std::size_t count_ = 0;
};

enum class Access : std::uint8_t {
  kGet,         // Get_Attribute_Single
  kGetSet,      // Get_ and Set_Attribute_Single
  kGetAllOnly,  // only a placeholder in Get_Attributes_All (e.g. TCP/IP attr 7, not implemented)
};

struct AttributeSpec {
  std::uint16_t id = 0;
  Access access = Access::kGet;
  bool in_get_all = true;
};

// The table of an object whose instance attributes are 1..N, each gettable and in Get_Attributes_All.
template <std::size_t N>
constexpr std::array<AttributeSpec, N> GettableAttributes() {
  std::array<AttributeSpec, N> attributes{};
  for (std::size_t i = 0; i < N; ++i) attributes[i] = {static_cast<std::uint16_t>(i + 1), Access::kGet, true};
  return attributes;
}

struct ClassSpec {
  std::uint16_t class_id = 0;
  std::uint16_t revision = 1;
  // The class attributes that exist, in ID order; IDs 1-7 are answered by AttributeObject, others by
  // GetClassAttribute.
  std::span<const std::uint16_t> class_attributes;
  std::span<const std::uint16_t> optional_attributes;  // class attribute 4
  std::span<const std::uint16_t> optional_services;    // class attribute 5
  std::uint16_t max_class_attribute = 7;                // class attribute 6
  std::uint16_t max_instance_attribute = 0;             // class attribute 7
  std::span<const std::uint8_t> class_services;
  std::span<const std::uint8_t> instance_services;
};

// What an object supplies to AttributeObject: its instances, attribute values and extra services.
// (An interface rather than a base class with out-of-line virtuals, so that tests built with RTTI can
// implement it while the library is built without.)
class AttributeHandler {
 public:
  virtual ~AttributeHandler() = default;
  // Instances are numbered 1..MaxInstance(); HasInstanceNumber says which exist (default: all).
  virtual std::uint32_t MaxInstance() const = 0;
  virtual std::uint32_t InstanceCount() const { return MaxInstance(); }
  virtual bool HasInstanceNumber(std::uint32_t instance) const { return instance >= 1 && instance <= MaxInstance(); }
  virtual std::span<const AttributeSpec> InstanceAttributes(std::uint32_t instance) const = 0;
  // Writes the value of an attribute listed in InstanceAttributes (kGetAllOnly ones included).
  virtual void GetInstanceAttribute(std::uint32_t instance, std::uint16_t id, base::ByteWriter& out) = 0;
  // Decodes and applies a kGetSet attribute; `value` holds exactly the request data.
  virtual ServiceStatus SetInstanceAttribute(std::uint32_t /*instance*/, std::uint16_t /*id*/, base::ByteReader& /*value*/) {
    return Error(GeneralStatus::kAttributeNotSettable);
  }
  // Class attributes beyond 7 (e.g. Port 8 and 9).
  virtual void GetClassAttribute(std::uint16_t /*id*/, base::ByteWriter& /*out*/) {}
  // Services other than 0x01/0x0E/0x10 that the ClassSpec lists (Reset, Get_and_Clear, ...).
  virtual ServiceStatus ExecuteOther(const ServiceRequest& /*request*/, base::ByteWriter& /*reply*/) {
    return Error(GeneralStatus::kServiceNotSupported);
  }
};

// A CipObject made of a ClassSpec and an AttributeHandler.
class AttributeObject final : public CipObject {
 public:
  AttributeObject(const ClassSpec& spec, AttributeHandler& handler) : spec_(spec), handler_(handler) {}

  std::uint16_t class_id() const override { return spec_.class_id; }
  bool HasInstance(std::uint32_t instance) const override;
  bool SupportsService(std::uint32_t instance, std::uint8_t service) const override;
  ServiceStatus Execute(const ServiceRequest& request, base::ByteWriter& reply) override;

 private:
  ServiceStatus GetAttributesAll(std::uint32_t instance, base::ByteWriter& reply);
  ServiceStatus GetAttributeSingle(const ServiceRequest& request, base::ByteWriter& reply);
  ServiceStatus SetAttributeSingle(const ServiceRequest& request);
  bool HasClassAttribute(std::uint16_t id) const;
  void GetCommonClassAttribute(std::uint16_t id, base::ByteWriter& out);

  const ClassSpec& spec_;
  AttributeHandler& handler_;
};

// Finds an attribute in a table; nullptr when it is not there.
const AttributeSpec* FindAttribute(std::span<const AttributeSpec> table, std::uint32_t id);

// Typed decoding of a Set_Attribute_Single value: the request data must be exactly the type's size
// (0x13 when shorter, 0x15 when longer).
ServiceStatus ReadExactU8(base::ByteReader& in, std::uint8_t& value);
ServiceStatus ReadExactU16(base::ByteReader& in, std::uint16_t& value);
ServiceStatus ReadExactU32(base::ByteReader& in, std::uint32_t& value);
// Checks that a fixed-size structure of `size` bytes is all the request holds.
ServiceStatus ExpectSize(const base::ByteReader& in, std::size_t size);

// The answer to a setting that went to a provider's store: kInvalidArgument (a value the store cannot
// hold) is 0x09 invalid attribute value, any other failure 0x19 store operation failure.
ServiceStatus StoreResult(base::Status status);

// Typed encoding of attribute values.
void PutShortString(std::span<const std::uint8_t> text, base::ByteWriter& out);  // USINT length + characters
// CIP STRING as the TCP/IP object uses it: UINT length, characters, a pad byte when the length is odd.
void PutPaddedString(std::span<const std::uint8_t> text, base::ByteWriter& out);
// A padded EPATH preceded by its size in 16-bit words (UINT), e.g. TCP/IP attr 4, Port attr 3.
void PutSizedPath(std::span<const std::uint8_t> padded_path, base::ByteWriter& out);

}  // namespace cip
