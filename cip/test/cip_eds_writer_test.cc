// The card's EDS (cip/eds/, docs/eds.md): the exact [Assembly] and [Connection Manager] sections, exact
// [Params] entries, what differs between the VF-MB1 and VF-S15 files, and the EdsFile served through a
// window: ReadAt at many offsets and sizes equals the whole text; size and checksum.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "cip/eds/eds_file.h"
#include "cip/eds/eds_writer.h"

namespace cip::eds {
namespace {

class StringSink final : public EdsSink {
 public:
  bool Append(std::string_view text) override {
    text_.append(text);
    return true;
  }
  const std::string& text() const { return text_; }

 private:
  std::string text_;
};

std::string Eds(DriveModel model) {
  StringSink sink;
  WriteEds(model, sink);
  return sink.text();
}

// From the line "[name]" up to (not including) the blank line before the next section or the end.
std::string Section(const std::string& text, std::string_view name) {
  const std::size_t start = text.find("\n[" + std::string(name) + "]\n");
  if (start == std::string::npos) return "";
  const std::size_t end = text.find("\n\n[", start + 1);
  return text.substr(start + 1, end == std::string::npos ? std::string::npos : end - start);
}

// From "    ParamN =" up to its ';' and the newline.
std::string Entry(const std::string& text, std::string_view key) {
  const std::size_t start = text.find("\n    " + std::string(key) + " =\n");
  if (start == std::string::npos) return "";
  const std::size_t end = text.find(";\n", start);
  return text.substr(start + 1, end + 2 - start - 1);
}

// Every drive assembly of assembly_codec.h with its size and 16-bit members; FA06/FA07 and FD01/FD00 name
// their parameters (Param145/146, Param154/153); 199 the input-only heartbeat.
constexpr std::string_view kAssemblySection = R"eds([Assembly]
    Object_Name = "Assembly Object";
    Object_Class_Code = 0x04;
    Assem20 =
        "Basic speed control (ODVA)",
        "20 04 24 14 30 03",
        4,
        0x0000,
        ,,
        16,,16,;
    Assem21 =
        "Extended speed control (ODVA)",
        "20 04 24 15 30 03",
        4,
        0x0000,
        ,,
        16,,16,;
    Assem100 =
        "Native command: FA06, FA07, scanner words c001-c006",
        "20 04 24 64 30 03",
        16,
        0x0000,
        ,,
        16,Param145,16,Param146,16,,16,,16,,16,,16,,16,;
    Assem101 =
        "Extended speed control + parameter channel",
        "20 04 24 65 30 03",
        8,
        0x0000,
        ,,
        16,,16,,16,,16,;
    Assem102 =
        "Scanner words c001-c006",
        "20 04 24 66 30 03",
        12,
        0x0000,
        ,,
        16,,16,,16,,16,,16,,16,;
    Assem105 =
        "Parameter channel + scanner words c001-c006",
        "20 04 24 69 30 03",
        18,
        0x0000,
        ,,
        16,,16,,16,,16,,16,,16,,16,,16,,16,;
    Assem70 =
        "Basic speed status (ODVA)",
        "20 04 24 46 30 03",
        4,
        0x0000,
        ,,
        16,,16,;
    Assem71 =
        "Extended speed status (ODVA)",
        "20 04 24 47 30 03",
        4,
        0x0000,
        ,,
        16,,16,;
    Assem150 =
        "Native status: FD01, FD00, monitor words c021-c026",
        "20 04 24 96 30 03",
        16,
        0x0000,
        ,,
        16,Param154,16,Param153,16,,16,,16,,16,,16,,16,;
    Assem151 =
        "Extended speed status + parameter channel",
        "20 04 24 97 30 03",
        8,
        0x0000,
        ,,
        16,,16,,16,,16,;
    Assem152 =
        "Monitor words c021-c026",
        "20 04 24 98 30 03",
        12,
        0x0000,
        ,,
        16,,16,,16,,16,,16,,16,;
    Assem155 =
        "Parameter channel + monitor words c021-c026",
        "20 04 24 9B 30 03",
        18,
        0x0000,
        ,,
        16,,16,,16,,16,,16,,16,,16,,16,,16,;
    Assem199 =
        "Input-only heartbeat",
        "20 04 24 C7 30 03",
        0,
        0x0000,
        ,,;
)eds";

// 6 exclusive owners (the §5 pairs), 6 input only (199), 6 listen only (198), configuration instance 1,
// RPI = Param187.
constexpr std::string_view kConnectionSection = R"eds([Connection Manager]
    Object_Name = "Connection Manager Object";
    Object_Class_Code = 0x06;
    Connection1 =
        0x04010002,
        0x44640405,
        Param187,4,Assem20,
        Param187,4,Assem70,
        ,,
        ,,
        "Exclusive Owner 20/70",
        "",
        "20 04 24 01 2C 14 2C 46";
    Connection2 =
        0x04010002,
        0x44640405,
        Param187,4,Assem21,
        Param187,4,Assem71,
        ,,
        ,,
        "Exclusive Owner 21/71",
        "",
        "20 04 24 01 2C 15 2C 47";
    Connection3 =
        0x04010002,
        0x44640405,
        Param187,16,Assem100,
        Param187,16,Assem150,
        ,,
        ,,
        "Exclusive Owner 100/150",
        "",
        "20 04 24 01 2C 64 2C 96";
    Connection4 =
        0x04010002,
        0x44640405,
        Param187,8,Assem101,
        Param187,8,Assem151,
        ,,
        ,,
        "Exclusive Owner 101/151",
        "",
        "20 04 24 01 2C 65 2C 97";
    Connection5 =
        0x04010002,
        0x44640405,
        Param187,12,Assem102,
        Param187,12,Assem152,
        ,,
        ,,
        "Exclusive Owner 102/152",
        "",
        "20 04 24 01 2C 66 2C 98";
    Connection6 =
        0x04010002,
        0x44640405,
        Param187,18,Assem105,
        Param187,18,Assem155,
        ,,
        ,,
        "Exclusive Owner 105/155",
        "",
        "20 04 24 01 2C 69 2C 9B";
    Connection7 =
        0x02010002,
        0x44640305,
        Param187,0,Assem199,
        Param187,4,Assem70,
        ,,
        ,,
        "Input Only 70",
        "",
        "20 04 24 01 2C C7 2C 46";
    Connection8 =
        0x02010002,
        0x44640305,
        Param187,0,Assem199,
        Param187,4,Assem71,
        ,,
        ,,
        "Input Only 71",
        "",
        "20 04 24 01 2C C7 2C 47";
    Connection9 =
        0x02010002,
        0x44640305,
        Param187,0,Assem199,
        Param187,16,Assem150,
        ,,
        ,,
        "Input Only 150",
        "",
        "20 04 24 01 2C C7 2C 96";
    Connection10 =
        0x02010002,
        0x44640305,
        Param187,0,Assem199,
        Param187,8,Assem151,
        ,,
        ,,
        "Input Only 151",
        "",
        "20 04 24 01 2C C7 2C 97";
    Connection11 =
        0x02010002,
        0x44640305,
        Param187,0,Assem199,
        Param187,12,Assem152,
        ,,
        ,,
        "Input Only 152",
        "",
        "20 04 24 01 2C C7 2C 98";
    Connection12 =
        0x02010002,
        0x44640305,
        Param187,0,Assem199,
        Param187,18,Assem155,
        ,,
        ,,
        "Input Only 155",
        "",
        "20 04 24 01 2C C7 2C 9B";
    Connection13 =
        0x01010002,
        0x44240305,
        Param187,0,,
        Param187,4,Assem70,
        ,,
        ,,
        "Listen Only 70",
        "",
        "20 04 24 01 2C C6 2C 46";
    Connection14 =
        0x01010002,
        0x44240305,
        Param187,0,,
        Param187,4,Assem71,
        ,,
        ,,
        "Listen Only 71",
        "",
        "20 04 24 01 2C C6 2C 47";
    Connection15 =
        0x01010002,
        0x44240305,
        Param187,0,,
        Param187,16,Assem150,
        ,,
        ,,
        "Listen Only 150",
        "",
        "20 04 24 01 2C C6 2C 96";
    Connection16 =
        0x01010002,
        0x44240305,
        Param187,0,,
        Param187,8,Assem151,
        ,,
        ,,
        "Listen Only 151",
        "",
        "20 04 24 01 2C C6 2C 97";
    Connection17 =
        0x01010002,
        0x44240305,
        Param187,0,,
        Param187,12,Assem152,
        ,,
        ,,
        "Listen Only 152",
        "",
        "20 04 24 01 2C C6 2C 98";
    Connection18 =
        0x01010002,
        0x44240305,
        Param187,0,,
        Param187,18,Assem155,
        ,,
        ,,
        "Listen Only 155",
        "",
        "20 04 24 01 2C C6 2C 9B";
)eds";

