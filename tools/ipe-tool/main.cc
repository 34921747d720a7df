// tools/ipe: the commissioning tool (docs/commissioning.md). Parses the command line and runs one
// command; a Failure ends it with its exit code and message.
#include <cstdio>
#include <string>
#include <vector>

#include "cli.h"
#include "commands.h"
#include "failure.h"

int main(int argc, char** argv) {
  const std::vector<std::string> arguments(argv + 1, argv + argc);
  const ipe::ParsedCommandLine parsed = ipe::ParseCommandLine(arguments);
  if (!parsed.ok) {
    std::fprintf(stderr, "ipe: %s\n", parsed.error.c_str());
    return ipe::kExitUsage;
  }
  const ipe::Options& options = parsed.options;
  if (options.help) {
    std::fputs(options.command.empty() ? ipe::UsageText().c_str() : ipe::CommandHelp(options.command).c_str(), stdout);
    return ipe::kExitOk;
  }
  try {
    const std::string& c = options.command;
    if (c == "discover") return ipe::RunDiscover(options);
    if (c == "identity") return ipe::RunIdentity(options);
    if (c == "get") return ipe::RunGet(options);
    if (c == "set") return ipe::RunSet(options);
    if (c == "watch") return ipe::RunWatch(options);
    if (c == "backup") return ipe::RunBackup(options);
    if (c == "restore") return ipe::RunRestore(options);
    if (c == "io") return ipe::RunIo(options);
    if (c == "eds") return ipe::RunEds(options);
  } catch (const ipe::Failure& failure) {
    std::fprintf(stderr, "ipe: %s\n", failure.message.c_str());
    return failure.code;
  }
  return ipe::kExitUsage;  // cannot happen: the parser knows the same commands
}
