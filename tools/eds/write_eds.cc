// ipe-write-eds: writes the card's EDS files (docs/eds.md) into a directory, one per product code:
// IPE002Z_VF-MB1.eds and IPE002Z_VF-S15.eds, byte for byte what the card serves (cip::eds::EdsFile).
//
//   ipe-write-eds OUTPUT_DIR
//
// Host-only. Exit status 0, or 1 with a message when a file cannot be written.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include "cip/eds/eds_file.h"
#include "cip/eds/eds_writer.h"

namespace {

bool WriteOne(const std::filesystem::path& directory, cip::DriveModel model) {
  const cip::eds::EdsFile file(model);
  std::vector<std::uint8_t> bytes(file.Size());
  if (file.ReadAt(0, bytes) != bytes.size()) {
    std::cerr << "ipe-write-eds: the writer gave fewer bytes than it counted\n";
    return false;
  }
  const std::filesystem::path path = directory / std::string(cip::eds::EdsFileName(model));
  const std::filesystem::path temporary = path.string() + ".tmp";
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
    if (!out) {
      std::cerr << "ipe-write-eds: cannot write " << temporary << "\n";
      return false;
    }
  }
  std::filesystem::rename(temporary, path);
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: ipe-write-eds OUTPUT_DIR\n";
    return 2;
  }
  const std::filesystem::path directory(argv[1]);
  std::error_code error;
  std::filesystem::create_directories(directory, error);
  if (error) {
    std::cerr << "ipe-write-eds: cannot create " << directory << ": " << error.message() << "\n";
    return 1;
  }
  const bool ok = WriteOne(directory, cip::DriveModel::kVfMb1) && WriteOne(directory, cip::DriveModel::kVfS15);
  return ok ? 0 : 1;
}
