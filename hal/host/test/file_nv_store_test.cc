#include "file_nv_store.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <string>
#include <vector>

namespace hal::host {
namespace {

using Bytes = std::vector<std::uint8_t>;
namespace fs = std::filesystem;

Bytes BytesOf(const std::string& text) { return Bytes(text.begin(), text.end()); }

class FileNvStoreTest : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string pattern = (fs::temp_directory_path() / "ipe-nv-test-XXXXXX").string();
    ASSERT_NE(mkdtemp(pattern.data()), nullptr);
    dir_ = pattern;
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::unique_ptr<FileNvStore> OpenStore() {
    std::string error;
    base::Result<std::unique_ptr<FileNvStore>> store = FileNvStore::Open(dir_.string(), &error);
    EXPECT_TRUE(store.ok()) << error;
    return std::move(store.value());
  }

  Bytes FileBytes(const std::string& name) const {
    std::ifstream in(dir_ / name, std::ios::binary);
    return Bytes(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  void SetFileBytes(const std::string& name, const Bytes& bytes) const {
    std::ofstream out(dir_ / name, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  }

  // Reads record `id` into a fresh store's view; the payload, or the status as the only element.
  base::Result<Bytes> ReadWithFreshStore(NvRecordId id) {
    std::unique_ptr<FileNvStore> store = OpenStore();
    Bytes buffer(kMaxRecordBytes);
    const base::Result<std::size_t> n = store->Read(id, buffer);
    if (!n.ok()) return n.status();
    buffer.resize(*n);
    return buffer;
  }

  fs::path dir_;
};

TEST_F(FileNvStoreTest, WritesTheDocumentedRecordFile) {
  std::unique_ptr<FileNvStore> store = OpenStore();
  ASSERT_EQ(store->Write(7, BytesOf("123456789")), base::OkStatus());

  const Bytes expected = {
      0x49, 0x50, 0x4E, 0x56,  // magic "IPNV"
      0x01, 0x00,              // format 1
      0x07, 0x00,              // record id 7
      0x09, 0x00, 0x00, 0x00,  // payload length 9
      0x26, 0x39, 0xF4, 0xCB,  // CRC-32("123456789") = 0xCBF43926, the standard check value
      '1',  '2',  '3',  '4',  '5', '6', '7', '8', '9'};
  EXPECT_EQ(FileBytes("nv-7.rec"), expected);
  EXPECT_FALSE(fs::exists(dir_ / "nv-7.rec.tmp"));
}

TEST_F(FileNvStoreTest, ReadsBackWhatWasWritten) {
  std::unique_ptr<FileNvStore> store = OpenStore();
  const Bytes data = BytesOf("admin:secret");
  ASSERT_EQ(store->Write(3, data), base::OkStatus());
  Bytes out(64, 0xEE);
  const base::Result<std::size_t> n = store->Read(3, out);
  ASSERT_TRUE(n.ok());
  ASSERT_EQ(*n, data.size());
  EXPECT_EQ(Bytes(out.begin(), out.begin() + 12), data);
  EXPECT_EQ(out[12], 0xEE);  // nothing written past the record
}

TEST_F(FileNvStoreTest, RecordsSurviveARestart) {
  ASSERT_EQ(OpenStore()->Write(1, BytesOf("one")), base::OkStatus());
  ASSERT_EQ(OpenStore()->Write(65535, BytesOf("last id")), base::OkStatus());
  EXPECT_EQ(ReadWithFreshStore(1).value(), BytesOf("one"));
  EXPECT_EQ(ReadWithFreshStore(65535).value(), BytesOf("last id"));
  EXPECT_TRUE(fs::exists(dir_ / "nv-65535.rec"));
}

TEST_F(FileNvStoreTest, NeverWrittenIsNotFound) {
  EXPECT_EQ(ReadWithFreshStore(9).status(), base::NotFound());
}

TEST_F(FileNvStoreTest, EmptyRecordIsValid) {
  ASSERT_EQ(OpenStore()->Write(2, Bytes{}), base::OkStatus());
  const base::Result<Bytes> read = ReadWithFreshStore(2);
  ASSERT_TRUE(read.ok());
  EXPECT_TRUE(read->empty());
  EXPECT_EQ(FileBytes("nv-2.rec").size(), FileNvStore::kHeaderBytes);
}

TEST_F(FileNvStoreTest, BufferTooSmallIsOutOfRange) {
  std::unique_ptr<FileNvStore> store = OpenStore();
  ASSERT_EQ(store->Write(4, BytesOf("0123456789")), base::OkStatus());
  Bytes small(9);
  EXPECT_EQ(store->Read(4, small).status(), base::OutOfRange());
  Bytes exact(10);
  EXPECT_EQ(store->Read(4, exact).value(), 10u);
}

TEST_F(FileNvStoreTest, LargestRecordFitsAndOneMoreByteIsRefused) {
  std::unique_ptr<FileNvStore> store = OpenStore();
  Bytes largest(kMaxRecordBytes);
  for (std::size_t i = 0; i < largest.size(); ++i) largest[i] = static_cast<std::uint8_t>(i * 7);
  ASSERT_EQ(store->Write(5, largest), base::OkStatus());
  EXPECT_EQ(ReadWithFreshStore(5).value(), largest);

  EXPECT_EQ(store->Write(6, Bytes(kMaxRecordBytes + 1)), base::InvalidArgument());
  EXPECT_FALSE(fs::exists(dir_ / "nv-6.rec"));
  EXPECT_FALSE(fs::exists(dir_ / "nv-6.rec.tmp"));
}

TEST_F(FileNvStoreTest, OverwriteReplacesTheWholeRecord) {
  std::unique_ptr<FileNvStore> store = OpenStore();
  ASSERT_EQ(store->Write(8, BytesOf("a long first value")), base::OkStatus());
  ASSERT_EQ(store->Write(8, BytesOf("short")), base::OkStatus());
  EXPECT_EQ(ReadWithFreshStore(8).value(), BytesOf("short"));
}

TEST_F(FileNvStoreTest, EraseForgetsTheRecordAndIsIdempotent) {
  std::unique_ptr<FileNvStore> store = OpenStore();
  ASSERT_EQ(store->Write(10, BytesOf("x")), base::OkStatus());
  EXPECT_EQ(store->Erase(10), base::OkStatus());
  EXPECT_EQ(ReadWithFreshStore(10).status(), base::NotFound());
  EXPECT_EQ(store->Erase(10), base::OkStatus());
  EXPECT_EQ(store->Erase(11), base::OkStatus());
}

TEST_F(FileNvStoreTest, EveryFlippedByteIsDataLoss) {
  ASSERT_EQ(OpenStore()->Write(12, BytesOf("web port 80")), base::OkStatus());
  const Bytes good = FileBytes("nv-12.rec");
  for (std::size_t i = 0; i < good.size(); ++i) {
    Bytes bad = good;
    bad[i] ^= 0x01;
    SetFileBytes("nv-12.rec", bad);
    EXPECT_EQ(ReadWithFreshStore(12).status(), base::DataLoss()) << "flipped byte " << i;
  }
  SetFileBytes("nv-12.rec", good);
  EXPECT_EQ(ReadWithFreshStore(12).value(), BytesOf("web port 80"));
}

TEST_F(FileNvStoreTest, TruncatedOrExtendedFileIsDataLoss) {
  ASSERT_EQ(OpenStore()->Write(13, BytesOf("abcdef")), base::OkStatus());
  const Bytes good = FileBytes("nv-13.rec");
  for (std::size_t size = 0; size < good.size(); ++size) {
    SetFileBytes("nv-13.rec", Bytes(good.begin(), good.begin() + static_cast<std::ptrdiff_t>(size)));
    EXPECT_EQ(ReadWithFreshStore(13).status(), base::DataLoss()) << "truncated to " << size;
  }
  Bytes longer = good;
  longer.push_back(0);
  SetFileBytes("nv-13.rec", longer);
  EXPECT_EQ(ReadWithFreshStore(13).status(), base::DataLoss());
}

TEST_F(FileNvStoreTest, OversizedFileIsDataLoss) {
  SetFileBytes("nv-14.rec", Bytes(FileNvStore::kHeaderBytes + kMaxRecordBytes + 100, 0));
  EXPECT_EQ(ReadWithFreshStore(14).status(), base::DataLoss());
}

TEST_F(FileNvStoreTest, RecordFileUnderAnotherIdIsDataLoss) {
  ASSERT_EQ(OpenStore()->Write(15, BytesOf("for 15")), base::OkStatus());
  fs::copy_file(dir_ / "nv-15.rec", dir_ / "nv-16.rec");
  EXPECT_EQ(ReadWithFreshStore(16).status(), base::DataLoss());
}

TEST_F(FileNvStoreTest, OpenRemovesStaleTempFilesOnly) {
  ASSERT_EQ(OpenStore()->Write(17, BytesOf("kept")), base::OkStatus());
  SetFileBytes("nv-17.rec.tmp", BytesOf("half a rec"));
  SetFileBytes("nv-99.rec.tmp", Bytes{});
  SetFileBytes("notes.txt", BytesOf("not ours"));
  EXPECT_EQ(ReadWithFreshStore(17).value(), BytesOf("kept"));
  EXPECT_FALSE(fs::exists(dir_ / "nv-17.rec.tmp"));
  EXPECT_FALSE(fs::exists(dir_ / "nv-99.rec.tmp"));
  EXPECT_TRUE(fs::exists(dir_ / "notes.txt"));
}

TEST_F(FileNvStoreTest, OpenCreatesAMissingDirectory) {
  const fs::path sub = dir_ / "nv";
  std::string error;
  base::Result<std::unique_ptr<FileNvStore>> store = FileNvStore::Open(sub.string(), &error);
  ASSERT_TRUE(store.ok()) << error;
  EXPECT_TRUE(fs::is_directory(sub));
  EXPECT_EQ(store.value()->Write(1, BytesOf("v")), base::OkStatus());
  EXPECT_TRUE(fs::exists(sub / "nv-1.rec"));
}

TEST_F(FileNvStoreTest, OpenSaysWhyItFailed) {
  const std::string missing_parent = (dir_ / "no" / "such").string();
  std::string error;
  EXPECT_EQ(FileNvStore::Open(missing_parent, &error).status(), base::NotFound());
  EXPECT_NE(error.find(missing_parent), std::string::npos) << error;
  EXPECT_NE(error.find("No such file or directory"), std::string::npos) << error;

  SetFileBytes("plain-file", Bytes{});
  EXPECT_EQ(FileNvStore::Open((dir_ / "plain-file").string(), &error).status(),
            base::FailedPrecondition());
  EXPECT_NE(error.find("Not a directory"), std::string::npos) << error;
}

// Power-cut simulation: for every number of bytes of the new record file that may have reached the disk
// when power failed (0 .. the whole file, the last one being "data safe, rename not done"), a store
// opened afterwards on the same directory must read the complete old contents (or kNotFound when there
// was none), and after an uninterrupted write the complete new contents.
class FileNvStorePowerCutTest : public FileNvStoreTest {
 protected:
  void CheckEveryCut(const std::optional<Bytes>& old_value, const Bytes& new_value) {
    constexpr NvRecordId kId = 20;
    if (old_value.has_value()) {
      ASSERT_EQ(OpenStore()->Write(kId, *old_value), base::OkStatus());
    }
    const std::size_t file_size = FileNvStore::kHeaderBytes + new_value.size();
    for (std::size_t cut = 0; cut <= file_size; ++cut) {
      {
        std::unique_ptr<FileNvStore> dying = OpenStore();
        dying->CutPowerAfterBytesForTest(cut);
        ASSERT_EQ(dying->Write(kId, new_value), base::Internal()) << "cut at " << cut;
      }
      // The model left exactly the bytes that reached the disk in the temp file.
      ASSERT_EQ(FileBytes(FileNvStore::TempFileName(kId)).size(), cut);

      const base::Result<Bytes> after = ReadWithFreshStore(kId);
      if (old_value.has_value()) {
        ASSERT_TRUE(after.ok()) << "cut at " << cut << ": " << base::StatusName(after.status());
        ASSERT_EQ(*after, *old_value) << "cut at " << cut;
      } else {
        ASSERT_EQ(after.status(), base::NotFound()) << "cut at " << cut;
      }
      ASSERT_FALSE(fs::exists(dir_ / FileNvStore::TempFileName(kId))) << "cut at " << cut;
    }
    ASSERT_EQ(OpenStore()->Write(kId, new_value), base::OkStatus());
    EXPECT_EQ(ReadWithFreshStore(kId).value(), new_value);
  }
};

TEST_F(FileNvStorePowerCutTest, LongerNewValue) {
  CheckEveryCut(BytesOf("password=old"), BytesOf("password=a-much-longer-new-one"));
}

TEST_F(FileNvStorePowerCutTest, ShorterNewValue) {
  CheckEveryCut(BytesOf("web timeout=600 language=en"), BytesOf("web timeout=60"));
}

TEST_F(FileNvStorePowerCutTest, FirstEverWrite) {
  CheckEveryCut(std::nullopt, BytesOf("first"));
}

TEST_F(FileNvStorePowerCutTest, EmptyOldAndNewValues) {
  CheckEveryCut(Bytes{}, Bytes{});
}

TEST_F(FileNvStorePowerCutTest, LargestRecord) {
  Bytes old_value(kMaxRecordBytes, 0xA5);
  Bytes new_value(kMaxRecordBytes, 0x5A);
  CheckEveryCut(old_value, new_value);
}

}  // namespace
}  // namespace hal::host
