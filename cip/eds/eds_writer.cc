// The card's EDS, section by section (eds_writer.h; docs/eds.md has the choices made).
#include "cip/eds/eds_writer.h"

#include <array>
#include <cstdint>
#include <initializer_list>
#include <optional>
#include <span>

#include "cip/connection_manager.h"
#include "cip/drive/assembly_codec.h"
#include "cip/dlr_object.h"
#include "cip/drive/cip_parameter_object.h"
#include "cip/ethernet_link_object.h"
#include "cip/identity_object.h"
#include "cip/message_router_object.h"
#include "cip/port_object.h"
#include "cip/qos_object.h"
#include "cip/tcpip_interface_object.h"
#include "drive_link/parameter_table.h"

namespace cip::eds {
namespace {

using drive_link::ParameterInfo;

constexpr std::uint16_t kNoRegister = 0xFFFF;       // ends in F: never a register

// One value of a Format pattern: a decimal number, a text, hexadecimal digits after 0x, or an EPATH.
struct Arg {
  enum class Kind : std::uint8_t { kDec, kText, kHex, kPath };
  Arg(std::int32_t value) : kind(Kind::kDec), number(value) {}  // NOLINT: implicit on purpose
  Arg(std::string_view value) : kind(Kind::kText), text(value) {}
  Arg(const char* value) : kind(Kind::kText), text(value) {}
  explicit Arg(std::span<const std::uint8_t> value) : kind(Kind::kPath), path(value) {}
  static Arg Hex(std::uint32_t value, std::uint8_t digits) {
    Arg arg(static_cast<std::int32_t>(value));
    arg.kind = Kind::kHex;
    arg.digits = digits;
    return arg;
  }

  Kind kind;
  std::int32_t number = 0;
  std::uint8_t digits = 0;
  std::string_view text;
  std::span<const std::uint8_t> path;
};

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
  // An EPATH as EDS writes it: "20 04 24 14 30 03".
  Text& Path(std::span<const std::uint8_t> bytes) {
    *this << "\"";
    for (std::size_t i = 0; i < bytes.size(); ++i) {
      if (i != 0) *this << " ";
      HexDigits(bytes[i], 2);
    }
    return *this << "\"";
  }
  // `pattern` with each '%' replaced by the next argument (a table of text is smaller in flash than a
  // call per piece; no pattern holds a '%' of its own).
  Text& Format(std::string_view pattern, std::initializer_list<Arg> args) {
    const Arg* next = args.begin();
    while (open_) {
      const std::size_t mark = pattern.find('%');
      *this << pattern.substr(0, mark);
      if (mark == std::string_view::npos || next == args.end()) break;
      Put(*next++);
      pattern.remove_prefix(mark + 1);
    }
    return *this;
  }

 private:
  void Put(const Arg& arg) {
    switch (arg.kind) {
      case Arg::Kind::kDec:
        Dec(arg.number);
        return;
      case Arg::Kind::kText:
        *this << arg.text;
        return;
      case Arg::Kind::kHex:
        Hex(static_cast<std::uint32_t>(arg.number), arg.digits);
        return;
      case Arg::Kind::kPath:
        Path(arg.path);
        return;
    }
  }