TEST(EdsWriter, AssemblySectionExactly) { EXPECT_EQ(Section(Eds(DriveModel::kVfMb1), "Assembly"), kAssemblySection); }

TEST(EdsWriter, ConnectionManagerSectionExactly) {
  EXPECT_EQ(Section(Eds(DriveModel::kVfMb1), "Connection Manager"), kConnectionSection);
  EXPECT_EQ(Section(Eds(DriveModel::kVfS15), "Connection Manager"), kConnectionSection);
}

TEST(EdsWriter, ParamsFromTheParameterTable) {
  const std::string text = Eds(DriveModel::kVfMb1);
  EXPECT_EQ(Entry(text, "Param6"),
            "    Param6 =\n"
            "        0, 6,\"20 0F 24 06 30 01\", 0x0004, 0xC7, 2,\n"
            "        \"acc\", \"s\", \"Acceleration time 1 (unit per f519)\",\n"
            "        1,60000,100, 1,10,1,0, ,,,, 1;\n");
  EXPECT_EQ(Entry(text, "Param8"),
            "    Param8 =\n"
            "        0, 6,\"20 0F 24 08 30 01\", 0x0004, 0xC7, 2,\n"
            "        \"fh\", \"Hz\", \"Maximum frequency\",\n"
            "        3000,50000,8000, 1,100,1,0, ,,,, 2;\n");
  EXPECT_EQ(Entry(text, "Param178"),
            "    Param178 =\n"
            "        0, 6,\"20 0F 24 B2 30 01\", 0x0034, 0xC3, 2,\n"
            "        \"fe36\", \"%\", \"VIB input value (-100.00 to +100.00 %)\",\n"
            "        -10000,10000,0, 1,100,1,0, ,,,, 2;\n");
  // The connections' RPI: the Connection Manager's floor (1 ms) and ceiling (10 s).
  EXPECT_EQ(Entry(text, "Param187"),
            "    Param187 =\n"
            "        0, ,, 0x0000, 0xC8, 4,\n"
            "        \"RPI\", \"us\", \"Requested packet interval of an I/O connection\",\n"
            "        1000,10000000,10000, ,,,, ,,,, ;\n");
  EXPECT_EQ(Entry(text, "Param188"), "");
}

