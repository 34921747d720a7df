// ipe002z-board-flash-check: an image that checks SemihostingFlash against hal/flash.h's contract on
// the emulated board, and that it keeps its bytes across a restart of QEMU. Run twice on one file
// (tests/board/semihosting_flash.sh): `run=first` erases, checks every rule and programs a marker;
// `run=second` finds the marker. Prints one line per check on UART0 ("check NAME ok" or "FAIL NAME ...")
// and ends QEMU through semihosting with status 0 only when every check passed.
#include <algorithm>
#include <array>
#include <cstdint>
#include <span>
#include <string_view>

#include "base/status.h"
#include "hal/text_line.h"
#include "panic.h"
#include "semihosting.h"
#include "semihosting_flash.h"

namespace {

using hal::mps2::SemihostingFlash;

constexpr std::array<std::uint8_t, 8> kMarker = {'I', 'P', 'E', '0', '0', '2', 'Z', 0x5A};
constexpr std::size_t kMarkerOffset = hal::mps2::kFlashSectorSize + 16;  // sector 1, third unit

bool g_passed = true;

void Report(std::string_view name, base::Status got, base::Status expected) {
  hal::TextLine line;
  if (got == expected) {
    line.Text("check ").Text(name).Text(" ok\r\n");
  } else {
    g_passed = false;
    line.Text("FAIL ").Text(name).Text(": ").Text(base::StatusName(got)).Text(", expected ");
    line.Text(base::StatusName(expected)).Text("\r\n");
  }
  hal::mps2::WriteConsolePolled(line.view());
}

void Check(std::string_view name, bool ok) { Report(name, ok ? base::OkStatus() : base::DataLoss(), base::OkStatus()); }

bool ReadsAs(SemihostingFlash& flash, std::size_t offset, std::span<const std::uint8_t> expected) {
  std::array<std::uint8_t, 64> bytes{};
  const auto view = std::span(bytes).first(expected.size());
  return flash.Read(offset, view).ok() && std::equal(view.begin(), view.end(), expected.begin());
}

void FirstRun(SemihostingFlash& flash) {
  Report("erase", flash.Erase(1), base::OkStatus());
  const std::array<std::uint8_t, 16> erased = {0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF,
                                               0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF};
  Check("erased-reads-ff", ReadsAs(flash, kMarkerOffset, erased));
  Report("program", flash.Program(kMarkerOffset, kMarker), base::OkStatus());
  Check("program-reads-back", ReadsAs(flash, kMarkerOffset, kMarker));
  Report("program-twice", flash.Program(kMarkerOffset, kMarker), base::FailedPrecondition());
  Report("misaligned-offset", flash.Program(kMarkerOffset + 3, std::span(kMarker)), base::InvalidArgument());
  Report("misaligned-length", flash.Program(kMarkerOffset + 8, std::span(kMarker).first(5)), base::InvalidArgument());
  Report("program-past-end", flash.Program(flash.Size() - 4, kMarker), base::OutOfRange());
  std::array<std::uint8_t, 8> out{};
  Report("read-past-end", flash.Read(flash.Size() - 4, out), base::OutOfRange());
  Report("erase-past-end", flash.Erase(flash.SectorCount()), base::OutOfRange());
  Check("neighbour-untouched", ReadsAs(flash, kMarkerOffset + 8, std::span(erased).first(8)));
}

void SecondRun(SemihostingFlash& flash) { Check("marker-survived-restart", ReadsAs(flash, kMarkerOffset, kMarker)); }

}  // namespace

int main() {
  hal::mps2::WriteConsolePolled("ipe002z-board-flash-check\r\n");
  std::array<char, 160> path{};
  std::array<char, 16> run{};
  const base::Result<std::string_view> file = hal::mps2::SemihostingArgument("flash", path);
  const base::Result<std::string_view> which = hal::mps2::SemihostingArgument("run", run);
  SemihostingFlash flash;
  if (!file.ok() || !which.ok()) {
    hal::mps2::WriteConsolePolled("FAIL arguments: give flash=PATH and run=first|second\r\n");
    hal::mps2::semihosting::Exit(false);
    return 1;
  }
  Report("open", flash.Open(std::string_view(path.data(), file->size() + 1)), base::OkStatus());
  if (flash.open()) {
    if (which.value() == "first") {
      FirstRun(flash);
    } else {
      SecondRun(flash);
    }
  }
  hal::mps2::WriteConsolePolled(g_passed ? "PASS\r\n" : "FAIL\r\n");
  hal::mps2::semihosting::Exit(g_passed);
  return g_passed ? 0 : 1;
}
