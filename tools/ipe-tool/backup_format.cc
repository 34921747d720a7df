#include "backup_format.h"

#include <cstdio>
#include <map>
#include <set>
#include <sstream>

#include "text.h"
#include "values.h"

namespace ipe {
namespace {

std::string Trim(const std::string& text) { return std::string(ipe::Trim(std::string_view(text))); }

ParsedBackup Error(std::size_t line, const std::string& message) {
  ParsedBackup parsed;
  parsed.error = "line " + std::to_string(line) + ": " + message;
  return parsed;
}

}  // namespace

std::string PrintBackup(const BackupHeader& header, const std::vector<BackupValue>& values) {
  std::string text = "# ipe backup of a VF-MB1/S15 drive (restore with: tools/ipe restore HOST FILE)\n";
  text += "# model: " + header.model + "\n";
  text += "# product: " + header.product + "\n";
  text += "# card: " + header.card + "\n";
  text += "# date: " + header.date + "\n";
  for (const BackupValue& value : values) {
    char number[8];
    std::snprintf(number, sizeof number, "%04X", value.info.number);
    text += value.info.title + " = " + FormatWithUnit(value.raw, value.info) + "  # " + number + " " +
            value.info.function + "\n";
  }
  return text;
}

ParsedBackup ParseBackup(const std::string& text) {
  ParsedBackup parsed;
  std::istringstream lines(text);
  std::string line;
  std::size_t number = 0;
  bool have_model = false;
  std::set<std::uint16_t> seen;
  std::vector<std::pair<std::size_t, std::string>> entries;
  while (std::getline(lines, line)) {
    ++number;
    const std::string content = Trim(line);
    if (content.empty()) continue;
    if (content[0] == '#') {
      const std::size_t colon = content.find(':');
      if (colon == std::string::npos) continue;
      const std::string key = Trim(content.substr(1, colon - 1));
      const std::string value = Trim(content.substr(colon + 1));
      if (key == "model") {
        const std::optional<Model> model = ModelFromName(value);
        if (!model) return Error(number, "unknown model '" + value + "' (VF-MB1 or VF-S15)");
        parsed.model = *model;
        parsed.header.model = ModelName(*model);
        have_model = true;
      } else if (key == "product") {
        parsed.header.product = value;
      } else if (key == "card") {
        parsed.header.card = value;
      } else if (key == "date") {
        parsed.header.date = value;
      }
      continue;
    }
    entries.emplace_back(number, content);
  }
  if (!have_model) return Error(number, "no '# model:' line: not an ipe backup");
  for (const auto& [at, content] : entries) {
    const std::string body = Trim(content.substr(0, content.find('#')));
    const std::size_t equals = body.find('=');
    if (equals == std::string::npos) return Error(at, "expected 'name = value', got '" + body + "'");
    const std::string name = Trim(body.substr(0, equals));
    const std::string value_text = Trim(body.substr(equals + 1));
    const std::optional<ParameterInfo> info = FindParameter(name, parsed.model);
    if (!info) return Error(at, "no parameter '" + name + "' on " + ModelName(parsed.model));
    if (!info->setting) return Error(at, name + " is not a setting a backup holds");
    if (!seen.insert(info->number).second) return Error(at, name + " appears twice");
    const ParsedValue value = ParseValue(value_text, *info);
    if (!value.ok) return Error(at, value.error);
    if (const std::string range = CheckRange(value.raw, *info, parsed.model); !range.empty()) return Error(at, range);
    parsed.values.push_back({*info, value.raw});
  }
  parsed.ok = true;
  return parsed;
}

std::vector<DiffLine> Diff(const std::vector<BackupValue>& file, const std::vector<BackupValue>& card) {
  std::map<std::uint16_t, std::int32_t> on_card;
  for (const BackupValue& value : card) on_card[value.info.number] = value.raw;
  std::vector<DiffLine> lines;
  for (const BackupValue& value : file) {
    const auto it = on_card.find(value.info.number);
    if (it == on_card.end() || it->second == value.raw) continue;
    lines.push_back({value.info, it->second, value.raw});
  }
  return lines;
}

std::string FormatDiffLine(const DiffLine& line) {
  return line.info.title + ": " + FormatWithUnit(line.card, line.info) + " -> " + FormatWithUnit(line.file, line.info);
}

}  // namespace ipe