TEST(EdsWriter, OneFilePerProductCode) {
  const std::string mb1 = Eds(DriveModel::kVfMb1);
  const std::string s15 = Eds(DriveModel::kVfS15);
  EXPECT_NE(mb1.find("\n    ProdCode = 32000;\n"), std::string::npos);
  EXPECT_NE(mb1.find("\n    ProdName = \"VF-MB1\";\n"), std::string::npos);
  EXPECT_NE(s15.find("\n    ProdCode = 32001;\n"), std::string::npos);
  EXPECT_NE(s15.find("\n    ProdName = \"VF-S15\";\n"), std::string::npos);
  EXPECT_NE(mb1.find("\n    VendCode = 377;\n    VendName = \"Toshiba\";\n    ProdType = 2;\n"), std::string::npos);
  EXPECT_NE(mb1.find("\n    MajRev = 1;\n    MinRev = 8;\n"), std::string::npos);
  // fmod's limits are the model's: 0-11 on VF-MB1, 0-14 on VF-S15 (row 3).
  EXPECT_NE(Entry(mb1, "Param3").find("\n        0,11,0, 1,1,1,0, ,,,, 0;\n"), std::string::npos);
  EXPECT_NE(Entry(s15, "Param3").find("\n        0,14,0, 1,1,1,0, ,,,, 0;\n"), std::string::npos);
  EXPECT_EQ(Section(mb1, "Assembly"), Section(s15, "Assembly"));
}

