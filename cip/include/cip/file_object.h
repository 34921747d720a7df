// File object 0x37 (CIP Vol. 1 §5A-42): the card's EDS, read-only, in instance 0xC8 ("EDS and Icon Files",
// the instance number the specification reserves for it), so that a scanner's "upload EDS from device"
// finds it. docs/file-object.md has the choices; in short:
//
//   class attributes  1 revision 3, 2 max instance 200, 3 instances (1, or 0 without a file), 6 max class
//                     attribute 32, 7 max instance attribute 11, 32 directory (per instance: instance UINT,
//                     instance name STRINGI, file name STRINGI)
//   class services    Get_Attributes_All 0x01, Get_Attribute_Single 0x0E
//   instance 0xC8     1 state USINT (2 file loaded, 3 upload initiated, 5 upload in progress; 1 file empty),
//                     2 instance name STRINGI, 3 instance format version UINT 1, 4 file name STRINGI,
//                     5 file revision USINT major + USINT minor, 6 file size UDINT, 7 file checksum INT,
//                     8 invocation method USINT 0xFF (not applicable), 9 file save parameters BYTE 0,
//                     10 file type USINT 1 (read only), 11 file encoding format USINT 0 (binary)
//   instance services Get_Attributes_All 0x01, Get_Attribute_Single 0x0E, Initiate_Upload 0x4B,
//                     Upload_Transfer 0x4F
//
// Uploads: one at a time, owned by the encapsulation session that initiated it.
//   Initiate_Upload    request  USINT maximum transfer size (1..255)
//                      reply    UDINT file size, USINT transfer size (the requested one)
//   Upload_Transfer    request  USINT transfer number (0 first, then +1 modulo 256)
//                      reply    USINT transfer number, USINT packet type (0 first, 1 middle, 2 last,
//                               4 first and last), the data (transfer size bytes, fewer in the last),
//                               and after the data of a last packet the file checksum INT
// A transfer with the number of the packet sent last sends that packet again (its reply was lost); any
// other number is out of sequence. Statuses: 0x13/0x15 request not exactly one byte; 0x20/0x0008 transfer
// size 0; 0x20/0x0006 transfer number out of sequence; 0x0C no upload of this session in progress
// (Upload_Transfer without Initiate_Upload, or another session's upload, active within the last
// kFileUploadIdleLimit), or an empty file. An upload idle for kFileUploadIdleLimit is dropped, so a
// scanner that vanished mid-upload never blocks the next one.
#pragma once

#include <cstdint>
#include <span>
#include <string_view>

#include "cip/file_content.h"
#include "cip/object_model.h"
#include "hal/clock.h"

namespace cip {

inline constexpr std::uint16_t kClassFile = 0x37;
inline constexpr std::uint32_t kEdsFileInstance = 0xC8;
inline constexpr std::uint8_t kServiceInitiateUpload = 0x4B;
inline constexpr std::uint8_t kServiceUploadTransfer = 0x4F;

// Extended status words of General Status 0x20 for the File object's transfers.
inline constexpr std::uint16_t kExtendedFileTransferOutOfSequence = 0x0006;
inline constexpr std::uint16_t kExtendedFileTransferZeroSize = 0x0008;

// Upload_Transfer packet types.
enum class FilePacketType : std::uint8_t { kFirst = 0, kMiddle = 1, kLast = 2, kAbort = 3, kFirstAndLast = 4 };

// Attribute 1 values the card uses.
enum class FileState : std::uint8_t { kFileEmpty = 1, kFileLoaded = 2, kUploadInitiated = 3, kUploadInProgress = 5 };

// An upload without a request for this long is dropped (the File object's default transfer timeout).
inline constexpr hal::Micros kFileUploadIdleLimit = 10 * hal::kMicrosPerSecond;

// What the card serves in instance 0xC8.
struct ServedFile {
  const FileContent* content = nullptr;  // nullptr: instance 0xC8 does not exist (0x16)
  std::string_view name;                 // attribute 4 and the HTTP download's file name, at most 255 bytes
  std::uint8_t major_revision = 1;       // attribute 5
  std::uint8_t minor_revision = 0;
};

class FileObject final : public AttributeHandler {
 public:
  explicit FileObject(const ServedFile& file);

  // The class as the registry sees it (it notes each request's time for attribute 1, then runs the
  // attribute tables and the upload services).
  CipObject& object() { return front_; }

  std::uint32_t MaxInstance() const override { return kEdsFileInstance; }
  std::uint32_t InstanceCount() const override { return file_.content != nullptr ? 1 : 0; }
  bool HasInstanceNumber(std::uint32_t instance) const override {
    return instance == kEdsFileInstance && file_.content != nullptr;
  }
  std::span<const AttributeSpec> InstanceAttributes(std::uint32_t instance) const override;
  void GetInstanceAttribute(std::uint32_t instance, std::uint16_t id, base::ByteWriter& out) override;
  void GetClassAttribute(std::uint16_t id, base::ByteWriter& out) override;
  ServiceStatus ExecuteOther(const ServiceRequest& request, base::ByteWriter& reply) override;

  // Attribute 1 as a request at `now` would see it.
  FileState state(hal::Micros now) const;

 private:
  struct Upload {
    bool active = false;
    bool finished = false;            // the last packet was sent; only it can be asked for again
    std::uint32_t session = 0;
    hal::Micros last_request = 0;
    std::uint8_t transfer_size = 0;
    bool sent_any = false;            // a packet was sent: `last_number` can be sent again
    std::uint8_t last_number = 0;     // of the packet sent last
    std::uint32_t last_offset = 0;    // where it started
    std::uint32_t next_offset = 0;    // where the next one starts
  };

  ServiceStatus InitiateUpload(const ServiceRequest& request, base::ByteWriter& reply);
  ServiceStatus UploadTransfer(const ServiceRequest& request, base::ByteWriter& reply);
  // Writes the packet starting at `offset` (its number, type, data and, when last, the checksum).
  void WritePacket(std::uint8_t number, std::uint32_t offset, base::ByteWriter& reply) const;
  // An upload in progress (not finished, not idle for kFileUploadIdleLimit).
  bool UploadLive(hal::Micros now) const;
  // The upload, finished or not, belongs to `session` and was used within kFileUploadIdleLimit.
  bool UploadOwnedBy(std::uint32_t session, hal::Micros now) const;

  class Front final : public CipObject {
   public:
    explicit Front(FileObject& owner) : owner_(owner) {}
    std::uint16_t class_id() const override { return owner_.object_.class_id(); }
    bool HasInstance(std::uint32_t instance) const override { return owner_.object_.HasInstance(instance); }
    bool SupportsService(std::uint32_t instance, std::uint8_t service) const override {
      return owner_.object_.SupportsService(instance, service);
    }
    ServiceStatus Execute(const ServiceRequest& request, base::ByteWriter& reply) override;

   private:
    FileObject& owner_;
  };

  ServedFile file_;
  Upload upload_;
  hal::Micros now_ = 0;  // of the request being executed
  AttributeObject object_;
  Front front_;
};

// STRINGI with one English string in ISO 8859-1 (attributes 2 and 4, the directory): USINT 1, "eng",
// USINT 0xDA (SHORT_STRING), UINT 4 (ISO 8859-1), USINT length, the characters.
void PutStringI(std::string_view text, base::ByteWriter& out);

}  // namespace cip
