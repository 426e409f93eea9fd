// Reading captures: the three PresentMon generations and a generic CSV, with
// the untidiness of real files. Every expected value is written here, read
// off the hand-written file by eye.
#include <catch2/catch.hpp>

#include <string>

#include "latsim/capture/capture.hpp"
#include "temp_file.hpp"

using namespace latsim::capture;
using latsim::capture::test::TempFile;
using latsim::des::Time;

namespace {

Time ms(double v) { return Time::from_ms(v); }

Capture read(const TempFile& f, std::vector<std::string> columns, ProcessSelect select = {}) {
  return read_capture(f.path(), CaptureRequest{std::move(columns), std::move(select)});
}

// Current generation: a byte-order mark, CRLF line ends, two processes
// interleaved, an NA cell, a frame never displayed (NA in MsUntilDisplayed),
// a quoted field with a comma, a spike, a blank line, extra columns.
const std::string kCurrent =
    "\xEF\xBB\xBF"
    "Application,ProcessID,PresentMode,TimeInQPC,MsBetweenPresents,MsUntilDisplayed,MsCPUBusy,MsGPUBusy\r\n"
    "game.exe,100,\"Hardware: Independent Flip, composed\",1000,16.6,20.1,5.5,8.25\r\n"
    "dwm.exe,7,Composed,1001,16.7,NA,1.0,0.5\r\n"
    "game.exe,100,Composed,1002,16.7,NA,6.0,NA\r\n"
    "\r\n"
    "game.exe,100,Composed,1003,350.0,352.5,340.125,9.0\r\n"
    "dwm.exe,7,Composed,1004,16.6,17.0,1.1,0.6\r\n";

}  // namespace

TEST_CASE("current generation: BOM, CRLF, quotes, one process chosen among two") {
  const TempFile f("current.csv", kCurrent);
  const Capture c = read(f, {"MsGPUBusy", "MsCPUBusy", "MsUntilDisplayed"}, {.application = "GAME.EXE"});
  CHECK(c.generation == Generation::current);
  CHECK(c.application == "game.exe");
  CHECK(c.process_id == 100);
  CHECK(c.rows_read == 5);
  CHECK(c.rows_of_other_processes == 2);
  CHECK(c.rows_selected == 3);
  const CaptureColumn& gpu = c.column("MsGPUBusy");
  CHECK(gpu.values == std::vector<Time>{ms(8.25), ms(9.0)});
  CHECK(gpu.skipped_na == 1);
  CHECK(gpu.skipped_not_displayed == 0);
  // A busy column keeps the frame that was never displayed, and the 340 ms spike.
  const CaptureColumn& cpu = c.column("MsCPUBusy");
  CHECK(cpu.values == std::vector<Time>{ms(5.5), ms(6.0), ms(340.125)});
  CHECK(cpu.min_line == 2);
  CHECK(cpu.max_line == 6);  // line 5 is blank
  CHECK(cpu.mean() == Time::ps((5'500'000'000 + 6'000'000'000 + 340'125'000'000 + 1) / 3));
  const CaptureColumn& shown = c.column("MsUntilDisplayed");
  CHECK(shown.values == std::vector<Time>{ms(20.1), ms(352.5)});
  CHECK(shown.skipped_not_displayed == 1);
  CHECK(shown.skipped_na == 0);
  REQUIRE(shown.values_ms().size() == 2);
  CHECK(shown.values_ms()[0] == Approx(20.1).epsilon(1e-12));
  CHECK(shown.values_ms()[1] == Approx(352.5).epsilon(1e-12));
}

TEST_CASE("a process chosen by id alone, and by application and id") {
  const TempFile f("current_pid.csv", kCurrent);
  CHECK(read(f, {"MsGPUBusy"}, {.process_id = 7}).column("MsGPUBusy").values == std::vector<Time>{ms(0.5), ms(0.6)});
  CHECK(read(f, {"MsGPUBusy"}, {.application = "dwm.exe", .process_id = 7}).application == "dwm.exe");
}

TEST_CASE("v1: Dropped frames keep their busy times but have no display time") {
  const TempFile f("v1.csv",
                   "Application,ProcessID,Dropped,TimeInSeconds,msBetweenPresents,msUntilRenderComplete,"
                   "msUntilDisplayed,msGPUActive\n"
                   "app.exe,5,0,0.10,16.0,2.0,18.0,4.0\n"
                   "app.exe,5,1,0.12,17.0,2.5,0.0,4.5\n"
                   "app.exe,5,0,0.14,15.0,3.0,19.0,5.0");  // no line end at the end
  const Capture c = read(f, {"msUntilDisplayed", "msGPUActive", "msBetweenPresents"});
  CHECK(c.generation == Generation::v1);
  CHECK(c.column("msUntilDisplayed").values == std::vector<Time>{ms(18.0), ms(19.0)});
  CHECK(c.column("msUntilDisplayed").skipped_not_displayed == 1);
  CHECK(c.column("msGPUActive").values == std::vector<Time>{ms(4.0), ms(4.5), ms(5.0)});
  CHECK(c.column("msBetweenPresents").values == std::vector<Time>{ms(16.0), ms(17.0), ms(15.0)});
}

TEST_CASE("v2 columns in another order, a single process chosen by default") {
  const TempFile f("v2.csv",
                   "GPUBusy,CPUBusy,Application,CPUStartQPC,ProcessID,DisplayLatency,FrameTime\n"
                   " 3.5 , 10.25 ,x.exe,1,9,NA,16.5\n"
                   "4,11,x.exe,2,9,30.5,16.75\n");
  const Capture c = read(f, {"CPUBusy", "GPUBusy", "DisplayLatency", "FrameTime"});
  CHECK(c.generation == Generation::v2);
  CHECK(c.process_id == 9);
  CHECK(c.column("CPUBusy").values == std::vector<Time>{ms(10.25), ms(11.0)});
  CHECK(c.column("GPUBusy").values == std::vector<Time>{ms(3.5), ms(4.0)});
  CHECK(c.column("DisplayLatency").values == std::vector<Time>{ms(30.5)});
  CHECK(c.column("DisplayLatency").skipped_not_displayed == 1);
}

TEST_CASE("a generic CSV: any header, no process columns, quoted header names") {
  const TempFile f("generic.csv", "frame,\"render ms\",\"say \"\"hi\"\"\"\n1,2.5,\"7\"\n2,3.5, 8 \n3,NA,9\n");
  const Capture c = read(f, {"render ms"});
  CHECK(c.generation == Generation::generic);
  CHECK(c.application.empty());
  CHECK_FALSE(c.process_id.has_value());
  CHECK(c.column("render ms").values == std::vector<Time>{ms(2.5), ms(3.5)});
  CHECK(c.column("render ms").skipped_na == 1);
  CHECK(read(f, {"say \"hi\""}).column("say \"hi\"").values == std::vector<Time>{ms(7), ms(8), ms(9)});
}

TEST_CASE("generation detection from the header alone") {
  CHECK(detect_generation({"Application", "MsBetweenPresents"}) == Generation::current);
  CHECK(detect_generation({"CPUStartQPC", "MsCPUBusy"}) == Generation::current);
  CHECK(detect_generation({"TimeInSeconds"}) == Generation::v1);
  CHECK(detect_generation({"CPUStartQPC", "CPUBusy"}) == Generation::v2);
  CHECK(detect_generation({"a", "b"}) == Generation::generic);
  CHECK(is_display_column("MsUntilDisplayed"));
  CHECK(is_display_column("DisplayLatency"));
  CHECK_FALSE(is_display_column("MsGPUBusy"));
}