TEST(EdsWriter, SectionsInOrder) {
  const std::string text = Eds(DriveModel::kVfMb1);
  std::size_t at = 0;
  for (const std::string_view name : {"[File]", "[Device]", "[Device Classification]", "[Params]", "[Groups]",
                                      "[Assembly]", "[Connection Manager]", "[Port]", "[Capacity]",
                                      "[Identity Class]", "[TCP/IP Interface Class]", "[Ethernet Link Class]",
                                      "[DLR Class]", "[QoS Class]"}) {
    const std::size_t found = text.find("\n" + std::string(name) + "\n", at);
    ASSERT_NE(found, std::string::npos) << name;
    at = found + 1;
  }
  EXPECT_NE(text.find("\n    Port1 = TCP, \"EtherNet/IP\", \"20 F5 24 01\", 2;\n"), std::string::npos);
  EXPECT_NE(text.find("\n    TSpec1 = TxRx, 18, 1000;\n"), std::string::npos);
  EXPECT_NE(text.find("\n[DLR Class]\n    Revision = 3;\n    Object_Name = \"Device Level Ring Object\";\n"
                      "    Object_Class_Code = 0x47;\n    MaxInst = 1;\n"),
            std::string::npos);
  EXPECT_NE(text.find("\n[QoS Class]\n    Revision = 1;\n    Object_Name = \"QoS Object\";\n    Object_Class_Code = 0x48;\n"
                      "    MaxInst = 1;\n    Number_Of_Static_Instances = 1;\n    Max_Number_Of_Dynamic_Instances = 0;\n"),
            std::string::npos);
  EXPECT_EQ(text.back(), '\n');
}

TEST(EdsFile, SizeAndChecksumOfTheWholeText) {
  for (const DriveModel model : {DriveModel::kVfMb1, DriveModel::kVfS15}) {
    const std::string text = Eds(model);
    const EdsFile file(model);
    EXPECT_EQ(file.Size(), text.size());
    std::uint16_t sum = 0;
    for (const char c : text) sum = static_cast<std::uint16_t>(sum + static_cast<std::uint8_t>(c));
    // The checksum makes the 16-bit sum of all bytes zero.
    EXPECT_EQ(static_cast<std::uint16_t>(sum + file.Checksum()), 0);
  }
  EXPECT_EQ(FileChecksum(0x0000), 0x0000);
  EXPECT_EQ(FileChecksum(0x0001), 0xFFFF);
  EXPECT_EQ(FileChecksum(0x1234), 0xEDCC);
}

TEST(EdsFile, AnyWindowEqualsTheWholeText) {
  const std::string text = Eds(DriveModel::kVfMb1);
  const EdsFile file(DriveModel::kVfMb1);
  const auto size = static_cast<std::uint32_t>(text.size());
  for (const std::size_t window : {std::size_t{1}, std::size_t{7}, std::size_t{64}, std::size_t{255}}) {
    // Offsets at a prime stride through the whole file, and the last bytes before and at the end.
    std::vector<std::uint32_t> offsets;
    for (std::uint32_t offset = 0; offset < size; offset += 997) offsets.push_back(offset);
    for (std::uint32_t back = 1; back <= 3; ++back) offsets.push_back(size - back);
    for (const std::uint32_t offset : offsets) {
      std::vector<std::uint8_t> out(window, 0xAA);
      const std::size_t copied = file.ReadAt(offset, out);
      const std::size_t expected = std::min<std::size_t>(window, size - offset);
      ASSERT_EQ(copied, expected) << "offset " << offset << " window " << window;
      EXPECT_EQ(std::string(out.begin(), out.begin() + static_cast<std::ptrdiff_t>(copied)), text.substr(offset, copied))
          << "offset " << offset << " window " << window;
    }
  }
  std::vector<std::uint8_t> out(16);
  EXPECT_EQ(file.ReadAt(size, out), 0u);
  EXPECT_EQ(file.ReadAt(size + 1000, out), 0u);
  EXPECT_EQ(file.ReadAt(0, std::span<std::uint8_t>()), 0u);
}

TEST(EdsFile, ConsecutiveChunksRebuildTheFile) {
  // As the File object's Upload_Transfer and an HTTP download read it: chunk after chunk.
  const std::string text = Eds(DriveModel::kVfS15);
  const EdsFile file(DriveModel::kVfS15);
  std::string rebuilt;
  std::vector<std::uint8_t> chunk(251);
  while (true) {
    const std::size_t copied = file.ReadAt(static_cast<std::uint32_t>(rebuilt.size()), chunk);
    if (copied == 0) break;
    rebuilt.append(chunk.begin(), chunk.begin() + static_cast<std::ptrdiff_t>(copied));
  }
  EXPECT_EQ(rebuilt, text);
}

}  // namespace
}  // namespace cip::eds
