#include "cip/object_model.h"

#include <algorithm>

namespace cip {
namespace {

template <typename T>
bool Contains(std::span<const T> values, T value) {
  return std::find(values.begin(), values.end(), value) != values.end();
}

void PutIdList(std::span<const std::uint16_t> ids, base::ByteWriter& out) {
  out.U16Le(static_cast<std::uint16_t>(ids.size()));
  for (std::uint16_t id : ids) out.U16Le(id);
}

}  // namespace

base::Status ObjectRegistry::Register(CipObject& object) {
  if (Find(object.class_id()) != nullptr) return base::InvalidArgument();
  if (count_ == objects_.size()) return base::ResourceExhausted();
  objects_[count_++] = &object;
  return base::OkStatus();
}

CipObject* ObjectRegistry::Find(std::uint32_t class_id) const {
  for (std::size_t i = 0; i < count_; ++i) {
    if (objects_[i]->class_id() == class_id) return objects_[i];
  }
  return nullptr;
}

const AttributeSpec* FindAttribute(std::span<const AttributeSpec> table, std::uint32_t id) {
  for (const AttributeSpec& spec : table) {
    if (spec.id == id) return &spec;
  }
  return nullptr;
}

bool AttributeObject::HasInstance(std::uint32_t instance) const {
  return instance == 0 || handler_.HasInstanceNumber(instance);
}

bool AttributeObject::SupportsService(std::uint32_t instance, std::uint8_t service) const {
  return Contains(instance == 0 ? spec_.class_services : spec_.instance_services, service);
}

ServiceStatus AttributeObject::Execute(const ServiceRequest& request, base::ByteWriter& reply) {
  switch (request.service) {
    case kServiceGetAttributesAll:
      if (!request.data.empty()) return Error(GeneralStatus::kTooMuchData);
      return GetAttributesAll(request.path.instance, reply);
    case kServiceGetAttributeSingle:
      return GetAttributeSingle(request, reply);
    case kServiceSetAttributeSingle:
      return SetAttributeSingle(request);
    default:
      return handler_.ExecuteOther(request, reply);
  }
}

ServiceStatus AttributeObject::GetAttributesAll(std::uint32_t instance, base::ByteWriter& reply) {
  if (instance == 0) {
    for (std::uint16_t id : spec_.class_attributes) {
      if (id <= 7) {
        GetCommonClassAttribute(id, reply);
      } else {
        handler_.GetClassAttribute(id, reply);
      }
    }
    return Success();
  }
  for (const AttributeSpec& attribute : handler_.InstanceAttributes(instance)) {
    if (attribute.in_get_all) handler_.GetInstanceAttribute(instance, attribute.id, reply);
  }
  return Success();
}

ServiceStatus AttributeObject::GetAttributeSingle(const ServiceRequest& request, base::ByteWriter& reply) {
  if (!request.path.attribute) return Error(GeneralStatus::kAttributeNotSupported);
  const std::uint32_t id = *request.path.attribute;
  if (request.path.instance == 0) {
    if (id > 0xFFFF || !HasClassAttribute(static_cast<std::uint16_t>(id))) {
      return Error(GeneralStatus::kAttributeNotSupported);
    }
    if (!request.data.empty()) return Error(GeneralStatus::kTooMuchData);
    if (id <= 7) {
      GetCommonClassAttribute(static_cast<std::uint16_t>(id), reply);
    } else {
      handler_.GetClassAttribute(static_cast<std::uint16_t>(id), reply);
    }
    return Success();
  }
  const AttributeSpec* attribute = FindAttribute(handler_.InstanceAttributes(request.path.instance), id);
  if (attribute == nullptr || attribute->access == Access::kGetAllOnly) {
    return Error(GeneralStatus::kAttributeNotSupported);
  }
  if (!request.data.empty()) return Error(GeneralStatus::kTooMuchData);
  handler_.GetInstanceAttribute(request.path.instance, attribute->id, reply);
  return Success();
}

ServiceStatus AttributeObject::SetAttributeSingle(const ServiceRequest& request) {
  if (!request.path.attribute) return Error(GeneralStatus::kAttributeNotSupported);
  const std::uint32_t id = *request.path.attribute;
  if (request.path.instance == 0) {
    // Every class attribute is read-only.
    if (id > 0xFFFF || !HasClassAttribute(static_cast<std::uint16_t>(id))) {
      return Error(GeneralStatus::kAttributeNotSupported);
    }
    return Error(GeneralStatus::kAttributeNotSettable);
  }
  const AttributeSpec* attribute = FindAttribute(handler_.InstanceAttributes(request.path.instance), id);
  if (attribute == nullptr || attribute->access == Access::kGetAllOnly) {
    return Error(GeneralStatus::kAttributeNotSupported);
  }
  if (attribute->access != Access::kGetSet) return Error(GeneralStatus::kAttributeNotSettable);
  base::ByteReader value(request.data);
  return handler_.SetInstanceAttribute(request.path.instance, attribute->id, value);
}

bool AttributeObject::HasClassAttribute(std::uint16_t id) const { return Contains(spec_.class_attributes, id); }

void AttributeObject::GetCommonClassAttribute(std::uint16_t id, base::ByteWriter& out) {
  switch (id) {
    case 1:
      out.U16Le(spec_.revision);
      break;
    case 2:
      out.U16Le(static_cast<std::uint16_t>(handler_.MaxInstance()));
      break;
    case 3:
      out.U16Le(static_cast<std::uint16_t>(handler_.InstanceCount()));
      break;
    case 4:
      PutIdList(spec_.optional_attributes, out);
      break;
    case 5:
      PutIdList(spec_.optional_services, out);
      break;
    case 6:
      out.U16Le(spec_.max_class_attribute);
      break;
    case 7:
      out.U16Le(spec_.max_instance_attribute);
      break;
    default:
      break;
  }
}

ServiceStatus ExpectSize(const base::ByteReader& in, std::size_t size) {
  if (in.remaining() < size) return Error(GeneralStatus::kNotEnoughData);
  if (in.remaining() > size) return Error(GeneralStatus::kTooMuchData);
  return Success();
}

ServiceStatus ReadExactU8(base::ByteReader& in, std::uint8_t& value) {
  const ServiceStatus status = ExpectSize(in, 1);
  if (status.ok()) value = in.U8();
  return status;
}

ServiceStatus ReadExactU16(base::ByteReader& in, std::uint16_t& value) {
  const ServiceStatus status = ExpectSize(in, 2);
  if (status.ok()) value = in.U16Le();
  return status;
}

ServiceStatus ReadExactU32(base::ByteReader& in, std::uint32_t& value) {
  const ServiceStatus status = ExpectSize(in, 4);
  if (status.ok()) value = in.U32Le();
  return status;
}

ServiceStatus StoreResult(base::Status status) {
  if (status.ok()) return Success();
  if (status.code() == base::StatusCode::kInvalidArgument) return Error(GeneralStatus::kInvalidAttributeValue);
  return Error(GeneralStatus::kStoreOperationFailure);
}

void PutShortString(std::span<const std::uint8_t> text, base::ByteWriter& out) {
  out.U8(static_cast<std::uint8_t>(text.size()));
  out.Bytes(text);
}

void PutPaddedString(std::span<const std::uint8_t> text, base::ByteWriter& out) {
  out.U16Le(static_cast<std::uint16_t>(text.size()));
  out.Bytes(text);
  if (text.size() % 2 != 0) out.U8(0);
}

void PutSizedPath(std::span<const std::uint8_t> padded_path, base::ByteWriter& out) {
  out.U16Le(static_cast<std::uint16_t>(padded_path.size() / 2));
  out.Bytes(padded_path);
}

}  // namespace cip