  EdsSink& sink_;
  bool open_ = true;
};

// ---- [File], [Device] --------------------------------------------------------------------------------

void WriteHeader(DriveModel model, Text& out) {
  const std::string_view name = ProductNameOf(model);
  // The EDS changes with the firmware: its revision is the Identity revision.
  out.Format(
      "$ EDS of the IPE002Z EtherNet/IP option card on a Toshiba % inverter.\n"
      "$ Generated from the card firmware's own tables (docs/eds.md); the card serves the same bytes.\n"
      "\n[File]\n    DescText = \"IPE002Z EtherNet/IP option card on a %\";\n"
      "    CreateDate = 11-27-2026;\n    CreateTime = 12:00:00;\n    ModDate = 11-27-2026;\n    ModTime = 12:00:00;\n"
      "    Revision = %.%;\n"
      "\n[Device]\n    VendCode = %;\n    VendName = \"Toshiba\";\n    ProdType = %;\n    ProdTypeStr = \"AC Drive\";\n"
      "    ProdCode = %;\n    MajRev = %;\n    MinRev = %;\n    ProdName = \"%\";\n    Catalog = \"IPE002Z\";\n"
      "\n[Device Classification]\n    Class1 = EtherNetIP;\n",
      {name, name, kMajorRevision, kMinorRevision, kVendorIdToshiba, kDeviceTypeAcDrive, ProductCodeOf(model),
       kMajorRevision, kMinorRevision, name});
}

// ---- [Params], [Groups] -------------------------------------------------------------------------------

// The RPI parameter the connections refer to: the last one, after the table's.
std::size_t RpiParam() { return drive_link::CardParameters().size() + 1; }

void WriteTableParam(std::size_t number, const ParameterInfo& row, drive_link::InverterModel model, Text& out) {
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
  const drive_link::ParameterLimits& limits = row.Limits(model);
  // Three lines: reserved, link path size and path, descriptor, type, size; name, units, help; min, max,
  // default, scaling multiplier, divisor, base, offset, the four scaling links (none), decimal places.
  out.Format("\n    Param% =\n        0, %,%, %, %, 2,\n        \"%\", \"%\", \"%\",\n        %,%,%, 1,%,1,0, ,,,, %;",
             {static_cast<std::int32_t>(number), static_cast<std::int32_t>(size),
              Arg(std::span<const std::uint8_t>(path).first(size)), Arg::Hex(drive::ParameterDescriptor(row), 4),
              Arg::Hex(drive::ParameterDataType(row), 2), row.title, row.unit, row.help, row.Value(limits.min),
              row.Value(limits.max), row.Value(limits.default_value), drive::ScalingDivisor(row), row.decimals});
}

void WriteParams(DriveModel model, Text& out) {
  out << "\n[Params]";
  const std::span<const ParameterInfo> rows = drive_link::CardParameters();
  const drive_link::InverterModel inverter = drive::InverterModelOf(model);
  for (std::size_t i = 0; i < rows.size() && out.open(); ++i) WriteTableParam(i + 1, rows[i], inverter, out);
  // The RPI of every connection (µs): the Connection Manager's floor and ceiling.
  constexpr ConnectionManagerOptions kCard;
  out.Format("\n    Param% =\n        0, ,, 0x0000, 0xC8, 4,\n"
             "        \"RPI\", \"us\", \"Requested packet interval of an I/O connection\",\n"
             "        %,%,10000, ,,,, ,,,, ;\n",
             {static_cast<std::int32_t>(RpiParam()), static_cast<std::int32_t>(kCard.min_rpi),
              static_cast<std::int32_t>(kCard.max_rpi)});
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
    const auto in_group = [&group](const ParameterInfo& row) {
      return row.number >= group.first && row.number <= group.last;
    };
    std::int32_t count = 0;
    for (const ParameterInfo& row : rows) count += in_group(row) ? 1 : 0;
    out.Format("\n    Group% =\n        \"%\", %", {static_cast<std::int32_t>(g + 1), group.name, count});
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
  const std::optional<std::size_t> row = drive_link::FindParameterByNumber(reg);
  if (row) out.Format("Param%", {static_cast<std::int32_t>(*row + 1)});
}

void WriteAssemblies(Text& out) {
  out << "\n[Assembly]\n    Object_Name = \"Assembly Object\";\n    Object_Class_Code = 0x04;";
  for (const AssemblyText& assembly : kAssemblies) {
    // Members are the 16-bit words of the largest size (100/150: 8 words; a connection may use fewer).
    const std::size_t size = drive::AssemblySize(assembly.instance);
    out.Format("\n    Assem% =\n        \"%\",\n        %,\n        %,\n        0x0000,\n        ,,\n        ",
               {assembly.instance, assembly.name, Arg(std::span<const std::uint8_t>(AssemblyPath(assembly.instance))),
                static_cast<std::int32_t>(size)});
    for (std::size_t word = 0; word < size / 2; ++word) {
      if (word != 0) out << ",";
      WriteMember(word == 0 ? assembly.word1 : word == 1 ? assembly.word2 : kNoRegister, out);
    }
    out << ";";
  }
  const std::array<std::uint8_t, 6> heartbeat = AssemblyPath(drive::kInputOnlyHeartbeat);
  out.Format("\n    Assem% =\n        \"Input-only heartbeat\",\n"
             "        %,\n        0,\n        0x0000,\n        ,,;\n",
             {drive::kInputOnlyHeartbeat, Arg(std::span<const std::uint8_t>(heartbeat))});
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
  out.Format("\n    Connection% =\n        %,\n        %,\n        Param%,%,",
             {number, Arg::Hex(kind.trigger_transport, 8), Arg::Hex(kind.parameters, 8),
              static_cast<std::int32_t>(RpiParam()),
              owner ? static_cast<std::int32_t>(drive::AssemblySize(consumed)) : 0});
  if (consumed != drive::kListenOnlyHeartbeat) out.Format("Assem%", {consumed});  // 198: a point, no instance
  out.Format(",\n        Param%,%,Assem%,\n        ,,\n        ,,\n        \"%",
             {static_cast<std::int32_t>(RpiParam()), static_cast<std::int32_t>(drive::AssemblySize(produced)),
              produced, kind.name});
  if (owner) out.Format("%/", {consumed});
  const std::array<std::uint8_t, 8> path = {0x20,
                                            0x04,
                                            0x24,
                                            static_cast<std::uint8_t>(drive::kConfigurationInstance),
                                            0x2C,
                                            static_cast<std::uint8_t>(consumed),
                                            0x2C,
                                            static_cast<std::uint8_t>(produced)};
  out.Format("%\",\n        \"\",\n        %;", {produced, Arg(std::span<const std::uint8_t>(path))});
}

void WriteConnections(Text& out) {
  out << "\n[Connection Manager]\n    Object_Name = \"Connection Manager Object\";\n    Object_Class_Code = 0x06;";
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
  out.Format("\n[%]\n    Revision = %;\n    Object_Name = \"%\";\n    Object_Class_Code = %;\n    MaxInst = %;\n"
             "    Number_Of_Static_Instances = %;\n    Max_Number_Of_Dynamic_Instances = 0;\n",
             {section, revision, name, Arg::Hex(class_id, 2), static_cast<std::int32_t>(instances),
              static_cast<std::int32_t>(instances)});
}

void WriteTail(Text& out) {
  constexpr ConnectionManagerOptions kCard;
  out.Format("\n[Port]\n    Port1 = TCP, \"EtherNet/IP\", \"20 F5 24 01\", %;\n"
             "\n[Capacity]\n    MaxMsgConnections = %;\n    MaxIOProduceConsume = %;\n    MaxConsumersPerMcast = %;\n"
             "    TSpec1 = TxRx, %, %;\n",
             {kPortNumber, static_cast<std::int32_t>(kMaxExplicitConnections), kMaxCipConnections,
              static_cast<std::int32_t>(kCard.max_connections_per_point),
              static_cast<std::int32_t>(drive::kMaxAssemblySize), static_cast<std::int32_t>(1000000 / kCard.min_rpi)});
  WriteClass("Identity Class", "Identity Object", kIdentityClassRevision, kClassIdentity, 1, out);
  WriteClass("TCP/IP Interface Class", "TCP/IP Interface Object", kTcpIpClassRevision, kClassTcpIpInterface, 1, out);
  WriteClass("Ethernet Link Class", "Ethernet Link Object", kEthernetLinkClassRevision, kClassEthernetLink,
             kEthernetLinkInstances, out);
  WriteClass("DLR Class", "Device Level Ring Object", kDlrClassRevision, kClassDlr, 1, out);
  WriteClass("QoS Class", "QoS Object", kQosClassRevision, kClassQos, 1, out);
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
