// Captures that cannot be used: each error is one line naming file and line,
// and for a cell the column and the value.
#include <catch2/catch.hpp>

#include <sys/stat.h>

#include <string>

#include "latsim/capture/capture.hpp"
#include "temp_file.hpp"

using namespace latsim::capture;
using latsim::capture::test::TempFile;

namespace {

std::string error_of(const std::filesystem::path& file, std::vector<std::string> columns, ProcessSelect select = {}) {
  try {
    (void)read_capture(file, CaptureRequest{std::move(columns), std::move(select)});
  } catch (const CaptureError& e) {
    const std::string text = e.what();
    CHECK(text.find('\n') == std::string::npos);
    CHECK(text.size() <= 300);
    return text;
  }
  FAIL("no CaptureError");
  return {};
}

const std::string kTwo =
    "Application,ProcessID,MsCPUBusy,MsGPUBusy\n"
    "a.exe,1,1.0,2.0\n"
    "b.exe,2,1.5,2.5\n"
    "a.exe,3,1.0,oops\n";

}  // namespace

TEST_CASE("a missing column names the columns there are, and its name in this generation") {
  const TempFile f("v2_missing.csv", "Application,ProcessID,CPUStartQPC,CPUBusy,GPUBusy\nx,1,1,2,3\n");
  const std::string e = error_of(f.path(), {"MsGPUBusy"});
  CHECK(e == f.path().string() +
                 ":1: no column \"MsGPUBusy\" in this v2 capture (here it is \"GPUBusy\"); its columns: Application, "
                 "ProcessID, CPUStartQPC, CPUBusy, GPUBusy");
}

TEST_CASE("an empty column name is no other generation's name for anything") {
  // The alias table pads its groups with empty names; an empty request used
  // to match every group and list each alias there as "here it is ..." (a
  // line of 586 bytes cut inside a name). Expected by hand: no alias, the
  // header listed.
  const TempFile f("v2_empty.csv", "Application,ProcessID,CPUStartQPC,CPUBusy,GPUBusy\nx,1,1,2,3\n");
  CHECK(error_of(f.path(), {""}) == f.path().string() +
                                      ":1: no column \"\" in this v2 capture; its columns: Application, ProcessID, "
                                      "CPUStartQPC, CPUBusy, GPUBusy");
}

TEST_CASE("a long header is listed in part") {
  std::string header;
  for (int i = 0; i < 40; ++i) header += (i ? ",column" : "column") + std::to_string(i);
  const TempFile f("wide.csv", header + "\n");
  CHECK(error_of(f.path(), {"x"}).find("... (40 in all)") != std::string::npos);
}

TEST_CASE("a malformed cell names the line, the column and the value") {
  const TempFile f("cell.csv", kTwo);
  CHECK(error_of(f.path(), {"MsGPUBusy"}, {.process_id = 3}) ==
        f.path().string() + ":4: column 4 (MsGPUBusy) holds 'oops', not a number of milliseconds");
  const TempFile g("inf.csv", "x\n1e300\n");
  CHECK(error_of(g.path(), {"x"}).find(":2: column 1 (x) holds '1e300', out of range") != std::string::npos);
}

TEST_CASE("several processes and none chosen: the processes are named") {
  const TempFile f("several.csv", kTwo);
  CHECK(error_of(f.path(), {"MsCPUBusy"}) ==
        f.path().string() + ": 3 processes match the capture: choose one with application and process_id: a.exe 1, "
                            "a.exe 3, b.exe 2");
  CHECK(error_of(f.path(), {"MsCPUBusy"}, {.application = "a.exe"}).find("2 processes match a.exe") !=
        std::string::npos);
  CHECK(error_of(f.path(), {"MsCPUBusy"}, {.application = "c.exe"}).find("no rows of c.exe among 3 rows") !=
        std::string::npos);
}

TEST_CASE("a selection needs the process columns; a column needs a value") {
  const TempFile f("plain.csv", "x,y\n1,NA\n");
  CHECK(error_of(f.path(), {"x"}, {.application = "a"}).find("no Application column") != std::string::npos);
  CHECK(error_of(f.path(), {"x"}, {.process_id = 1}).find("no ProcessID column") != std::string::npos);
  CHECK(error_of(f.path(), {"y"}) == f.path().string() + ": column y has no values for the capture (1 NA, 0 not displayed)");
}

TEST_CASE("files that are not captures") {
  const TempFile empty("empty.csv", "\n\n");
  CHECK(error_of(empty.path(), {"x"}).find("no header line") != std::string::npos);
  const TempFile quote("quote.csv", "x,y\n1,\"2\n");
  CHECK(error_of(quote.path(), {"y"}) == quote.path().string() + ":2: an unterminated quote");
  CHECK(latsim::capture::read_capture(quote.path(), {{"x"}, {}}).column("x").values.size() == 1);  // not split so far
  const TempFile short_row("short.csv", "a,b,c\n1,2\n");
  CHECK(error_of(short_row.path(), {"c"}) == short_row.path().string() + ":2: a row of 2 fields; the columns read need 3");
  CHECK(error_of("/nonexistent/capture.csv", {"x"}).find("cannot read the capture file") != std::string::npos);
  CHECK(error_of("/dev/zero", {"x"}).find("not a regular file") != std::string::npos);
  const auto fifo = std::filesystem::temp_directory_path() / ("latsim-capture-fifo-" + std::to_string(::getpid()));
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
  CHECK(error_of(fifo, {"x"}).find("not a regular file") != std::string::npos);
  std::filesystem::remove(fifo);
}

TEST_CASE("a column named twice in the header is refused, not read from its first place") {
  // Two MsGPUBusy columns with different values: the first was taken silently.
  const TempFile f("twice.csv", "Application,ProcessID,MsGPUBusy,MsGPUBusy\na.exe,1,2.0,3.0\n");
  CHECK(error_of(f.path(), {"MsGPUBusy"}) ==
        f.path().string() + ":1: column \"MsGPUBusy\" appears twice in the header: which one is meant cannot be told");
  // A column not read may repeat: nothing depends on which is which.
  const TempFile g("twice_unread.csv", "Application,ProcessID,MsCPUBusy,MsCPUBusy,MsGPUBusy\na.exe,1,1,1,2.0\n");
  CHECK(read_capture(g.path(), CaptureRequest{{"MsGPUBusy"}, {}}).columns.at(0).values.size() == 1);
}
