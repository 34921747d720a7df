// backup and restore: every writable EEPROM parameter of the drive to a text file and back.
#include <unistd.h>

#include <cstdio>
#include <ctime>
#include <fstream>
#include <sstream>

#include "backup_format.h"
#include "commands.h"
#include "drive_link/drive_registers.h"
#include "failure.h"
#include "values.h"

namespace ipe {
namespace {

// One progress line on stderr: rewritten in place on a terminal, every 20th and the last one otherwise.
void Progress(const char* what, std::size_t done, std::size_t total, const std::string& name) {
  const bool tty = isatty(STDERR_FILENO) != 0;
  if (!tty && done % 20 != 0 && done != total) return;
  std::fprintf(stderr, "%s%s: %zu/%zu %s%s", tty ? "\r\033[K" : "", what, done, total, name.c_str(),
               tty && done != total ? "" : "\n");
  std::fflush(stderr);
}

std::string UtcNow() {
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&now, &utc);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &utc);
  return text;
}

// Reads every parameter in `list` from the card; a refused read ends the command (exit 1) naming it.
std::vector<BackupValue> ReadAll(Card& card, const std::vector<ParameterInfo>& list, const char* what) {
  std::vector<BackupValue> values;
  for (const ParameterInfo& info : list) {
    const AccessResult result = card.access->Read(info.number);
    if (!result.ok) Fail(kExitRefused, std::string(what) + ": reading " + info.title + " refused by the card: " + result.refusal);
    values.push_back({info, info.FromWord(result.word)});
    Progress(what, values.size(), list.size(), info.title);
  }
  return values;
}

}  // namespace

int RunBackup(const Options& options) {
  const std::string& file = options.args[1];
  Card card = ConnectCard(options, options.args[0]);
  const std::vector<BackupValue> values = ReadAll(card, BackupParameters(card.model), "backup");
  const BackupHeader header{ModelName(card.model), card.product, card.host, UtcNow()};
  std::ofstream out(file, std::ios::trunc);
  out << PrintBackup(header, values);
  out.close();
  if (!out) Fail(kExitUsage, "backup: cannot write " + file);
  std::fprintf(stderr, "backup: %zu parameters of the %s at %s saved to %s\n", values.size(), ModelName(card.model),
               card.host.c_str(), file.c_str());
  return kExitOk;
}

int RunRestore(const Options& options) {
  const std::string& file = options.args[1];
  std::ifstream in(file);
  if (!in) Fail(kExitUsage, "restore: cannot read " + file);
  std::stringstream text;
  text << in.rdbuf();
  const ParsedBackup backup = ParseBackup(text.str());
  if (!backup.ok) Fail(kExitUsage, "restore: " + file + " " + backup.error);

  Card card = ConnectCard(options, options.args[0]);
  if (card.model != backup.model) {
    Fail(kExitUsage, "restore: " + file + " is a backup of a " + ModelName(backup.model) + "; the card at " +
                         card.host + " drives a " + ModelName(card.model) + ": nothing written");
  }
  std::vector<ParameterInfo> list;
  for (const BackupValue& value : backup.values) list.push_back(value.info);
  const std::vector<DiffLine> diff = Diff(backup.values, ReadAll(card, list, "restore: reading"));
  for (const DiffLine& line : diff) std::printf("%s\n", FormatDiffLine(line).c_str());
  std::fflush(stdout);
  if (diff.empty()) {
    std::fprintf(stderr, "restore: the card already holds every value of %s\n", file.c_str());
    return kExitOk;
  }
  if (options.dry_run) {
    std::fprintf(stderr, "restore: %zu differences, nothing written (--dry-run)\n", diff.size());
    return kExitOk;
  }
  // A running drive refuses some parameters (write_during_run no) and a half-restored drive that keeps
  // running on it is worse than none: the restore runs only on a stopped drive.
  const AccessResult status = card.access->Read(drive_link::reg::kFd01);
  if (!status.ok) Fail(kExitRefused, "restore: reading fd01 refused by the card: " + status.refusal);
  if ((status.word & drive_link::reg::status_bit::kRunning) != 0) {
    Fail(kExitRefused, "restore: the drive is running (fd01 bit 10): stop it first; nothing written");
  }
  std::size_t done = 0;
  int refused = 0;
  std::string after_reset;
  for (const DiffLine& line : diff) {
    const AccessResult result = card.access->Write(line.info.number, line.info.ToWord(line.file));
    Progress("restore", ++done, diff.size(), line.info.title);
    if (!result.ok) {
      std::fprintf(stderr, "restore: %s = %s refused by the card: %s\n", line.info.title.c_str(),
                   FormatWithUnit(line.file, line.info).c_str(), result.refusal.c_str());
      ++refused;
      continue;
    }
    if (line.info.effective_after_reset) after_reset += (after_reset.empty() ? "" : ", ") + line.info.title;
  }
  std::fprintf(stderr, "restore: %zu written, %d refused\n", diff.size() - static_cast<std::size_t>(refused), refused);
  if (!after_reset.empty()) {
    std::fprintf(stderr,
                 "restore: %s act only after a reset: power-cycle the drive or write f899=1 "
                 "(tools/ipe set %s f899=1; the card restarts)\n",
                 after_reset.c_str(), card.host.c_str());
  }
  return refused == 0 ? kExitOk : kExitRefused;
}

}  // namespace ipe
