// The Toshiba inverter protocol codec against every worked example of the VF-S11 communications manual
// (E6581222, seed 003): exact bytes both ways, the manual's error cases, every truncation of every
// example, and encode -> decode round trips. Page numbers are the manual's own.
#include "drive_link/wire/toshiba_frame.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <optional>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

namespace drive_link::wire {

// Readable failure messages for the codec's structs (found by GoogleTest through ADL).
void PrintTo(const InverterAddress& a, std::ostream* os) {
  *os << "addr(" << static_cast<int>(a.kind) << "," << static_cast<int>(a.value) << ")";
}
void PrintTo(const Envelope& e, std::ostream* os) {
  *os << (e.mode == Mode::kAscii ? "ascii " : "binary ");
  PrintTo(e.address, os);
  *os << " sum=" << e.ascii_checksum << " stop=" << e.ascii_stop_code;
}
void PrintTo(const Request& r, std::ostream* os) {
  PrintTo(r.envelope, os);
  *os << " " << static_cast<char>(r.command) << std::hex << " no=" << r.comm_number << " data=" << r.data
      << std::dec << " digits=" << static_cast<int>(r.ascii_data_digits);
}
void PrintTo(const Reply& r, std::ostream* os) {
  PrintTo(r.envelope, os);
  *os << " " << static_cast<char>(r.command) << (r.tripped ? " tripped" : "") << std::hex
      << " no=" << r.comm_number << " data=" << r.data << std::dec;
}
void PrintTo(const ErrorReply& r, std::ostream* os) {
  PrintTo(r.envelope, os);
  *os << (r.tripped ? " n" : " N") << static_cast<int>(r.code);
}
void PrintTo(const BlockRequest& b, std::ostream* os) {
  PrintTo(b.address, os);
  *os << " X nW=" << static_cast<int>(b.write_count) << " nR=" << static_cast<int>(b.read_count) << std::hex;
  for (std::uint16_t w : b.write_data) *os << " " << w;
  *os << std::dec;
}
void PrintTo(const BlockReply& b, std::ostream* os) {
  PrintTo(b.address, os);
  *os << (b.tripped ? " y" : " Y") << " nR=" << static_cast<int>(b.read_count)
      << " wstat=" << static_cast<int>(b.write_status) << std::hex;
  for (std::uint16_t w : b.read_data) *os << " " << w;
  *os << std::dec;
}
void PrintTo(FrameFault fault, std::ostream* os) { *os << FrameFaultName(fault); }

namespace {

using Bytes = std::vector<std::uint8_t>;

// "2F 52 00 00 81" -> bytes.
Bytes Hex(std::string_view text) {
  Bytes bytes;
  std::size_t i = 0;
  while (i < text.size()) {
    if (text[i] == ' ') {
      ++i;
      continue;
    }
    bytes.push_back(static_cast<std::uint8_t>(std::stoi(std::string(text.substr(i, 2)), nullptr, 16)));
    i += 2;
  }
  return bytes;
}

// An ASCII frame as the manual prints it, "CR" left off: "(RFE03)" -> "(RFE03)\r".
Bytes Ascii(std::string_view text) {
  Bytes bytes(text.begin(), text.end());
  bytes.push_back(kCarriageReturn);
  return bytes;
}

template <typename T, typename Encoder>
Bytes EncodeWith(Encoder encode, const T& value) {
  std::array<std::uint8_t, kMaxFrameLength> buffer{};
  const base::Result<std::size_t> length = encode(value, std::span<std::uint8_t>(buffer));
  EXPECT_TRUE(length.ok()) << base::StatusName(length.status());
  if (!length.ok()) return {};
  return Bytes(buffer.begin(), buffer.begin() + static_cast<std::ptrdiff_t>(*length));
}
Bytes Encode(const Request& r) { return EncodeWith(EncodeRequest, r); }
Bytes Encode(const Reply& r) { return EncodeWith(EncodeReply, r); }
Bytes Encode(const ErrorReply& r) { return EncodeWith(EncodeErrorReply, r); }
Bytes Encode(const BlockRequest& r) { return EncodeWith(EncodeBlockRequest, r); }
Bytes Encode(const BlockReply& r) { return EncodeWith(EncodeBlockReply, r); }

using Kind = InverterAddress::Kind;
constexpr InverterAddress kOmitted = InverterAddress::Omitted();

Envelope BinaryEnvelope(InverterAddress address = kOmitted) {
  return {.mode = Mode::kBinary, .address = address};
}
// The manual's ASCII examples carry the stop code ")" and, unless they show "&", no checksum.
Envelope AsciiEnvelope(InverterAddress address = kOmitted, bool checksum = false, bool stop_code = true) {
  return {.mode = Mode::kAscii, .address = address, .ascii_checksum = checksum, .ascii_stop_code = stop_code};
}

Request MakeRequest(Envelope envelope, Command command, std::uint16_t number, std::uint16_t data = 0,
                    std::uint8_t digits = 4) {
  return {.envelope = envelope, .command = command, .comm_number = number, .data = data,
          .ascii_data_digits = digits};
}
Reply MakeReply(Envelope envelope, Command command, std::uint16_t number, std::uint16_t data,
                bool tripped = false) {
  return {.envelope = envelope, .command = command, .tripped = tripped, .comm_number = number, .data = data};
}

// --- The manual's examples, as tables ---

struct RequestExample {
  const char* name;
  Bytes wire;
  Request request;
};
struct ReplyExample {
  const char* name;
  Bytes wire;
  Reply reply;
};
struct ErrorReplyExample {
  const char* name;
  Bytes wire;
  ErrorReply reply;
};
struct BlockRequestExample {
  const char* name;
  Bytes wire;
  BlockRequest request;
  BlockWriteLimit limit;
};
struct BlockReplyExample {
  const char* name;
  Bytes wire;
  BlockReply reply;
};

std::vector<RequestExample> BinaryRequestExamples() {
  const Envelope b = BinaryEnvelope();
  return {
      {"p11 checksum example 2F 52 00 (sum)", Hex("2F 52 00 00 81"), MakeRequest(b, Command::kRead, 0x0000)},
      {"p18 W decel time 10 s", Hex("2F 57 00 10 00 64 FA"), MakeRequest(b, Command::kWrite, 0x0010, 0x0064)},
      {"p19 P emergency stop", Hex("2F 50 FA 00 90 00 09"), MakeRequest(b, Command::kWriteRam, 0xFA00, 0x9000)},
      {"p19 R current", Hex("2F 52 FE 03 82"), MakeRequest(b, Command::kRead, 0xFE03)},
      {"p19 G current", Hex("2F 47 FE 03 00 00 77"), MakeRequest(b, Command::kReadTwoWire, 0xFE03, 0x0000)},
      {"p22 broadcast 60 Hz", Hex("2F FF 50 FA 01 17 70 00"),
       MakeRequest(BinaryEnvelope(InverterAddress::Broadcast()), Command::kWriteRam, 0xFA01, 0x1770)},
      {"p24 set 60 Hz", Hex("2F 50 FA 01 17 70 01"), MakeRequest(b, Command::kWriteRam, 0xFA01, 0x1770)},
      {"p24 forward run", Hex("2F 50 FA 00 C4 00 3D"), MakeRequest(b, Command::kWriteRam, 0xFA00, 0xC400)},
      {"p24 monitor frequency", Hex("2F 52 FD 00 7E"), MakeRequest(b, Command::kRead, 0xFD00)},
      {"p24 monitor status", Hex("2F 52 FD 01 7F"), MakeRequest(b, Command::kRead, 0xFD01)},
      {"p24 trip code", Hex("2F 52 FC 90 0D"), MakeRequest(b, Command::kRead, 0xFC90)},
  };
}

std::vector<ReplyExample> BinaryReplyExamples() {
  const Envelope b = BinaryEnvelope();
  return {
      {"p18 W echo", Hex("2F 57 00 10 00 64 FA"), MakeReply(b, Command::kWrite, 0x0010, 0x0064)},
      {"p19 P echo", Hex("2F 50 FA 00 90 00 09"), MakeReply(b, Command::kWriteRam, 0xFA00, 0x9000)},
      {"p19 R current 19.15 %", Hex("2F 52 FE 03 07 7B 04"), MakeReply(b, Command::kRead, 0xFE03, 0x077B)},
      {"p19 G current 19.15 %", Hex("2F 47 FE 03 07 7B F9"), MakeReply(b, Command::kReadTwoWire, 0xFE03, 0x077B)},
      {"p22 broadcast answered by 00", Hex("2F 00 50 FA 01 17 70 01"),
       MakeReply(BinaryEnvelope(InverterAddress::Number(0)), Command::kWriteRam, 0xFA01, 0x1770)},
      {"p24 set 60 Hz echo", Hex("2F 50 FA 01 17 70 01"), MakeReply(b, Command::kWriteRam, 0xFA01, 0x1770)},
      {"p24 forward run echo", Hex("2F 50 FA 00 C4 00 3D"), MakeReply(b, Command::kWriteRam, 0xFA00, 0xC400)},
      {"p24 frequency 60 Hz", Hex("2F 52 FD 00 17 70 05"), MakeReply(b, Command::kRead, 0xFD00, 0x1770)},
      {"p24 status while tripped", Hex("2F 72 FD 01 00 03 A2"),
       MakeReply(b, Command::kRead, 0xFD01, 0x0003, /*tripped=*/true)},
      {"p24 trip code err5", Hex("2F 72 FC 90 00 18 45"),
       MakeReply(b, Command::kRead, 0xFC90, 0x0018, /*tripped=*/true)},
  };
}

std::vector<ErrorReplyExample> BinaryErrorReplyExamples() {
  const Envelope b = BinaryEnvelope();
  return {
      {"p13 impossible to execute", Hex("2F 4E 00 00 7D"), {b, false, ErrorCode::kImpossibleToExecute}},
      {"p13 data error", Hex("2F 4E 00 01 7E"), {b, false, ErrorCode::kDataError}},
      {"p13 no communication number", Hex("2F 4E 00 02 7F"), {b, false, ErrorCode::kCommunicationNumberError}},
      {"p13/p17 checksum error", Hex("2F 4E 00 04 81"), {b, false, ErrorCode::kChecksumError}},
  };
}

std::vector<BlockRequestExample> BlockRequestExamples() {
  return {
      {"p16/p20 run 60 Hz and monitor", Hex("2F 58 02 05 C4 00 17 70 D9"),
       {.address = kOmitted, .write_count = 2, .read_count = 5, .write_data = {0xC400, 0x1770, 0, 0, 0}},
       BlockWriteLimit::kParameters},
      {"p57 LED display 0123", Hex("2F 58 05 05 00 30 00 31 00 32 00 33 00 03 5A"),
       {.address = kOmitted, .write_count = 5, .read_count = 5, .write_data = {0x30, 0x31, 0x32, 0x33, 0x03}},
       BlockWriteLimit::kLedDisplay},
  };
}

std::vector<BlockReplyExample> BlockReplyExamples() {
  return {
      {"p16 parameters not set", Hex("2F 59 05 03 00 00 00 00 00 00 00 00 00 00 90"),
       {.read_count = 5, .write_status = 0x03, .read_data = {0, 0, 0, 0, 0}}},
      {"p16 parameters set, stopped", Hex("2F 59 05 00 40 00 00 00 00 00 00 00 00 00 CD"),
       {.read_count = 5, .write_status = 0, .read_data = {0x4000, 0, 0, 0, 0}}},
      {"p16/p20 running at 60 Hz", Hex("2F 59 05 00 64 00 17 70 1A 8A 24 FD 00 00 3D"),
       {.read_count = 5, .write_status = 0, .read_data = {0x6400, 0x1770, 0x1A8A, 0x24FD, 0x0000}}},
      {"p57 LED display was dAtA", Hex("2F 59 05 00 00 64 00 41 00 74 00 41 00 00 E7"),
       {.read_count = 5, .write_status = 0, .read_data = {0x64, 0x41, 0x74, 0x41, 0x00}}},
  };
}

std::vector<RequestExample> AsciiRequestExamples() {
  const Envelope a = AsciiEnvelope();
  const Envelope with_sum = AsciiEnvelope(kOmitted, /*checksum=*/true);
  return {
      {"p8 checksum example (R0000&sum)", Ascii("(R0000&60)"), MakeRequest(with_sum, Command::kRead, 0x0000)},
      {"p9 one-digit-group read (*2R0000)", Ascii("(*2R0000)"),
       MakeRequest(AsciiEnvelope(InverterAddress::OnesDigitGroup(2)), Command::kRead, 0x0000)},
      {"p9 short data (W123412)", Ascii("(W123412)"), MakeRequest(a, Command::kWrite, 0x1234, 0x0012, 2)},
      {"p18 W decel time", Ascii("(W00100064)"), MakeRequest(a, Command::kWrite, 0x0010, 0x0064)},
      {"p19 P emergency stop", Ascii("(PFA009000)"), MakeRequest(a, Command::kWriteRam, 0xFA00, 0x9000)},
      {"p19 R current", Ascii("(RFE03)"), MakeRequest(a, Command::kRead, 0xFE03)},
      {"p22 overall broadcast", Ascii("(**PFA011770)"),
       MakeRequest(AsciiEnvelope(InverterAddress::Broadcast()), Command::kWriteRam, 0xFA01, 0x1770)},
      {"p22 group broadcast *9", Ascii("(*9PFA011770)"),
       MakeRequest(AsciiEnvelope(InverterAddress::OnesDigitGroup(9)), Command::kWriteRam, 0xFA01, 0x1770)},
      {"p24 set 60 Hz", Ascii("(PFA011770)"), MakeRequest(a, Command::kWriteRam, 0xFA01, 0x1770)},
      {"p24 forward run", Ascii("(PFA00C400)"), MakeRequest(a, Command::kWriteRam, 0xFA00, 0xC400)},
      {"p24 monitor frequency", Ascii("(RFD00)"), MakeRequest(a, Command::kRead, 0xFD00)},
      {"p24 monitor status", Ascii("(RFD01)"), MakeRequest(a, Command::kRead, 0xFD01)},
      {"p24 trip code", Ascii("(RFC90)"), MakeRequest(a, Command::kRead, 0xFC90)},
      // Program 2 (p.26) sends "(" + text + "&" + sum + ")"; the manual prints only the typed text, so the
      // sums here are computed by its BASIC rule. The W echo below shows the manual's own sum (36).
      {"p26 program 2 read max frequency", Ascii("(R0011&62)"), MakeRequest(with_sum, Command::kRead, 0x0011)},
      {"p26 program 2 write max frequency", Ascii("(W00111770&36)"),
       MakeRequest(with_sum, Command::kWrite, 0x0011, 0x1770)},
      {"p27 program 3 with inverter number", Ascii("(00R0011)"),
       MakeRequest(AsciiEnvelope(InverterAddress::Number(0)), Command::kRead, 0x0011)},
      {"p27 program 3 without inverter number", Ascii("(R0011)"), MakeRequest(a, Command::kRead, 0x0011)},
      {"p42 timer off to EEPROM (W08030)", Ascii("(W08030)"), MakeRequest(a, Command::kWrite, 0x0803, 0x0000, 1)},
  };
}

std::vector<ReplyExample> AsciiReplyExamples() {
  const Envelope a = AsciiEnvelope();
  const Envelope with_sum = AsciiEnvelope(kOmitted, /*checksum=*/true);
  return {
      {"p9 group read answered by 02", Ascii("(02R00000000)"),
       MakeReply(AsciiEnvelope(InverterAddress::Number(2)), Command::kRead, 0x0000, 0x0000)},
      {"p9 short data padded", Ascii("(W12340012)"), MakeReply(a, Command::kWrite, 0x1234, 0x0012)},
      {"p18 W echo", Ascii("(W00100064)"), MakeReply(a, Command::kWrite, 0x0010, 0x0064)},
      {"p19 P echo", Ascii("(PFA009000)"), MakeReply(a, Command::kWriteRam, 0xFA00, 0x9000)},
      {"p19 R current", Ascii("(RFE03077B)"), MakeReply(a, Command::kRead, 0xFE03, 0x077B)},
      {"p22 broadcast answered by 00", Ascii("(00PFA011770)"),
       MakeReply(AsciiEnvelope(InverterAddress::Number(0)), Command::kWriteRam, 0xFA01, 0x1770)},
      {"p22 group answered by 09", Ascii("(09PFA011770)"),
       MakeReply(AsciiEnvelope(InverterAddress::Number(9)), Command::kWriteRam, 0xFA01, 0x1770)},
      {"p24 set 60 Hz echo", Ascii("(PFA011770)"), MakeReply(a, Command::kWriteRam, 0xFA01, 0x1770)},
      {"p24 forward run echo", Ascii("(PFA00C400)"), MakeReply(a, Command::kWriteRam, 0xFA00, 0xC400)},
      {"p24 frequency 60 Hz", Ascii("(RFD001770)"), MakeReply(a, Command::kRead, 0xFD00, 0x1770)},
      {"p24 status while tripped", Ascii("(rFD010003)"), MakeReply(a, Command::kRead, 0xFD01, 0x0003, true)},
      {"p24 trip code err5", Ascii("(rFC900018)"), MakeReply(a, Command::kRead, 0xFC90, 0x0018, true)},
      {"p26 max frequency 80 Hz", Ascii("(R00111F40&3D)"), MakeReply(with_sum, Command::kRead, 0x0011, 0x1F40)},
      {"p26 write max frequency echo", Ascii("(W00111770&36)"),
       MakeReply(with_sum, Command::kWrite, 0x0011, 0x1770)},
      {"p26 max frequency 60 Hz", Ascii("(R00111770&31)"), MakeReply(with_sum, Command::kRead, 0x0011, 0x1770)},
      {"p27 program 3 with inverter number", Ascii("(00R00111770)"),
       MakeReply(AsciiEnvelope(InverterAddress::Number(0)), Command::kRead, 0x0011, 0x1770)},
      {"p27 program 3 without inverter number", Ascii("(R00111770)"),
       MakeReply(a, Command::kRead, 0x0011, 0x1770)},
      {"p42 timer off echo padded", Ascii("(W08030000)"), MakeReply(a, Command::kWrite, 0x0803, 0x0000)},
  };
}

std::vector<ErrorReplyExample> AsciiErrorReplyExamples() {
  const Envelope e = AsciiEnvelope(kOmitted, /*checksum=*/true);
  return {
      {"p10 impossible to execute", Ascii("(N0000&5C)"), {e, false, ErrorCode::kImpossibleToExecute}},
      {"p10 data error", Ascii("(N0001&5D)"), {e, false, ErrorCode::kDataError}},
      {"p10 no communication number", Ascii("(N0002&5E)"), {e, false, ErrorCode::kCommunicationNumberError}},
      {"p10 command error", Ascii("(N0003&5F)"), {e, false, ErrorCode::kCommandError}},
      {"p10 checksum error", Ascii("(N0004&60)"), {e, false, ErrorCode::kChecksumError}},
  };
}

template <typename Example>
std::vector<Example> Concat(std::vector<Example> a, const std::vector<Example>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}
std::vector<RequestExample> AllRequestExamples() {
  return Concat(BinaryRequestExamples(), AsciiRequestExamples());
}
std::vector<ReplyExample> AllReplyExamples() { return Concat(BinaryReplyExamples(), AsciiReplyExamples()); }
std::vector<ErrorReplyExample> AllErrorReplyExamples() {
  return Concat(BinaryErrorReplyExamples(), AsciiErrorReplyExamples());
}

// Every complete frame of the manual, as the receiving side sees it.
std::vector<Bytes> AllRequestFrames() {
  std::vector<Bytes> frames;
  for (const auto& e : AllRequestExamples()) frames.push_back(e.wire);
  for (const auto& e : BlockRequestExamples()) frames.push_back(e.wire);
  return frames;
}
std::vector<Bytes> AllReplyFrames() {
  std::vector<Bytes> frames;
  for (const auto& e : AllReplyExamples()) frames.push_back(e.wire);
  for (const auto& e : AllErrorReplyExamples()) frames.push_back(e.wire);
  for (const auto& e : BlockReplyExamples()) frames.push_back(e.wire);
  return frames;
}

// The 29 distinct binary frames of the manual: 27 above, the inter-drive S frame and the deliberate
// bad-checksum block request (both tested on their own below).
const Bytes kInterDriveExample = Hex("2F 53 FA 01 13 88 18");          // p.20
const Bytes kBadChecksumBlockExample = Hex("2F 58 02 05 C4 00 17 70 D8");  // p.17

TEST(ToshibaManualExamples, CountsMatchTheManual) {
  std::vector<Bytes> binary = {kInterDriveExample, kBadChecksumBlockExample};
  for (const Bytes& frame : AllRequestFrames()) {
    if (frame[0] == kBinaryStartCode) binary.push_back(frame);
  }
  for (const Bytes& frame : AllReplyFrames()) {
    if (frame[0] == kBinaryStartCode) binary.push_back(frame);
  }
  std::sort(binary.begin(), binary.end());
  binary.erase(std::unique(binary.begin(), binary.end()), binary.end());
  EXPECT_EQ(binary.size(), 29U);
}

// --- Checksums ---

TEST(ToshibaChecksum, BinaryManualExample_2F52000000_Is81) {
  EXPECT_EQ(BinaryChecksum(Hex("2F 52 00 00")), 0x81);
}

TEST(ToshibaChecksum, EveryBinaryExampleEndsInItsChecksum) {
  std::vector<Bytes> frames = AllRequestFrames();
  const std::vector<Bytes> replies = AllReplyFrames();
  frames.insert(frames.end(), replies.begin(), replies.end());
  frames.push_back(kInterDriveExample);
  for (const Bytes& frame : frames) {
    if (frame[0] != kBinaryStartCode) continue;
    EXPECT_EQ(BinaryChecksum(std::span(frame).first(frame.size() - 1)), frame.back());
  }
}

TEST(ToshibaChecksum, AsciiManualExamples_AllNine) {
  struct Case {
    const char* area;  // "(" through "&"
    const char* sum;
  };
  const Case cases[] = {{"(R0000&", "60"},      {"(N0000&", "5C"},      {"(N0001&", "5D"},
                        {"(N0002&", "5E"},      {"(N0003&", "5F"},      {"(N0004&", "60"},
                        {"(R00111F40&", "3D"}, {"(W00111770&", "36"}, {"(R00111770&", "31"}};
  for (const Case& c : cases) {
    const std::string_view area(c.area);
    const std::array<std::uint8_t, 2> sum = AsciiChecksum(Bytes(area.begin(), area.end()));
    EXPECT_EQ(std::string(sum.begin(), sum.end()), c.sum) << c.area;
  }
}

TEST(ToshibaChecksum, AsciiSumIsUppercaseHex) {
  const Bytes area = {'(', 'W', 'F', 'A', '0', '1', 'F', 'F', 'F', 'F', '&'};  // sum 0x3A5 -> "A5"
  const std::array<std::uint8_t, 2> sum = AsciiChecksum(area);
  EXPECT_EQ(sum[0], 'A');
  EXPECT_EQ(sum[1], '5');
}

// --- Exact bytes, both directions ---

TEST(ToshibaRequest, ManualExamples_EncodeExactBytes) {
  for (const RequestExample& e : AllRequestExamples()) {
    EXPECT_EQ(Encode(e.request), e.wire) << e.name;
  }
}

TEST(ToshibaRequest, ManualExamples_DecodeToTheirFields) {
  for (const RequestExample& e : AllRequestExamples()) {
    const DecodedRequest decoded = DecodeRequest(e.wire);
    EXPECT_EQ(decoded.fault, FrameFault::kNone) << e.name;
    EXPECT_EQ(decoded.kind, RequestKind::kRegister) << e.name;
    EXPECT_EQ(decoded.request, e.request) << e.name;
  }
}

TEST(ToshibaReply, ManualExamples_EncodeExactBytes) {
  for (const ReplyExample& e : AllReplyExamples()) {
    EXPECT_EQ(Encode(e.reply), e.wire) << e.name;
  }
}

TEST(ToshibaReply, ManualExamples_DecodeToTheirFields) {
  for (const ReplyExample& e : AllReplyExamples()) {
    const DecodedReply decoded = DecodeReply(e.wire);
    EXPECT_EQ(decoded.fault, FrameFault::kNone) << e.name;
    EXPECT_EQ(decoded.kind, ReplyKind::kRegister) << e.name;
    EXPECT_EQ(decoded.reply, e.reply) << e.name;
  }
}

TEST(ToshibaErrorReply, ManualExamples_EncodeExactBytes) {
  for (const ErrorReplyExample& e : AllErrorReplyExamples()) {
    EXPECT_EQ(Encode(e.reply), e.wire) << e.name;
  }
}

TEST(ToshibaErrorReply, ManualExamples_DecodeToTheirCodes) {
  for (const ErrorReplyExample& e : AllErrorReplyExamples()) {
    const DecodedReply decoded = DecodeReply(e.wire);
    EXPECT_EQ(decoded.fault, FrameFault::kNone) << e.name;
    EXPECT_EQ(decoded.kind, ReplyKind::kError) << e.name;
    EXPECT_EQ(decoded.error, e.reply) << e.name;
  }
}

TEST(ToshibaBlockRequest, ManualExamples_EncodeExactBytes) {
  for (const BlockRequestExample& e : BlockRequestExamples()) {
    EXPECT_EQ(Encode(e.request), e.wire) << e.name;
  }
}

TEST(ToshibaBlockRequest, ManualExamples_DecodeToTheirFields) {
  for (const BlockRequestExample& e : BlockRequestExamples()) {
    const DecodedRequest decoded = DecodeRequest(e.wire, e.limit);
    EXPECT_EQ(decoded.fault, FrameFault::kNone) << e.name;
    EXPECT_EQ(decoded.kind, RequestKind::kBlock) << e.name;
    EXPECT_EQ(decoded.block, e.request) << e.name;
  }
}

TEST(ToshibaBlockReply, ManualExamples_EncodeExactBytes) {
  for (const BlockReplyExample& e : BlockReplyExamples()) {
    EXPECT_EQ(Encode(e.reply), e.wire) << e.name;
  }
}

TEST(ToshibaBlockReply, ManualExamples_DecodeToTheirFields) {
  for (const BlockReplyExample& e : BlockReplyExamples()) {
    const DecodedReply decoded = DecodeReply(e.wire);
    EXPECT_EQ(decoded.fault, FrameFault::kNone) << e.name;
    EXPECT_EQ(decoded.kind, ReplyKind::kBlock) << e.name;
    EXPECT_EQ(decoded.block, e.reply) << e.name;
  }
}

// A few single examples under their own names, so a regression names the frame.
TEST(ToshibaBinaryRequest, ReadExample_EncodesExactBytes) {
  EXPECT_EQ(Encode(MakeRequest(BinaryEnvelope(), Command::kRead, 0xFE03)), Hex("2F 52 FE 03 82"));
}

TEST(ToshibaBinaryReply, TrippedStatus_DecodesLowercaseAsTripped) {
  const DecodedReply decoded = DecodeReply(Hex("2F 72 FD 01 00 03 A2"));
  ASSERT_TRUE(decoded.ok());
  EXPECT_TRUE(decoded.reply.tripped);
  EXPECT_EQ(decoded.reply.command, Command::kRead);
  EXPECT_EQ(decoded.reply.data, 0x0003);
}

TEST(ToshibaAsciiRequest, ChecksumExample_EncodesExactBytes) {
  const Request request = MakeRequest(AsciiEnvelope(kOmitted, /*checksum=*/true), Command::kRead, 0x0000);
  EXPECT_EQ(Encode(request), Ascii("(R0000&60)"));
}

TEST(ToshibaAsciiReply, TrippedTripCode_DecodesLowercaseAsTripped) {
  const DecodedReply decoded = DecodeReply(Ascii("(rFC900018)"));
  ASSERT_TRUE(decoded.ok());
  EXPECT_TRUE(decoded.reply.tripped);
  EXPECT_EQ(decoded.reply.comm_number, 0xFC90);
  EXPECT_EQ(decoded.reply.data, 0x0018);
}

// --- Exchanges: what the simulated inverter answers to the manual's requests ---

// The inverter side of one exchange: decode, then answer with `data` from inverter `own_number`.
Bytes Answer(const Bytes& request_frame, std::uint8_t own_number, std::uint16_t data) {
  const DecodedRequest decoded = DecodeRequest(request_frame);
  EXPECT_TRUE(decoded.ok()) << FrameFaultName(decoded.fault);
  const Request& request = decoded.request;
  EXPECT_EQ(ResolveAddress(request.envelope.mode, request.envelope.address, own_number),
            Addressing::kExecuteAndReply);
  return Encode(MakeReply(ReplyEnvelope(request.envelope, own_number), request.command, request.comm_number,
                          data));
}

TEST(ToshibaExchange, AsciiShortWriteData_EchoIsPaddedToFourDigits) {
  EXPECT_EQ(Answer(Ascii("(W123412)"), 0, 0x0012), Ascii("(W12340012)"));
  EXPECT_EQ(Answer(Ascii("(W08030)"), 0, 0x0000), Ascii("(W08030000)"));
}

TEST(ToshibaExchange, AsciiBroadcasts_RepresentativeAnswersWithItsOwnNumber) {
  EXPECT_EQ(Answer(Ascii("(**PFA011770)"), 0, 0x1770), Ascii("(00PFA011770)"));
  EXPECT_EQ(Answer(Ascii("(*9PFA011770)"), 9, 0x1770), Ascii("(09PFA011770)"));
  EXPECT_EQ(Answer(Ascii("(*2R0000)"), 2, 0x0000), Ascii("(02R00000000)"));
}

TEST(ToshibaExchange, BinaryBroadcast_ReplierSubstitutesItsNumberAndChecksum) {
  EXPECT_EQ(Answer(Hex("2F FF 50 FA 01 17 70 00"), 0, 0x1770), Hex("2F 00 50 FA 01 17 70 01"));
}

TEST(ToshibaExchange, AsciiChecksumAndInverterNumber_AreMirrored) {
  EXPECT_EQ(Answer(Ascii("(R0011&62)"), 0, 0x1F40), Ascii("(R00111F40&3D)"));
  EXPECT_EQ(Answer(Ascii("(00R0011)"), 0, 0x1770), Ascii("(00R00111770)"));
  EXPECT_EQ(Answer(Ascii("(R0011)"), 0, 0x1770), Ascii("(R00111770)"));
}

TEST(ToshibaExchange, BinaryReadAndTwoWireRead_ReturnTheValue) {
  EXPECT_EQ(Answer(Hex("2F 52 FE 03 82"), 0, 0x077B), Hex("2F 52 FE 03 07 7B 04"));
  EXPECT_EQ(Answer(Hex("2F 47 FE 03 00 00 77"), 0, 0x077B), Hex("2F 47 FE 03 07 7B F9"));
}

// --- The manual's failure cases ---

TEST(ToshibaBlockRequest, BadChecksumExample_IsRejectedAndAnsweredWith0004) {
  const DecodedRequest decoded = DecodeRequest(kBadChecksumBlockExample);
  EXPECT_EQ(decoded.fault, FrameFault::kBadChecksum);
  EXPECT_EQ(decoded.kind, RequestKind::kBlock);
  const std::optional<ErrorCode> code = ErrorReplyFor(decoded);
  ASSERT_TRUE(code.has_value());
  const ErrorReply reply{.envelope = {.mode = Mode::kBinary, .address = ReplyAddress(decoded.block.address, 0)},
                         .tripped = false,
                         .code = *code};
  EXPECT_EQ(Encode(reply), Hex("2F 4E 00 04 81"));  // p.17
}

TEST(ToshibaBlockReply, DuplicatedTrailingByteInManual_IsTrailingBytes) {
  // p.16 prints "... 00 CD CD": the 15-byte frame ends at the first CD.
  EXPECT_EQ(DecodeReply(Hex("2F 59 05 00 40 00 00 00 00 00 00 00 00 00 CD CD")).fault, FrameFault::kTrailingBytes);
}

TEST(ToshibaInterDrive, ManualExample_IsRecognisedButUnsupportedAndNeverAnswered) {
  const DecodedRequest decoded = DecodeRequest(kInterDriveExample);
  EXPECT_EQ(decoded.fault, FrameFault::kInterDriveCommand);
  EXPECT_FALSE(ErrorReplyFor(Mode::kBinary, decoded.fault).has_value());
  // Silent whatever its checksum: S is never answered (p.20).
  Bytes corrupted = kInterDriveExample;
  corrupted.back() ^= 0x01;
  EXPECT_EQ(DecodeRequest(corrupted).fault, FrameFault::kInterDriveCommand);
  Bytes tripped_master = Hex("2F 73 FA 01 13 88 38");  // 's': master tripped
  EXPECT_EQ(DecodeRequest(tripped_master).fault, FrameFault::kInterDriveCommand);
}

struct FailureCase {
  const char* name;
  Bytes wire;
  FrameFault fault;
  std::optional<ErrorCode> answer;
};

TEST(ToshibaAsciiRequest, ManualFailureCases_GetTheManualsAnswer) {
  const FailureCase cases[] = {
      {"p21 (R0)))) takes 0))) as the number", Ascii("(R0))))"), FrameFault::kBadCommunicationNumber,
       ErrorCode::kCommunicationNumberError},
      {"p21 (R11) takes 11)CR as the number, no CR", Ascii("(R11)"), FrameFault::kTruncated, std::nullopt},
      {"p10 '}' in the stop-code position", Ascii("(RFE03}"), FrameFault::kBadStopCode, std::nullopt},
      {"p8 one-digit inverter number", Ascii("(0RFE03)"), FrameFault::kBadInverterNumber, std::nullopt},
      {"p27 () gets no reply", Ascii("()"), FrameFault::kTruncated, std::nullopt},
      {"p10 data with too many digits", Ascii("(W001012345)"), FrameFault::kBadData, ErrorCode::kDataError},
      {"p10 bad checksum", Ascii("(R0000&61)"), FrameFault::kBadChecksum, ErrorCode::kChecksumError},
      {"p21 maintenance command", Ascii("(M0000)"), FrameFault::kMaintenanceCommand,
       ErrorCode::kImpossibleToExecute},
      {"read with data", Ascii("(RFE031234)"), FrameFault::kBadData, ErrorCode::kDataError},
      {"over 17 bytes", Ascii("(00W00100064&XX)))"), FrameFault::kTooLong, std::nullopt},
      {"nothing after the CR", Bytes{'(', 'R', 'F', 'E', '0', '3', '\r', '\r'}, FrameFault::kTrailingBytes,
       std::nullopt},
  };
  for (const FailureCase& c : cases) {
    const DecodedRequest decoded = DecodeRequest(c.wire);
    EXPECT_EQ(decoded.fault, c.fault) << c.name;
    EXPECT_EQ(ErrorReplyFor(decoded), c.answer) << c.name;
  }
}

TEST(ToshibaAsciiRequest, CommandErrorsListedInTheManual_AreAnswered0003) {
  // p.10: "Commands other than the R, W and P commands (Ex.: L, S, G, a, b, m, r, t, w ...)".
  for (const char letter : std::string_view("LSGabmrtwX")) {
    const Bytes frame = Ascii(std::string("(") + letter + "0000)");
    const DecodedRequest decoded = DecodeRequest(frame);
    EXPECT_EQ(decoded.fault, FrameFault::kUnknownCommand) << letter;
    EXPECT_EQ(ErrorReplyFor(Mode::kAscii, decoded.fault), ErrorCode::kCommandError) << letter;
  }
}

TEST(ToshibaAsciiRequest, ErrorAnswerMirrorsTheRequestsEnvelope) {
  const DecodedRequest decoded = DecodeRequest(Ascii("(07L0000&C1)"));
  ASSERT_EQ(decoded.fault, FrameFault::kUnknownCommand);
  const ErrorReply reply{.envelope = ReplyEnvelope(decoded.request.envelope, 7), .tripped = true,
                         .code = ErrorCode::kCommandError};
  EXPECT_EQ(Encode(reply), Ascii("(07n0003&E6)"));
}

TEST(ToshibaAsciiRequest, ChecksumIsCheckedBeforeTheCommand) {
  EXPECT_EQ(DecodeRequest(Ascii("(L0000&00)")).fault, FrameFault::kBadChecksum);
}

TEST(ToshibaAsciiRequest, LowercaseHexIsAccepted) {
  const DecodedRequest decoded = DecodeRequest(Ascii("(Pfa01abcd&50)"));
  ASSERT_EQ(decoded.fault, FrameFault::kNone);
  EXPECT_EQ(decoded.request.comm_number, 0xFA01);
  EXPECT_EQ(decoded.request.data, 0xABCD);
}

TEST(ToshibaAsciiRequest, WriteWithoutDataDigits_WritesZero) {
  const DecodedRequest decoded = DecodeRequest(Ascii("(W0803)"));
  ASSERT_EQ(decoded.fault, FrameFault::kNone);
  EXPECT_EQ(decoded.request.data, 0);
  EXPECT_EQ(decoded.request.ascii_data_digits, 0);
}

TEST(ToshibaBinaryRequest, UnknownCommand_IsSilent) {
  for (const Bytes& frame : {Hex("2F 41 00 00 70"), Hex("2F 72 FD 00 9E"), Hex("2F 59 05 00 87")}) {
    const DecodedRequest decoded = DecodeRequest(frame);
    EXPECT_EQ(decoded.fault, FrameFault::kUnknownCommand);
    EXPECT_FALSE(ErrorReplyFor(decoded).has_value());
  }
}

TEST(ToshibaBinaryRequest, BadChecksum_IsAnswered0004WithTheRequestsNumber) {
  const DecodedRequest decoded = DecodeRequest(Hex("2F 05 52 FD 00 00"));
  ASSERT_EQ(decoded.fault, FrameFault::kBadChecksum);
  EXPECT_EQ(decoded.request.envelope.address, InverterAddress::Number(5));
  EXPECT_EQ(ErrorReplyFor(Mode::kBinary, decoded.fault), ErrorCode::kChecksumError);
}

TEST(ToshibaBinaryRequest, WrongLength_IsSilent) {
  EXPECT_EQ(DecodeRequest(Hex("2F 52 FD 00 00 00 7E")).fault, FrameFault::kTrailingBytes);  // R takes no data
  EXPECT_FALSE(ErrorReplyFor(Mode::kBinary, FrameFault::kTrailingBytes).has_value());
}

TEST(ToshibaBinaryRequest, InverterNumbersAndBroadcast) {
  EXPECT_EQ(DecodeRequest(Hex("2F 3F 52 FD 00 BD")).request.envelope.address, InverterAddress::Number(0x3F));
  EXPECT_EQ(DecodeRequest(Hex("2F FF 52 FD 00 7D")).request.envelope.address, InverterAddress::Broadcast());
  // 40h-FEh is neither an inverter number nor a command.
  EXPECT_EQ(DecodeRequest(Hex("2F 40 52 FD 00 BE")).fault, FrameFault::kUnknownCommand);
}

TEST(ToshibaBlockRequest, WriteCountOverTwo_IsAFormatErrorUnlessInLedMode) {
  const Bytes three = Hex("2F 58 03 00 00 01 00 02 00 03 90");
  EXPECT_EQ(DecodeRequest(three).fault, FrameFault::kBadBlockWriteCount);
  EXPECT_FALSE(ErrorReplyFor(Mode::kBinary, FrameFault::kBadBlockWriteCount).has_value());
  EXPECT_EQ(DecodeRequest(three, BlockWriteLimit::kLedDisplay).fault, FrameFault::kNone);
  EXPECT_EQ(DecodeRequest(Hex("2F 58 06 00"), BlockWriteLimit::kLedDisplay).fault,
            FrameFault::kBadBlockWriteCount);
}

TEST(ToshibaBlockRequest, ReadCountOverFive_IsAnsweredWithNoReads) {
  const DecodedRequest decoded = DecodeRequest(Hex("2F 58 00 07 8E"));
  ASSERT_EQ(decoded.fault, FrameFault::kNone);
  EXPECT_EQ(decoded.block.read_count, 7);
  EXPECT_EQ(ReadGroupsToReturn(decoded.block), 0);
  EXPECT_EQ(ReadGroupsToReturn(DecodeRequest(Hex("2F 58 00 05 8C")).block), 5);
}

TEST(ToshibaBinaryReply, Faults) {
  EXPECT_EQ(DecodeReply(Hex("2F 52 FE 03 07 7B 05")).fault, FrameFault::kBadChecksum);
  EXPECT_EQ(DecodeReply(Hex("2F 4E 00 05 82")).fault, FrameFault::kBadErrorCode);
  EXPECT_EQ(DecodeReply(Hex("2F 59 06 00")).fault, FrameFault::kBadBlockReadCount);
  EXPECT_EQ(DecodeReply(Hex("2F FF 52 FD 00 17 70 04")).fault, FrameFault::kBadInverterNumber);
  EXPECT_EQ(DecodeReply(Hex("2F 58 00 00 87")).fault, FrameFault::kUnknownCommand);  // X is a request
  EXPECT_EQ(DecodeReply(Hex("28")).fault, FrameFault::kTruncated);
  EXPECT_EQ(DecodeReply(Hex("41 42")).fault, FrameFault::kBadStartCode);
  EXPECT_EQ(DecodeReply({}).fault, FrameFault::kTruncated);
}

TEST(ToshibaAsciiReply, Faults) {
  EXPECT_EQ(DecodeReply(Ascii("(RFD00177)")).fault, FrameFault::kBadData);  // replies carry 4 digits
  EXPECT_EQ(DecodeReply(Ascii("(*0RFD001770)")).fault, FrameFault::kBadInverterNumber);
  EXPECT_EQ(DecodeReply(Ascii("(N0005)")).fault, FrameFault::kBadErrorCode);
  EXPECT_EQ(DecodeReply(Ascii("(RFD001770&00)")).fault, FrameFault::kBadChecksum);
  EXPECT_EQ(DecodeReply(Ascii("(GFD001770)")).fault, FrameFault::kUnknownCommand);  // G is binary only
  EXPECT_EQ(DecodeReply(Ascii("(RFDX01770)")).fault, FrameFault::kBadCommunicationNumber);
}

TEST(ToshibaAsciiReply, TrippedErrorReply) {
  const DecodedReply decoded = DecodeReply(Ascii("(n0000)"));
  ASSERT_TRUE(decoded.ok());
  EXPECT_EQ(decoded.kind, ReplyKind::kError);
  EXPECT_TRUE(decoded.error.tripped);
}

// --- Every truncation of every example is rejected ---

TEST(ToshibaTruncation, EveryPrefixOfEveryRequestExample_IsRejected) {
  for (const Bytes& frame : AllRequestFrames()) {
    for (std::size_t length = 0; length < frame.size(); ++length) {
      const auto prefix = std::span(frame).first(length);
      EXPECT_NE(DecodeRequest(prefix, BlockWriteLimit::kLedDisplay).fault, FrameFault::kNone)
          << "prefix " << length << " of " << frame.size();
    }
  }
}

TEST(ToshibaTruncation, EveryPrefixOfEveryReplyExample_IsRejected) {
  for (const Bytes& frame : AllReplyFrames()) {
    for (std::size_t length = 0; length < frame.size(); ++length) {
      EXPECT_NE(DecodeReply(std::span(frame).first(length)).fault, FrameFault::kNone)
          << "prefix " << length << " of " << frame.size();
    }
  }
}

TEST(ToshibaTruncation, EveryPrefixOfEveryExample_NeverCompletesAFrame) {
  const auto check = [](Direction direction, const std::vector<Bytes>& frames) {
    for (const Bytes& frame : frames) {
      for (std::size_t length = 0; length < frame.size(); ++length) {
        StreamFramer framer(direction);
        EXPECT_FALSE(framer.Feed(std::span(frame).first(length)).frame_ready);
      }
    }
  };
  check(Direction::kRequests, AllRequestFrames());
  check(Direction::kReplies, AllReplyFrames());
}

TEST(ToshibaFramer, EveryManualExampleFedByteByByte_ComesOutWhole) {
  const auto check = [](Direction direction, const std::vector<Bytes>& frames) {
    for (const Bytes& frame : frames) {
      StreamFramer framer(direction);
      for (std::size_t i = 0; i < frame.size(); ++i) {
        const StreamFramer::FeedResult result = framer.Feed(std::span(frame).subspan(i, 1));
        EXPECT_EQ(result.consumed, 1U);
        EXPECT_EQ(result.frame_ready, i + 1 == frame.size());
      }
      EXPECT_EQ(Bytes(framer.frame().begin(), framer.frame().end()), frame);
    }
  };
  check(Direction::kRequests, AllRequestFrames());
  check(Direction::kReplies, AllReplyFrames());
}

// --- Round trips ---

TEST(ToshibaRoundTrip, RequestsInEveryModeAddressAndTrailer) {
  const InverterAddress ascii_addresses[] = {kOmitted, InverterAddress::Number(0), InverterAddress::Number(99),
                                             InverterAddress::Broadcast(), InverterAddress::OnesDigitGroup(3),
                                             InverterAddress::TensDigitGroup(9)};
  const InverterAddress binary_addresses[] = {kOmitted, InverterAddress::Number(0),
                                              InverterAddress::Number(0x3F), InverterAddress::Broadcast()};
  for (const Command command : {Command::kRead, Command::kWrite, Command::kWriteRam, Command::kReadTwoWire}) {
    const std::uint16_t data = command == Command::kRead ? 0 : 0xBEEF;
    for (const InverterAddress& address : binary_addresses) {
      const Request request = MakeRequest(BinaryEnvelope(address), command, 0xFA2F, data);
      const DecodedRequest decoded = DecodeRequest(Encode(request));
      EXPECT_EQ(decoded.fault, FrameFault::kNone);
      EXPECT_EQ(decoded.request, request);
    }
    if (command == Command::kReadTwoWire) continue;  // binary only
    for (const InverterAddress& address : ascii_addresses) {
      for (const int trailer : {0, 1, 2, 3}) {
        const Envelope envelope = AsciiEnvelope(address, (trailer & 1) != 0, (trailer & 2) != 0);
        const Request request = MakeRequest(envelope, command, 0x0880, data);
        const DecodedRequest decoded = DecodeRequest(Encode(request));
        EXPECT_EQ(decoded.fault, FrameFault::kNone);
        EXPECT_EQ(decoded.request, request);
      }
    }
  }
}

TEST(ToshibaRoundTrip, AsciiWriteDataWithEveryDigitCount) {
  for (std::uint8_t digits = 0; digits <= 4; ++digits) {
    const auto data = static_cast<std::uint16_t>(digits == 0 ? 0 : (1U << (4U * digits)) - 1U);
    const Request request = MakeRequest(AsciiEnvelope(), Command::kWriteRam, 0xFA01, data, digits);
    EXPECT_EQ(DecodeRequest(Encode(request)).request, request) << int{digits};
  }
}

TEST(ToshibaRoundTrip, RepliesAndErrorRepliesTrippedOrNot) {
  for (const bool tripped : {false, true}) {
    for (const Command command : {Command::kRead, Command::kWrite, Command::kWriteRam, Command::kReadTwoWire}) {
      for (const Envelope& envelope : {BinaryEnvelope(), BinaryEnvelope(InverterAddress::Number(63)),
                                       AsciiEnvelope(), AsciiEnvelope(InverterAddress::Number(42), true, false)}) {
        if (command == Command::kReadTwoWire && envelope.mode == Mode::kAscii) continue;
        const Reply reply = MakeReply(envelope, command, 0xFE03, 0x8001, tripped);
        const DecodedReply decoded = DecodeReply(Encode(reply));
        EXPECT_EQ(decoded.fault, FrameFault::kNone);
        EXPECT_EQ(decoded.reply, reply);
      }
    }
    for (std::uint16_t code = 0; code <= 4; ++code) {
      for (const Envelope& envelope : {BinaryEnvelope(), AsciiEnvelope(InverterAddress::Number(1), false, true)}) {
        const ErrorReply reply{.envelope = envelope, .tripped = tripped, .code = static_cast<ErrorCode>(code)};
        const DecodedReply decoded = DecodeReply(Encode(reply));
        EXPECT_EQ(decoded.fault, FrameFault::kNone);
        EXPECT_EQ(decoded.error, reply);
      }
    }
  }
}

TEST(ToshibaRoundTrip, BlockFramesWithEveryCount) {
  for (std::uint8_t writes = 0; writes <= kMaxLedBlockWrites; ++writes) {
    BlockRequest request{.address = InverterAddress::Broadcast(), .write_count = writes, .read_count = 5};
    for (std::size_t i = 0; i < writes; ++i) request.write_data[i] = static_cast<std::uint16_t>(0x1111 * (i + 1));
    const DecodedRequest decoded = DecodeRequest(Encode(request), BlockWriteLimit::kLedDisplay);
    EXPECT_EQ(decoded.fault, FrameFault::kNone);
    EXPECT_EQ(decoded.block, request);
  }
  for (std::uint8_t reads = 0; reads <= kMaxBlockReads; ++reads) {
    BlockReply reply{.address = InverterAddress::Number(9), .tripped = reads % 2 == 1, .read_count = reads,
                     .write_status = 0x02};
    for (std::size_t i = 0; i < reads; ++i) reply.read_data[i] = static_cast<std::uint16_t>(0xA000 + i);
    const DecodedReply decoded = DecodeReply(Encode(reply));
    EXPECT_EQ(decoded.fault, FrameFault::kNone);
    EXPECT_EQ(decoded.block, reply);
  }
}

// --- Encoder refusals ---

TEST(ToshibaEncode, FieldsTheModeCannotCarry_AreInvalidArgument) {
  std::array<std::uint8_t, kMaxFrameLength> out{};
  const auto status = [&out](const Request& r) { return EncodeRequest(r, out).status(); };
  EXPECT_EQ(status(MakeRequest(AsciiEnvelope(), Command::kReadTwoWire, 1)), base::InvalidArgument());
  EXPECT_EQ(status(MakeRequest(AsciiEnvelope(), Command::kRead, 1, 5)), base::InvalidArgument());
  EXPECT_EQ(status(MakeRequest(BinaryEnvelope(), Command::kRead, 1, 5)), base::InvalidArgument());
  EXPECT_EQ(status(MakeRequest(AsciiEnvelope(InverterAddress::Number(100)), Command::kRead, 1)),
            base::InvalidArgument());
  EXPECT_EQ(status(MakeRequest(BinaryEnvelope(InverterAddress::Number(0x40)), Command::kRead, 1)),
            base::InvalidArgument());
  EXPECT_EQ(status(MakeRequest(BinaryEnvelope(InverterAddress::OnesDigitGroup(1)), Command::kRead, 1)),
            base::InvalidArgument());
  EXPECT_EQ(status(MakeRequest(AsciiEnvelope(InverterAddress::TensDigitGroup(10)), Command::kRead, 1)),
            base::InvalidArgument());
  EXPECT_EQ(status(MakeRequest(AsciiEnvelope(), Command::kWrite, 1, 0x100, 2)), base::InvalidArgument());
  EXPECT_EQ(status(MakeRequest(AsciiEnvelope(), Command::kWrite, 1, 0, 5)), base::InvalidArgument());

  EXPECT_EQ(EncodeReply(MakeReply(BinaryEnvelope(InverterAddress::Broadcast()), Command::kRead, 1, 2), out)
                .status(),
            base::InvalidArgument());
  EXPECT_EQ(EncodeReply(MakeReply(AsciiEnvelope(InverterAddress::OnesDigitGroup(2)), Command::kRead, 1, 2), out)
                .status(),
            base::InvalidArgument());
  EXPECT_EQ(EncodeReply(MakeReply(AsciiEnvelope(), Command::kReadTwoWire, 1, 2), out).status(),
            base::InvalidArgument());
  EXPECT_EQ(EncodeErrorReply({.envelope = BinaryEnvelope(), .tripped = false, .code = ErrorCode{5}}, out).status(),
            base::InvalidArgument());
  EXPECT_EQ(EncodeBlockRequest({.write_count = 6}, out).status(), base::InvalidArgument());
  EXPECT_EQ(EncodeBlockReply({.read_count = 6}, out).status(), base::InvalidArgument());
  EXPECT_EQ(EncodeBlockReply({.address = InverterAddress::Broadcast()}, out).status(), base::InvalidArgument());
}

TEST(ToshibaEncode, EveryBufferShorterThanTheFrame_IsResourceExhausted) {
  const Request request = MakeRequest(AsciiEnvelope(InverterAddress::Number(12), true, true), Command::kWrite,
                                      0xFA01, 0x1770);
  std::array<std::uint8_t, kMaxFrameLength + 4> out{};
  const base::Result<std::size_t> full = EncodeRequest(request, out);
  ASSERT_TRUE(full.ok());
  EXPECT_EQ(*full, kMaxFrameLength);  // the longest frame there is
  for (std::size_t size = 0; size < *full; ++size) {
    out.fill(0xEE);
    EXPECT_EQ(EncodeRequest(request, std::span(out).first(size)).status(), base::ResourceExhausted()) << size;
    EXPECT_EQ(out[size], 0xEE) << "wrote past the end at size " << size;
  }
  const BlockReply reply{.read_count = 5};
  for (std::size_t size = 0; size < 15; ++size) {
    EXPECT_EQ(EncodeBlockReply(reply, std::span(out).first(size)).status(), base::ResourceExhausted());
  }
}

// --- Addressing (p.8-9, p.21-23) ---

TEST(ToshibaAddressing, OverallBroadcast_OnlyInverter00Answers) {
  EXPECT_EQ(ResolveAddress(Mode::kAscii, InverterAddress::Broadcast(), 0), Addressing::kExecuteAndReply);
  EXPECT_EQ(ResolveAddress(Mode::kAscii, InverterAddress::Broadcast(), 57), Addressing::kExecuteSilently);
  EXPECT_EQ(ResolveAddress(Mode::kBinary, InverterAddress::Broadcast(), 0), Addressing::kExecuteAndReply);
  EXPECT_EQ(ResolveAddress(Mode::kBinary, InverterAddress::Broadcast(), 63), Addressing::kExecuteSilently);
  // Beyond what the mode can address (ASCII 0-99, binary 0-63): not a member.
  EXPECT_EQ(ResolveAddress(Mode::kBinary, InverterAddress::Broadcast(), 64), Addressing::kIgnore);
  EXPECT_EQ(ResolveAddress(Mode::kAscii, InverterAddress::Broadcast(), 100), Addressing::kIgnore);
}

TEST(ToshibaAddressing, GroupBroadcasts_MemberWithZeroInTheStarPositionAnswers) {
  const InverterAddress ones9 = InverterAddress::OnesDigitGroup(9);  // "*9": 09, 19, ... 99
  EXPECT_EQ(ResolveAddress(Mode::kAscii, ones9, 9), Addressing::kExecuteAndReply);
  EXPECT_EQ(ResolveAddress(Mode::kAscii, ones9, 19), Addressing::kExecuteSilently);
  EXPECT_EQ(ResolveAddress(Mode::kAscii, ones9, 99), Addressing::kExecuteSilently);
  EXPECT_EQ(ResolveAddress(Mode::kAscii, ones9, 8), Addressing::kIgnore);
  const InverterAddress tens1 = InverterAddress::TensDigitGroup(1);  // "1*": block 1 of p.23, 10-19
  EXPECT_EQ(ResolveAddress(Mode::kAscii, tens1, 10), Addressing::kExecuteAndReply);
  EXPECT_EQ(ResolveAddress(Mode::kAscii, tens1, 11), Addressing::kExecuteSilently);
  EXPECT_EQ(ResolveAddress(Mode::kAscii, tens1, 20), Addressing::kIgnore);
  EXPECT_EQ(ResolveAddress(Mode::kAscii, tens1, 1), Addressing::kIgnore);
}

TEST(ToshibaAddressing, NumberMismatchIsIgnoredAndOmittedNumberIsOneToOne) {
  EXPECT_EQ(ResolveAddress(Mode::kBinary, InverterAddress::Number(5), 5), Addressing::kExecuteAndReply);
  EXPECT_EQ(ResolveAddress(Mode::kBinary, InverterAddress::Number(5), 6), Addressing::kIgnore);
  EXPECT_EQ(ResolveAddress(Mode::kAscii, kOmitted, 200), Addressing::kExecuteAndReply);
  EXPECT_EQ(ReplyAddress(kOmitted, 7), kOmitted);
  EXPECT_EQ(ReplyAddress(InverterAddress::Broadcast(), 0), InverterAddress::Number(0));
}

TEST(ToshibaFaults, EveryFaultHasANameAndSilenceIsTheDefault) {
  for (int i = 0; i <= static_cast<int>(FrameFault::kInterDriveCommand); ++i) {
    EXPECT_STRNE(FrameFaultName(static_cast<FrameFault>(i)), "unknown fault") << i;
  }
  EXPECT_FALSE(ErrorReplyFor(Mode::kAscii, FrameFault::kTruncated).has_value());
  EXPECT_FALSE(ErrorReplyFor(Mode::kBinary, FrameFault::kBadCommunicationNumber).has_value());
  EXPECT_EQ(ErrorReplyFor(Mode::kBinary, FrameFault::kBadChecksum), ErrorCode::kChecksumError);
}

}  // namespace
}  // namespace drive_link::wire
