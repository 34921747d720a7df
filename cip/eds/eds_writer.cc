// The card's EDS, section by section (eds_writer.h; docs/eds.md has the choices made).
#include "cip/eds/eds_writer.h"

#include <array>
#include <cstdint>
#include <span>

#include "cip/connection_manager.h"
#include "cip/drive/assembly_codec.h"
#include "cip/drive/cip_parameter_object.h"
#include "cip/ethernet_link_object.h"
#include "cip/identity_object.h"
#include "cip/message_router_object.h"
#include "cip/port_object.h"
#include "cip/tcpip_interface_object.h"
#include "drive_link/parameter_table.h"

namespace cip::eds {
namespace {

using drive_link::ParameterInfo;

constexpr std::string_view kKey = "\n    ";      // a key of a section
constexpr std::string_view kField = "\n        ";  // a field of a multi-line entry
constexpr std::uint16_t kNoRegister = 0xFFFF;       // ends in F: never a register

// The text around the sink: pieces, decimal and hexadecimal numbers. Once the sink has said no, nothing
// more is offered to it (open() turns false and the loops below stop).
class Text {
 public:
  explicit Text(EdsSink& sink) : sink_(sink) {}
  bool open() const { return open_; }

  Text& operator<<(std::string_view piece) {
    if (open_ && !piece.empty()) open_ = sink_.Append(piece);
    return *this;
  }
  Text& Dec(std::int32_t value) {
    std::array<char, 12> digits{};
    std::size_t at = digits.size();
    std::uint32_t magnitude = value < 0 ? 0U - static_cast<std::uint32_t>(value) : static_cast<std::uint32_t>(value);
    do {
      digits[--at] = static_cast<char>('0' + magnitude % 10);
      magnitude /= 10;
    } while (magnitude != 0);
    if (value < 0) digits[--at] = '-';
    return *this << std::string_view(&digits[at], digits.size() - at);
  }
  // `count` upper-case hexadecimal digits, without a prefix.
  Text& HexDigits(std::uint32_t value, int count) {
    std::array<char, 8> digits{};
    for (int i = count - 1; i >= 0; --i) {
      digits[static_cast<std::size_t>(i)] = "0123456789ABCDEF"[value & 0xF];
      value >>= 4;
    }
    return *this << std::string_view(digits.data(), static_cast<std::size_t>(count));
  }
  Text& Hex(std::uint32_t value, int count) { return (*this << "0x").HexDigits(value, count); }
  Text& Quoted(std::string_view text) { return *this << "\"" << text << "\""; }
  // An EPATH as EDS writes it: "20 04 24 14 30 03".
  Text& Path(std::span<const std::uint8_t> bytes) {
    *this << "\"";
    for (std::size_t i = 0; i < bytes.size(); ++i) {
      if (i != 0) *this << " ";
      HexDigits(bytes[i], 2);
    }
    return *this << "\"";
  }
  Text& Param(std::size_t number) { return (*this << "Param").Dec(static_cast<std::int32_t>(number)); }
  Text& Assem(std::uint32_t instance) { return (*this << "Assem").Dec(static_cast<std::int32_t>(instance)); }

