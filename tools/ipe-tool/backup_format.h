// The backup file of `ipe backup` / `ipe restore`: readable text, one parameter a line.
//
//   # ipe backup of a VF-MB1/S15 drive (restore with: tools/ipe restore HOST FILE)
//   # model: VF-MB1
//   # product: VF-MB1
//   # card: 127.0.0.2
//   # date: 2026-11-27T22:00:00Z
//   acc = 5.0 s  # 0009 Acceleration time 1 (unit per f519)
//
// '#' starts a comment (the header fields are comments of the form "# key: value"); blank lines are
// ignored. Pure printing, parsing and the diff against a card.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "parameter_table.h"

namespace ipe {

struct BackupHeader {
  std::string model;    // "VF-MB1"
  std::string product;  // the card's product name
  std::string card;     // the address it was read from
  std::string date;     // UTC, ISO 8601
};

struct BackupValue {
  ParameterInfo info;
  std::int32_t raw = 0;
};

std::string PrintBackup(const BackupHeader& header, const std::vector<BackupValue>& values);

struct ParsedBackup {
  bool ok = false;
  std::string error;  // "FILE line 7: ..." without the file name: "line 7: ..."
  BackupHeader header;
  Model model = Model::kVfMb1;
  std::vector<BackupValue> values;  // in file order
};

// Parses a backup. Errors: no or an unknown "# model:", a line that is not "name = value", a name the
// model does not have or that is not a backed-up setting, a value that does not parse for its
// parameter, a value outside its limits, a name twice.
ParsedBackup ParseBackup(const std::string& text);

struct DiffLine {
  ParameterInfo info;
  std::int32_t card = 0;
  std::int32_t file = 0;
};

// The values of `file` that differ from `card` (same order as `file`); `card` is looked up by number.
std::vector<DiffLine> Diff(const std::vector<BackupValue>& file, const std::vector<BackupValue>& card);
// "acc: 10.0 s -> 5.0 s"
std::string FormatDiffLine(const DiffLine& line);

}  // namespace ipe
