#include "cip/file_object.h"

#include <algorithm>
#include <array>

namespace cip {
namespace {

constexpr std::array<std::uint16_t, 6> kClassAttributes = {1, 2, 3, 6, 7, 32};
constexpr std::array<std::uint8_t, 2> kClassServices = {kServiceGetAttributesAll, kServiceGetAttributeSingle};
constexpr std::array<std::uint8_t, 4> kInstanceServices = {kServiceGetAttributesAll, kServiceGetAttributeSingle,
                                                           kServiceInitiateUpload, kServiceUploadTransfer};
// Revision 3 as OpENer's File object reports it; attribute 12 (transfer timeout, settable) is not
// implemented, so the highest instance attribute is 11.
constexpr ClassSpec kFileClass = {
    kClassFile, 3, kClassAttributes, {}, {}, 32, 11, kClassServices, kInstanceServices,
};
constexpr std::array<AttributeSpec, 11> kAttributes = GettableAttributes<11>();

constexpr std::string_view kInstanceName = "EDS and Icon Files";
constexpr std::uint16_t kInstanceFormatVersion = 1;
constexpr std::uint8_t kInvocationNotApplicable = 0xFF;
constexpr std::uint8_t kFileSaveParameters = 0;
constexpr std::uint8_t kFileTypeReadOnly = 1;
constexpr std::uint8_t kEncodingBinary = 0;
constexpr std::uint8_t kShortStringType = 0xDA;
constexpr std::uint16_t kCharacterSetIso8859_1 = 4;

struct RequestOrigin {
  std::uint32_t session = 0;
  hal::Micros now = 0;
};

RequestOrigin OriginOf(const ServiceRequest& request) {
  if (request.context == nullptr) return {};
  return {request.context->session_handle, request.context->now};
}

}  // namespace

void PutStringI(std::string_view text, base::ByteWriter& out) {
  out.U8(1);
  out.Bytes(std::span(reinterpret_cast<const std::uint8_t*>("eng"), 3));
  out.U8(kShortStringType);
  out.U16Le(kCharacterSetIso8859_1);
  PutShortString(std::span(reinterpret_cast<const std::uint8_t*>(text.data()), std::min<std::size_t>(text.size(), 255)),
                 out);
}

FileObject::FileObject(const ServedFile& file) : file_(file), object_(kFileClass, *this), front_(*this) {}

ServiceStatus FileObject::Front::Execute(const ServiceRequest& request, base::ByteWriter& reply) {
  if (request.context != nullptr) owner_.now_ = request.context->now;
  return owner_.object_.Execute(request, reply);
}

std::span<const AttributeSpec> FileObject::InstanceAttributes(std::uint32_t) const { return kAttributes; }

FileState FileObject::state(hal::Micros now) const {
  if (file_.content == nullptr || file_.content->Size() == 0) return FileState::kFileEmpty;
  if (!UploadLive(now)) return FileState::kFileLoaded;
  return upload_.sent_any ? FileState::kUploadInProgress : FileState::kUploadInitiated;
}

void FileObject::GetInstanceAttribute(std::uint32_t, std::uint16_t id, base::ByteWriter& out) {
  switch (id) {
    case 1:
      out.U8(static_cast<std::uint8_t>(state(now_)));
      break;
    case 2:
      PutStringI(kInstanceName, out);
      break;
    case 3:
      out.U16Le(kInstanceFormatVersion);
      break;
    case 4:
      PutStringI(file_.name, out);
      break;
    case 5:
      out.U8(file_.major_revision);
      out.U8(file_.minor_revision);
      break;
    case 6:
      out.U32Le(file_.content->Size());
      break;
    case 7:
      out.U16Le(file_.content->Checksum());
      break;
    case 8:
      out.U8(kInvocationNotApplicable);
      break;
    case 9:
      out.U8(kFileSaveParameters);
      break;
    case 10:
      out.U8(kFileTypeReadOnly);
      break;
    case 11:
      out.U8(kEncodingBinary);
      break;
    default:
      break;
  }
}

void FileObject::GetClassAttribute(std::uint16_t id, base::ByteWriter& out) {
  if (id != 32 || file_.content == nullptr) return;
  out.U16Le(static_cast<std::uint16_t>(kEdsFileInstance));
  PutStringI(kInstanceName, out);
  PutStringI(file_.name, out);
}

ServiceStatus FileObject::ExecuteOther(const ServiceRequest& request, base::ByteWriter& reply) {
  if (request.service == kServiceInitiateUpload) return InitiateUpload(request, reply);
  if (request.service == kServiceUploadTransfer) return UploadTransfer(request, reply);
  return Error(GeneralStatus::kServiceNotSupported);
}

bool FileObject::UploadLive(hal::Micros now) const {
  return upload_.active && !upload_.finished && now - upload_.last_request < kFileUploadIdleLimit;
}

bool FileObject::UploadOwnedBy(std::uint32_t session, hal::Micros now) const {
  return upload_.active && upload_.session == session && now - upload_.last_request < kFileUploadIdleLimit;
}

ServiceStatus FileObject::InitiateUpload(const ServiceRequest& request, base::ByteWriter& reply) {
  base::ByteReader in(request.data);
  std::uint8_t transfer_size = 0;
  if (ServiceStatus status = ReadExactU8(in, transfer_size); !status.ok()) return status;
  if (transfer_size == 0) return ErrorWithExtended(GeneralStatus::kInvalidParameter, kExtendedFileTransferZeroSize);
  const RequestOrigin origin = OriginOf(request);
  if (file_.content->Size() == 0) return Error(GeneralStatus::kObjectStateConflict);
  // Another session's upload keeps the instance until it ends or idles out; the same session may start over.
  if (UploadLive(origin.now) && upload_.session != origin.session) return Error(GeneralStatus::kObjectStateConflict);
  upload_ = Upload{};
  upload_.active = true;
  upload_.session = origin.session;
  upload_.last_request = origin.now;
  upload_.transfer_size = transfer_size;
  reply.U32Le(file_.content->Size());
  reply.U8(transfer_size);
  return Success();
}

ServiceStatus FileObject::UploadTransfer(const ServiceRequest& request, base::ByteWriter& reply) {
  base::ByteReader in(request.data);
  std::uint8_t number = 0;
  if (ServiceStatus status = ReadExactU8(in, number); !status.ok()) return status;
  const RequestOrigin origin = OriginOf(request);
  if (!UploadOwnedBy(origin.session, origin.now)) return Error(GeneralStatus::kObjectStateConflict);
  if (upload_.sent_any && number == upload_.last_number) {
    // The reply to the packet sent last was lost: the same packet again.
    upload_.last_request = origin.now;
    WritePacket(number, upload_.last_offset, reply);
    return Success();
  }
  if (upload_.finished) return Error(GeneralStatus::kObjectStateConflict);
  const std::uint8_t expected = upload_.sent_any ? static_cast<std::uint8_t>(upload_.last_number + 1) : 0;
  if (number != expected) {
    return ErrorWithExtended(GeneralStatus::kInvalidParameter, kExtendedFileTransferOutOfSequence);
  }
  const std::uint32_t size = file_.content->Size();
  const std::uint32_t offset = upload_.next_offset;
  const std::uint32_t length = std::min<std::uint32_t>(upload_.transfer_size, size - offset);
  upload_.last_request = origin.now;
  upload_.sent_any = true;
  upload_.last_number = number;
  upload_.last_offset = offset;
  upload_.next_offset = offset + length;
  upload_.finished = upload_.next_offset == size;
  WritePacket(number, offset, reply);
  return Success();
}

void FileObject::WritePacket(std::uint8_t number, std::uint32_t offset, base::ByteWriter& reply) const {
  const std::uint32_t size = file_.content->Size();
  const std::uint32_t length = std::min<std::uint32_t>(upload_.transfer_size, size - offset);
  const bool first = offset == 0;
  const bool last = offset + length == size;
  FilePacketType type = FilePacketType::kMiddle;
  if (first && last) {
    type = FilePacketType::kFirstAndLast;
  } else if (first) {
    type = FilePacketType::kFirst;
  } else if (last) {
    type = FilePacketType::kLast;
  }
  reply.U8(number);
  reply.U8(static_cast<std::uint8_t>(type));
  // A reply buffer too small or a short read fails the writer: the router answers 0x11, never short data.
  if (length > reply.room() || file_.content->ReadAt(offset, reply.Tail().first(length)) != length) {
    reply.Advance(reply.room() + 1);
    return;
  }
  reply.Advance(length);
  if (last) reply.U16Le(file_.content->Checksum());
}

}  // namespace cip
