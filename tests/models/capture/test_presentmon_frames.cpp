// PresentMon's columns read as PresentMon defines them, per generation: the
// same frame of dwm.exe (gold case 0) read from its current, v1 and v2 files
// gives the same quantities, the v1 and v2 ones derived as docs/measured.md
// says and checked here against the current file's cells by hand; the
// limiters and the display's refresh; the warnings a replay gives.
#include <catch2/catch.hpp>

#include "latsim/capture/capture.hpp"
#include "latsim/capture/presentmon.hpp"
#include "temp_file.hpp"

using namespace latsim::capture;

namespace {

const std::string kDir = LATSIM_SOURCE_DIR "/scenarios/measured/captures/";

}  // namespace

TEST_CASE("presentmon: dwm.exe's second frame, the same in the three generations") {
  // The current file, line 3: MsBetweenPresents 33.4043, MsInPresentAPI
  // (= MsCPUWait) 0.1524, MsCPUBusy 33.3150, MsGPUBusy 1.2105, MsGPUTime
  // 33.4282, MsUntilDisplayed 16.3576, MsBetweenDisplayChange 33.3323.
  const PresentMonProcess cur = read_presentmon(kDir + "test_case_0.csv", {"dwm.exe", 1268});
  const PresentMonFrame& c = cur.frames[1];
  CHECK(c.line == 3);
  CHECK(*c.between_presents_ms == 33.4043);
  CHECK(*c.in_present_ms == 0.1524);
  CHECK(*c.cpu_busy_ms == 33.3150);
  CHECK(*c.gpu_busy_ms == 1.2105);
  CHECK(*c.gpu_time_ms == 33.4282);
  CHECK(*c.until_displayed_ms == 16.3576);
  CHECK(*c.between_display_change_ms == 33.3323);
  CHECK(c.sync_interval == 1);
  CHECK(c.mode == PresentMode::hardware_legacy_flip);
  CHECK_FALSE(c.allows_tearing);
  CHECK(c.runtime == "DXGI");
  // v1: CPU busy = msBetweenPresents 33.4043 less the first frame's
  // msInPresentAPI 0.0893 = 33.3150; GPU time = msUntilRenderComplete 0.0912
  // less msUntilRenderStart -33.3370 = 33.4282; GPU busy msGPUActive 1.2105.
  const PresentMonProcess v1 = read_presentmon(kDir + "test_case_0_v1.csv", {"dwm.exe", 1268});
  CHECK(v1.generation == Generation::v1);
  CHECK(*v1.frames[1].cpu_busy_ms == Approx(33.3150).margin(1e-12));
  CHECK(*v1.frames[1].gpu_time_ms == Approx(33.4282).margin(1e-12));
  CHECK(*v1.frames[1].gpu_busy_ms == 1.2105);
  CHECK(*v1.frames[1].until_displayed_ms == 16.3576);
  CHECK_FALSE(v1.frames[0].cpu_busy_ms);  // its previous present is not in the file
  // v2: the interval = the first frame's CPUWait 0.0893 + CPUBusy 33.3150 =
  // 33.4043; until displayed = DisplayLatency 49.6726 less CPUBusy = 16.3576;
  // the display change = the first frame's DisplayedTime 33.3323.
  const PresentMonProcess v2 = read_presentmon(kDir + "test_case_0_v2.csv", {"dwm.exe", 1268});
  CHECK(v2.generation == Generation::v2);
  CHECK(*v2.frames[1].between_presents_ms == Approx(33.4043).margin(1e-12));
  CHECK(*v2.frames[1].until_displayed_ms == Approx(16.3576).margin(1e-12));
  CHECK(*v2.frames[1].between_display_change_ms == 33.3323);
  CHECK(*v2.frames[1].in_present_ms == 0.1524);
  CHECK_FALSE(v2.frames[0].between_presents_ms);
}

TEST_CASE("presentmon: frames never displayed, in each generation's way") {
  // Presenter.exe 10792, frame 6 (line 57 of the current file): NA display
  // columns; the same frame in v1 has Dropped 1; in v2 DisplayedTime NA.
  for (const char* file : {"test_case_0.csv", "test_case_0_v1.csv", "test_case_0_v2.csv"}) {
    INFO(file);
    const PresentMonProcess p = read_presentmon(kDir + file, {"Presenter.exe", 10792});
    int not_displayed = 0;
    for (const PresentMonFrame& f : p.frames) not_displayed += f.displayed ? 0 : 1;
    CHECK(not_displayed == 1);
    CHECK(p.mode() == PresentMode::composed_copy_gpu_gdi);
    CHECK(p.sync_interval() == -1);
  }
}

TEST_CASE("presentmon: the display's refresh from its display-change intervals") {
  // Case 0's 230 intervals of frames flipped at a vertical blank (sync
  // interval 1 or more, no tearing) make 279 whole periods whose sum gives
  // 16.6794 ms: 59.954 Hz (their median, 16.6799 ms, is one period).
  CHECK(*refresh_period_ms(kDir + "test_case_0.csv") == Approx(16.6794).margin(1e-4));
  CHECK(*refresh_period_ms(kDir + "test_case_0_v1.csv") == Approx(16.68).margin(0.01));
  CHECK(*refresh_period_ms(kDir + "test_case_0_v2.csv") == Approx(16.68).margin(0.01));
}

