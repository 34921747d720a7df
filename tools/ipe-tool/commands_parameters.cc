// get, set and watch: drive parameters by panel title.
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <thread>

#include "commands.h"
#include "failure.h"
#include "values.h"

namespace ipe {
namespace {

// Names are checked before the card is contacted: a name neither model has is a usage error at once.
void CheckNamesExist(const std::vector<std::string>& names) {
  for (const std::string& name : names) {
    if (!FindParameter(name, Model::kVfMb1) && !FindParameter(name, Model::kVfS15)) {
      Fail(kExitUsage, "unknown parameter '" + name + "' (a panel title such as acc, dec, fh, c101, fd00)");
    }
  }
}

ParameterInfo Lookup(const std::string& name, Model model) {
  const std::optional<ParameterInfo> info = FindParameter(name, model);
  if (!info) Fail(kExitUsage, "the " + std::string(ModelName(model)) + " has no parameter '" + name + "'");
  return *info;
}

struct Assignment {
  ParameterInfo info;
  std::int32_t raw = 0;
};

}  // namespace

int RunGet(const Options& options) {
  const std::vector<std::string> names(options.args.begin() + 1, options.args.end());
  CheckNamesExist(names);
  Card card = ConnectCard(options, options.args[0]);
  int status = kExitOk;
  for (const std::string& name : names) {
    const ParameterInfo info = Lookup(name, card.model);
    const AccessResult result = card.access->Read(info.number);
    if (!result.ok) {
      std::fprintf(stderr, "ipe: get %s: refused by the card: %s\n", info.title.c_str(), result.refusal.c_str());
      status = kExitRefused;
      continue;
    }
    std::printf("%s = %s\n", info.title.c_str(), FormatWithUnit(info.FromWord(result.word), info).c_str());
  }
  return status;
}

int RunSet(const Options& options) {
  std::vector<std::pair<std::string, std::string>> pairs;
  for (std::size_t i = 1; i < options.args.size(); ++i) {
    const std::string& argument = options.args[i];
    const std::size_t equals = argument.find('=');
    if (equals == std::string::npos || equals == 0) Fail(kExitUsage, "set wants NAME=VALUE, not '" + argument + "'");
    pairs.emplace_back(argument.substr(0, equals), argument.substr(equals + 1));
  }
  std::vector<std::string> names;
  for (const auto& pair : pairs) names.push_back(pair.first);
  CheckNamesExist(names);
  Card card = ConnectCard(options, options.args[0]);
  // Every value is parsed and checked against the model's limits before the first write.
  std::vector<Assignment> assignments;
  for (const auto& [name, text] : pairs) {
    Assignment a{Lookup(name, card.model), 0};
    if (!a.info.host_writable) Fail(kExitUsage, a.info.title + " is read-only (" + a.info.function + ")");
    const ParsedValue value = ParseValue(text, a.info);
    if (!value.ok) Fail(kExitUsage, value.error);
    if (const std::string range = CheckRange(value.raw, a.info, card.model); !range.empty()) Fail(kExitUsage, range);
    a.raw = value.raw;
    assignments.push_back(a);
  }
  int status = kExitOk;
  for (const Assignment& a : assignments) {
    const AccessResult result = card.access->Write(a.info.number, a.info.ToWord(a.raw));
    if (!result.ok) {
      std::fprintf(stderr, "ipe: set %s = %s: refused by the card: %s\n", a.info.title.c_str(),
                   FormatWithUnit(a.raw, a.info).c_str(), result.refusal.c_str());
      status = kExitRefused;
      continue;
    }
    std::printf("%s = %s\n", a.info.title.c_str(), FormatWithUnit(a.raw, a.info).c_str());
  }
  return status;
}

int RunWatch(const Options& options) {
  const std::vector<std::string> names(options.args.begin() + 1, options.args.end());
  CheckNamesExist(names);
  Card card = ConnectCard(options, options.args[0]);
  std::vector<ParameterInfo> infos;
  for (const std::string& name : names) infos.push_back(Lookup(name, card.model));
  InstallInterruptHandler();
  const auto interval = std::chrono::milliseconds(options.interval_ms);
  auto next = std::chrono::steady_clock::now();
  for (std::uint32_t line = 0; !options.count || line < *options.count; ++line) {
    std::string text;
    for (const ParameterInfo& info : infos) {
      const AccessResult result = card.access->Read(info.number);
      if (!result.ok) Fail(kExitRefused, "watch " + info.title + ": refused by the card: " + result.refusal);
      if (!text.empty()) text += "  ";
      text += info.title + " = " + FormatWithUnit(info.FromWord(result.word), info);
    }
    std::printf("%s\n", text.c_str());
    std::fflush(stdout);
    if (options.count && line + 1 >= *options.count) break;
    next += interval;
    // Sleep in short steps so that Ctrl-C ends the watch at once.
    while (!Interrupted() && std::chrono::steady_clock::now() < next) {
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    if (Interrupted()) break;
  }
  return kExitOk;
}

}  // namespace ipe