 private:
  EdsSink& sink_;
  bool open_ = true;
};

// ---- [File], [Device] --------------------------------------------------------------------------------

void WriteHeader(DriveModel model, Text& out) {
  const std::string_view name = ProductNameOf(model);
  out << "$ EDS of the IPE002Z EtherNet/IP option card on a Toshiba " << name << " inverter.\n"
      << "$ Generated from the card firmware's own tables (docs/eds.md); the card serves the same bytes.\n";
  out << "\n[File]" << kKey << "DescText = " << "\"IPE002Z EtherNet/IP option card on a " << name << "\";";
  // The EDS changes with the firmware: its revision is the Identity revision.
  out << kKey << "CreateDate = 11-27-2026;" << kKey << "CreateTime = 12:00:00;";
  out << kKey << "ModDate = 11-27-2026;" << kKey << "ModTime = 12:00:00;";
  out << kKey << "Revision = ";
  out.Dec(kMajorRevision) << ".";
  out.Dec(kMinorRevision) << ";\n";

  out << "\n[Device]" << kKey << "VendCode = ";
  out.Dec(kVendorIdToshiba) << ";" << kKey << "VendName = \"Toshiba\";" << kKey << "ProdType = ";
  out.Dec(kDeviceTypeAcDrive) << ";" << kKey << "ProdTypeStr = \"AC Drive\";" << kKey << "ProdCode = ";
  out.Dec(ProductCodeOf(model)) << ";" << kKey << "MajRev = ";
  out.Dec(kMajorRevision) << ";" << kKey << "MinRev = ";
  out.Dec(kMinorRevision) << ";" << kKey << "ProdName = ";
  out.Quoted(name) << ";" << kKey << "Catalog = \"IPE002Z\";\n";

  out << "\n[Device Classification]" << kKey << "Class1 = EtherNetIP;\n";
}

// ---- [Params], [Groups] -------------------------------------------------------------------------------

// The RPI parameter the connections refer to: the last one, after the table's.
std::size_t RpiParam() { return drive_link::CardParameters().size() + 1; }

void WriteTableParam(std::size_t number, const ParameterInfo& row, drive_link::InverterModel model, Text& out) {
  out << kKey;
  // Three lines: reserved, link path size and path, descriptor, type, size; name, units, help; min, max,
  // default, scaling multiplier, divisor, base, offset, the four scaling links (none), decimal places.
  out.Param(number) << " =" << kField << "0, ";
  // The value's path: attribute 1 of Parameter object instance `number`, 8- or 16-bit instance segment.
  const auto instance = static_cast<std::uint16_t>(number);
  std::array<std::uint8_t, 8> path = {0x20, drive::kClassParameter};
  std::size_t size = 2;
  if (instance <= 0xFF) {
    path[size++] = 0x24;
    path[size++] = static_cast<std::uint8_t>(instance);
  } else {
    path[size++] = 0x25;
    path[size++] = 0x00;
    path[size++] = static_cast<std::uint8_t>(instance & 0xFF);
    path[size++] = static_cast<std::uint8_t>(instance >> 8);
  }
  path[size++] = 0x30;
  path[size++] = drive::kParameterValue;
  out.Dec(static_cast<std::int32_t>(size)) << ",";
  out.Path(std::span<const std::uint8_t>(path).first(size));
  out << ", ";
  out.Hex(drive::ParameterDescriptor(row), 4) << ", ";
  out.Hex(drive::ParameterDataType(row), 2) << ", 2," << kField;
  out.Quoted(row.title) << ", ";
  out.Quoted(row.unit) << ", ";
  out.Quoted(row.help) << "," << kField;
  const drive_link::ParameterLimits& limits = row.Limits(model);
  out.Dec(row.Value(limits.min)) << ",";
  out.Dec(row.Value(limits.max)) << ",";
  out.Dec(row.Value(limits.default_value)) << ", 1,";
  out.Dec(drive::ScalingDivisor(row)) << ",1,0, ,,,, ";
  out.Dec(row.decimals) << ";";
}

void WriteParams(DriveModel model, Text& out) {
  out << "\n[Params]";
  const std::span<const ParameterInfo> rows = drive_link::CardParameters();
  const drive_link::InverterModel inverter = drive::InverterModelOf(model);
  for (std::size_t i = 0; i < rows.size() && out.open(); ++i) WriteTableParam(i + 1, rows[i], inverter, out);
  // The RPI of every connection (µs): the Connection Manager's floor and ceiling.
  constexpr ConnectionManagerOptions kCard;
  out << kKey;
  out.Param(RpiParam()) << " =" << kField << "0, ,, 0x0000, 0xC8, 4," << kField
                        << "\"RPI\", \"us\", \"Requested packet interval of an I/O connection\"," << kField;
  out.Dec(static_cast<std::int32_t>(kCard.min_rpi)) << ",";
  out.Dec(static_cast<std::int32_t>(kCard.max_rpi)) << ",10000, ,,,, ,,,, ;\n";
}

struct Group {
  std::string_view name;
  std::uint16_t first;  // communication numbers first..last
  std::uint16_t last;
};
constexpr std::array<Group, 4> kGroups = {{
    {"Basic and extended parameters", 0x0000, 0x0FFF},
    {"Communication option parameters", 0xC000, 0xCFFF},
    {"Commands (FA)", 0xFA00, 0xFAFF},
    {"Monitors", 0xFB00, 0xFEFF},
}};

void WriteGroups(Text& out) {
  out << "\n[Groups]";
  const std::span<const ParameterInfo> rows = drive_link::CardParameters();
  for (std::size_t g = 0; g < kGroups.size(); ++g) {
    const Group& group = kGroups[g];
    const auto in_group = [&group](const ParameterInfo& row) { return row.number >= group.first && row.number <= group.last; };
    std::int32_t count = 0;
    for (const ParameterInfo& row : rows) count += in_group(row) ? 1 : 0;
    out << kKey << "Group";
    out.Dec(static_cast<std::int32_t>(g + 1)) << " =" << kField;
    out.Quoted(group.name) << ", ";
    out.Dec(count);
    std::int32_t written = 0;
    for (std::size_t i = 0; i < rows.size() && out.open(); ++i) {
      if (!in_group(rows[i])) continue;
      out << (written % 16 == 0 ? std::string_view(",\n        ") : std::string_view(","));
      out.Dec(static_cast<std::int32_t>(i + 1));
      ++written;
    }
    out << ";";
  }
  out << "\n";
}

// ---- [Assembly] --------------------------------------------------------------------------------------

struct AssemblyText {
  std::uint16_t instance;
  std::string_view name;
  // The registers of words 1 and 2 when they are rows of the parameter table (member references).
  std::uint16_t word1;
  std::uint16_t word2;
};
constexpr std::array<AssemblyText, 12> kAssemblies = {{
    {drive::kBasicSpeedOutput, "Basic speed control (ODVA)", kNoRegister, kNoRegister},
    {drive::kExtendedSpeedOutput, "Extended speed control (ODVA)", kNoRegister, kNoRegister},
    {drive::kNativeOutput, "Native command: FA06, FA07, scanner words c001-c006", 0xFA06, 0xFA07},
    {drive::kNativeParameterOutput, "Extended speed control + parameter channel", kNoRegister, kNoRegister},
    {drive::kScannerOutput, "Scanner words c001-c006", kNoRegister, kNoRegister},
    {drive::kToshibaOutput, "Parameter channel + scanner words c001-c006", kNoRegister, kNoRegister},
    {drive::kBasicSpeedInput, "Basic speed status (ODVA)", kNoRegister, kNoRegister},
    {drive::kExtendedSpeedInput, "Extended speed status (ODVA)", kNoRegister, kNoRegister},
    {drive::kNativeInput, "Native status: FD01, FD00, monitor words c021-c026", 0xFD01, 0xFD00},
    {drive::kNativeParameterInput, "Extended speed status + parameter channel", kNoRegister, kNoRegister},
    {drive::kScannerInput, "Monitor words c021-c026", kNoRegister, kNoRegister},
    {drive::kToshibaInput, "Parameter channel + monitor words c021-c026", kNoRegister, kNoRegister},
}};

constexpr bool CoversEveryAssembly() {
  for (std::size_t i = 0; i < drive::kOutputInstances.size(); ++i) {
    if (kAssemblies[i].instance != drive::kOutputInstances[i]) return false;
    if (kAssemblies[i + 6].instance != drive::kInputInstances[i]) return false;
  }
  return true;
}
static_assert(CoversEveryAssembly(), "one text per drive assembly, in the codec's order");

std::array<std::uint8_t, 6> AssemblyPath(std::uint32_t instance) {
  return {0x20, 0x04, 0x24, static_cast<std::uint8_t>(instance), 0x30, 0x03};
}

void WriteMember(std::uint16_t reg, Text& out) {
  out << "16,";
  if (reg == kNoRegister) return;
  if (const auto row = drive_link::FindParameterByNumber(reg)) out.Param(*row + 1);
}

void WriteAssemblies(Text& out) {
  out << "\n[Assembly]" << kKey << "Object_Name = \"Assembly Object\";" << kKey << "Object_Class_Code = 0x04;";
  for (const AssemblyText& assembly : kAssemblies) {
    // Members are the 16-bit words of the largest size (100/150: 8 words; a connection may use fewer).
    const std::size_t size = drive::AssemblySize(assembly.instance);
    out << kKey;
    out.Assem(assembly.instance) << " =" << kField;
    out.Quoted(assembly.name) << "," << kField;
    out.Path(AssemblyPath(assembly.instance)) << "," << kField;
    out.Dec(static_cast<std::int32_t>(size)) << "," << kField << "0x0000," << kField << ",," << kField;
    for (std::size_t word = 0; word < size / 2; ++word) {
      if (word != 0) out << ",";
      WriteMember(word == 0 ? assembly.word1 : word == 1 ? assembly.word2 : kNoRegister, out);
    }
    out << ";";
  }
  out << kKey;
  out.Assem(drive::kInputOnlyHeartbeat) << " =" << kField << "\"Input-only heartbeat\"," << kField;
  out.Path(AssemblyPath(drive::kInputOnlyHeartbeat)) << "," << kField << "0," << kField << "0x0000," << kField
                                                     << ",,;\n";
}

// ---- [Connection Manager] ----------------------------------------------------------------------------

// Trigger and transport (bits 0-15 class, 16 cyclic, 24 listen only, 25 input only, 26 exclusive owner)
// and connection parameters (bits 0/2 fixed O->T/T->O size, 8-10 O->T format 4 run/idle header or 3
// heartbeat, 12-14 T->O format 0 modeless, 18 O->T point-to-point, 21/22 T->O multicast/point-to-point,
// 26/30 scheduled priority: the card accepts any).
constexpr std::uint32_t kClass1Cyclic = 0x00010002;

struct ConnectionKind {
  std::uint32_t trigger_transport;
  std::uint32_t parameters;
  std::string_view name;
};
constexpr ConnectionKind kExclusiveOwner = {kClass1Cyclic | 1U << 26, 0x44640405, "Exclusive Owner "};
constexpr ConnectionKind kInputOnly = {kClass1Cyclic | 1U << 25, 0x44640305, "Input Only "};
// T->O multicast only: a listen-only connection joins an existing production.
constexpr ConnectionKind kListenOnly = {kClass1Cyclic | 1U << 24, 0x44240305, "Listen Only "};

void WriteConnection(std::int32_t number, const ConnectionKind& kind, std::uint16_t consumed, std::uint16_t produced,
                     Text& out) {
  const bool owner = &kind == &kExclusiveOwner;
  out << kKey << "Connection";
  out.Dec(number) << " =" << kField;
  out.Hex(kind.trigger_transport, 8) << "," << kField;
  out.Hex(kind.parameters, 8) << "," << kField;
  out.Param(RpiParam()) << ",";
  out.Dec(owner ? static_cast<std::int32_t>(drive::AssemblySize(consumed)) : 0) << ",";
  if (consumed != drive::kListenOnlyHeartbeat) out.Assem(consumed);  // 198 is a point, not an instance
  out << "," << kField;
  out.Param(RpiParam()) << ",";
  out.Dec(static_cast<std::int32_t>(drive::AssemblySize(produced))) << ",";
  out.Assem(produced) << "," << kField << ",," << kField << ",," << kField << "\"" << kind.name;
  if (owner) out.Dec(consumed) << "/";
  out.Dec(produced) << "\"," << kField << "\"\"," << kField;
  const std::array<std::uint8_t, 8> path = {
      0x20, 0x04, 0x24, static_cast<std::uint8_t>(drive::kConfigurationInstance), 0x2C, static_cast<std::uint8_t>(consumed),
      0x2C, static_cast<std::uint8_t>(produced)};
  out.Path(path) << ";";
}

void WriteConnections(Text& out) {
  out << "\n[Connection Manager]" << kKey << "Object_Name = \"Connection Manager Object\";" << kKey
      << "Object_Class_Code = 0x06;";
  std::int32_t number = 1;
  for (const std::uint16_t output : drive::kOutputInstances) {
    WriteConnection(number++, kExclusiveOwner, output, drive::PairedInput(output), out);
  }
  for (const std::uint16_t input : drive::kInputInstances) {
    WriteConnection(number++, kInputOnly, drive::kInputOnlyHeartbeat, input, out);
  }
  for (const std::uint16_t input : drive::kInputInstances) {
    WriteConnection(number++, kListenOnly, drive::kListenOnlyHeartbeat, input, out);
  }
  out << "\n";
}

// ---- [Port], [Capacity], object classes ---------------------------------------------------------------

void WriteClass(std::string_view section, std::string_view name, std::uint16_t revision, std::uint16_t class_id,
                std::uint32_t instances, Text& out) {
  out << "\n[" << section << "]" << kKey << "Revision = ";
  out.Dec(revision) << ";" << kKey << "Object_Name = ";
  out.Quoted(name) << ";" << kKey << "Object_Class_Code = ";
  out.Hex(class_id, 2) << ";" << kKey << "MaxInst = ";
  out.Dec(static_cast<std::int32_t>(instances)) << ";" << kKey << "Number_Of_Static_Instances = ";
  out.Dec(static_cast<std::int32_t>(instances)) << ";" << kKey << "Max_Number_Of_Dynamic_Instances = 0;\n";
}

void WriteTail(Text& out) {
  constexpr ConnectionManagerOptions kCard;
  out << "\n[Port]" << kKey << "Port1 = TCP, \"EtherNet/IP\", \"20 F5 24 01\", ";
  out.Dec(kPortNumber) << ";\n";
  out << "\n[Capacity]" << kKey << "MaxMsgConnections = ";
  out.Dec(static_cast<std::int32_t>(kMaxExplicitConnections)) << ";" << kKey << "MaxIOProduceConsume = ";
  out.Dec(kMaxCipConnections) << ";" << kKey << "MaxConsumersPerMcast = ";
  out.Dec(static_cast<std::int32_t>(kCard.max_connections_per_point)) << ";" << kKey << "TSpec1 = TxRx, ";
  out.Dec(static_cast<std::int32_t>(drive::kMaxAssemblySize)) << ", ";
  out.Dec(static_cast<std::int32_t>(1000000 / kCard.min_rpi)) << ";\n";
  WriteClass("Identity Class", "Identity Object", kIdentityClassRevision, kClassIdentity, 1, out);
  WriteClass("TCP/IP Interface Class", "TCP/IP Interface Object", kTcpIpClassRevision, kClassTcpIpInterface, 1, out);
  WriteClass("Ethernet Link Class", "Ethernet Link Object", kEthernetLinkClassRevision, kClassEthernetLink,
             kEthernetLinkInstances, out);
}

}  // namespace

void WriteEds(DriveModel model, EdsSink& sink) {
  Text out(sink);
  WriteHeader(model, out);
  WriteParams(model, out);
  WriteGroups(out);
  WriteAssemblies(out);
  WriteConnections(out);
  WriteTail(out);
}

std::string_view EdsFileName(DriveModel model) {
  return model == DriveModel::kVfS15 ? "IPE002Z_VF-S15.eds" : "IPE002Z_VF-MB1.eds";
}

}  // namespace cip::eds