TEST_CASE("presentmon: no refresh when no interval is a whole number of the median's periods") {
  // Two vsynced display changes, 1 ms and 2 ms apart: their median is 1.5 ms;
  // 1 ms is one such period 33 % short, 2 ms one period 33 % long, both past
  // the 10 % a whole number of periods may be off. No refresh period (found
  // by fuzzing: the sum over no periods was 0/0, a NaN refresh).
  const test::TempFile f("two_intervals.csv",
                         "Application,ProcessID,SyncInterval,AllowsTearing,TimeInSeconds,MsBetweenPresents,"
                         "MsBetweenDisplayChange\n"
                         "app.exe,1,1,0,0.001,1,1\n"
                         "app.exe,1,1,0,0.003,2,2\n");
  CHECK_FALSE(refresh_period_ms(f.path()).has_value());
}

TEST_CASE("presentmon: a replay warns of an uncapped, a composed, another refresh rate, and busy that waits") {
  const auto period = refresh_period_ms(kDir + "test_case_0.csv");
  auto warnings = [&](const char* app, int64_t pid, double hz, bool busy) {
    return presentmon_warnings(read_presentmon(kDir + "test_case_0.csv", {app, pid}), period, hz, busy);
  };
  auto has = [](const std::vector<std::string>& w, const char* text) {
    for (const std::string& s : w)
      if (s.find(text) != std::string::npos) return true;
    return false;
  };
  // dwm.exe on its own display: only its CPU busy, when read as work.
  CHECK(warnings("dwm.exe", 1268, 59.954, false).empty());
  CHECK(has(warnings("dwm.exe", 1268, 59.954, true), "holds waiting"));
  CHECK(has(warnings("dwm.exe", 1268, 90.0, false), "refreshing at 59.95 Hz"));
  // Presenter.exe 11648: sync interval 0 with tearing; 12268: Composed: Flip.
  CHECK(has(warnings("Presenter.exe", 11648, 59.954, false), "uncapped"));
  CHECK(has(warnings("Presenter.exe", 12268, 59.954, false), "desktop compositor"));
}

TEST_CASE("presentmon: a cell the capture reader refuses is refused here too (one verdict per file)") {
  // 1e308 ms passed this reader and printed 310 digits in compare.md; the
  // capture reader refuses anything past 1e9 ms. Both readers on one file:
  const std::string header = "Application,ProcessID,MsBetweenPresents,MsGPUBusy,MsCPUBusy\n";
  const test::TempFile f("pm_1e308.csv", header + "a.exe,1,16.6,1e308,1\n");
  CHECK_THROWS_WITH(read_presentmon(f.path(), {"a.exe", 1}), Catch::Contains("out of range"));
  CHECK_THROWS_WITH(read_capture(f.path(), CaptureRequest{{"MsGPUBusy"}, {}}), Catch::Contains("out of range"));
  // 1e9 ms itself is within both.
  const test::TempFile g("pm_1e9.csv", header + "a.exe,1,16.6,1e9,1\n");
  CHECK(read_presentmon(g.path(), {"a.exe", 1}).frames.at(0).gpu_busy_ms.value() == Approx(1e9));
  CHECK(read_capture(g.path(), CaptureRequest{{"MsGPUBusy"}, {}}).columns.at(0).values.size() == 1);
}

TEST_CASE("presentmon: a ProcessID or SyncInterval no integer type holds is not a number read wrapped") {
  // Found by fuzz_compare (tests/fuzz/regressions/compare/process_id_1e19.csv):
  // 9999999999999000000 is above 2^63 - 1 = 9223372036854775807, and a
  // SyncInterval of 1e300 above any int. The process list counts the rows
  // (2 of 3, by hand) under no process id, the same verdict as the readers'
  // (a ProcessID that is no integer leaves the process unnamed); the frame's
  // sync interval stays "not said" (-1).
  const latsim::capture::test::TempFile file(
      "pid_1e19.csv",
      "Application,ProcessID,SwapChainAddress,Runtime,SyncInterval,PresentFlags,AllowsTearing,PresentMode,"
      "MsBetweenPresents,MsInPresentAPI,MsUntilDisplayed,MsBetweenDisplayChange\n"
      "a.exe,9999999999999000000,0x1,DXGI,1e300,0,0,Hardware: Legacy Flip,16.6,0.1,10.0,16.6\n"
      "a.exe,9999999999999000000,0x1,DXGI,1e300,0,0,Hardware: Legacy Flip,16.7,0.1,10.0,16.7\n"
      "b.exe,12,0x1,DXGI,1,0,0,Hardware: Legacy Flip,16.7,0.1,10.0,16.7\n");
  const auto processes = presentmon_processes(file.path());
  REQUIRE(processes.size() == 2);
  CHECK(processes[0].application == "a.exe");
  CHECK(processes[0].process_id == 0);
  CHECK(processes[0].frames == 2);
  CHECK(processes[1].process_id == 12);
  const PresentMonProcess a = read_presentmon(file.path(), {"a.exe", std::nullopt});
  REQUIRE(a.frames.size() == 2);
  CHECK_FALSE(a.process_id.has_value());
  CHECK(a.frames[0].sync_interval == -1);
}
