// PresentMonLog: which rows are written when, and what they hold, for frames
// given by hand (every expected cell derived in the comments).
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <unistd.h>
#include <vector>

#include "latsim/results/presentmon_log.hpp"
#include "latsim/results/run_files.hpp"

namespace {

using latsim::des::Time;
using latsim::results::FrameTimes;
using latsim::results::PresentMonLog;
using latsim::results::RunFiles;
namespace fs = std::filesystem;

// A frame with CPU work from `start_ms`: CPU busy 2 ms, present at +3 ms, GPU
// from +3.5 ms to +10 ms of which 6 ms busy.
FrameTimes frame(int64_t id, double start_ms) {
  FrameTimes f;
  f.frame = id;
  f.has_cpu = true;
  f.cpu_start = Time::from_ms(start_ms);
  f.cpu_busy = Time::ms(2);
  f.present = Time::from_ms(start_ms + 3);
  f.gpu_start = Time::from_ms(start_ms + 3.5);
  f.gpu_end = Time::from_ms(start_ms + 10);
  f.gpu_busy = Time::ms(6);
  return f;
}

struct Dir {
  fs::path path = fs::temp_directory_path() / ("latsim_presentmon_log_" + std::to_string(::getpid()));
  Dir() { fs::remove_all(path); }
  ~Dir() { fs::remove_all(path); }
};

std::vector<std::string> lines_of(const fs::path& file) {
  std::ifstream in(file);
  std::vector<std::string> out;
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

// The cells of a row from column `first` on.
std::vector<std::string> cells(const std::string& row) {
  std::vector<std::string> out;
  std::stringstream s(row);
  for (std::string c; std::getline(s, c, ',');) out.push_back(c);
  return out;
}

}  // namespace

TEST_CASE("presentmon.csv: rows in frame order once final, NA for frames passed over, none for frames in flight") {
  Dir dir;
  {
    RunFiles files(dir.path);
    PresentMonLog log("frame_stages", {.sync_interval = 1, .allows_tearing = false});
    // Frame 1 completes before frame 0 (alternate frame rendering).
    log.completed(frame(1, 20), files);
    log.completed(frame(0, 0), files);
    // Frame 0 first lit at 16.5 ms (right eye), then 16 ms (left eye): 16 ms is its first photon.
    log.shown(0, Time::from_ms(16.5), files);
    log.shown(0, Time::ms(16), files);
    CHECK(log.rows() == 0);  // frame 0 may still have an earlier image: not final
    // Frame 1 is never lit; frame 2 is (it was newer): rows 0 and 1 are final.
    log.completed(frame(2, 40), files);
    log.shown(2, Time::ms(64), files);
    CHECK(log.rows() == 2);
    // Frame 3 completes but is not lit before the end: no row.
    log.completed(frame(3, 60), files);
    log.finish(files);
    CHECK(log.rows() == 3);
    files.commit();
  }
  const auto rows = lines_of(dir.path / "presentmon.csv");
  REQUIRE(rows.size() == 4);
  CHECK(rows[0] ==
        "Application,ProcessID,SwapChainAddress,PresentRuntime,SyncInterval,AllowsTearing,FrameType,TimeInSeconds,"
        "MsBetweenPresents,MsBetweenDisplayChange,MsRenderPresentLatency,MsUntilDisplayed,CPUStartTimeInSeconds,"
        "MsCPUBusy,MsGPULatency,MsGPUTime,MsGPUBusy,MsGPUWait,FrameId,PresentMode,MsInPresentAPI,MsCPUWait,"
        "MsBetweenAppStart,MsUntilScanout");
  // Frame 0: present at 3 ms; no previous present or photon; GPU end 10 - present 3 = 7; displayed 16 - 3 = 13;
  // CPU start 0; busy 2; GPU latency 3.5 - 0; GPU time 10 - 3.5 = 6.5, busy 6, wait 0.5.
  CHECK(rows[1] ==
        "frame_stages,0,0x0,latsim,1,0,Application,0.003000000000,NA,NA,7.000000000,13.000000000,0.000000000000,"
        "2.000000000,3.500000000,6.500000000,6.000000000,0.500000000,0,NA,NA,NA,NA,NA");
  // Frame 1: present 23 ms, 20 after frame 0's; never displayed: NA, NA.
  const auto f1 = cells(rows[2]);
  CHECK(f1[7] == "0.023000000000");
  CHECK(f1[8] == "20.000000000");
  CHECK(f1[9] == "NA");
  CHECK(f1[11] == "NA");
  CHECK(f1[18] == "1");
  // Frame 2: present 43 ms; first photon 64 ms, 48 after frame 0's (the last displayed); until displayed 21.
  const auto f2 = cells(rows[3]);
  CHECK(f2[7] == "0.043000000000");
  CHECK(f2[8] == "20.000000000");
  CHECK(f2[9] == "48.000000000");
  CHECK(f2[11] == "21.000000000");
}

TEST_CASE("presentmon.csv: a frame without CPU work has NA CPU columns, and times are exact to the picosecond") {
  Dir dir;
  {
    RunFiles files(dir.path);
    PresentMonLog log("double_buffer", {.sync_interval = 0, .allows_tearing = true});
    FrameTimes f;
    f.frame = 0;
    f.gpu_start = Time::ps(1);
    f.present = f.gpu_end = Time::ps(12'345'678'901);  // 12.345678901 ms
    f.gpu_busy = f.gpu_end - f.gpu_start;
    log.completed(f, files);
    log.shown(0, Time::ps(20'000'000'000), files);
    log.finish(files);
    files.commit();
  }
  const auto rows = lines_of(dir.path / "presentmon.csv");
  REQUIRE(rows.size() == 2);
  // Present 12345678901 ps = 0.012345678901 s; render-present 0; until displayed 20 ms - 12.345678901 ms.
  CHECK(rows[1] ==
        "double_buffer,0,0x0,latsim,0,1,Application,0.012345678901,NA,NA,0.000000000,7.654321099,NA,NA,NA,"
        "12.345678900,12.345678900,0.000000000,0,NA,NA,NA,NA,NA");
}

TEST_CASE("presentmon.csv: a pipeline that models the Present call and the flip fills their columns") {
  // present_replay's facts: a Legacy Flip swap chain; frame 0 presented at
  // 3 ms after 2 ms of CPU busy time, its call returning 0.5 ms later (CPU
  // wait 0.5, CPU start to next CPU start 2.5), flipped in at the retrace at
  // 16 ms (scanout 16 - 3 = 13 ms after the present) and first lit at 16.5.
  Dir dir;
  {
    RunFiles files(dir.path);
    PresentMonLog log("present_replay", {.sync_interval = 1, .present_mode = "Hardware: Legacy Flip"});
    FrameTimes f = frame(0, 0);
    f.in_present = Time::us(500);
    log.completed(f, files);
    log.flipped(0, Time::ms(16));
    log.shown(0, Time::from_ms(16.5), files);
    log.finish(files);
    files.commit();
  }
  const auto rows = lines_of(dir.path / "presentmon.csv");
  REQUIRE(rows.size() == 2);
  const auto c = cells(rows[1]);
  REQUIRE(c.size() == 24);
  CHECK(c[11] == "13.500000000");  // MsUntilDisplayed: first light
  CHECK(c[19] == "Hardware: Legacy Flip");
  CHECK(c[20] == "0.500000000");
  CHECK(c[21] == "0.500000000");
  CHECK(c[22] == "2.500000000");
  CHECK(c[23] == "13.000000000");  // MsUntilScanout: the flip, PresentMon's display time
}

TEST_CASE("presentmon.csv: a run with no frame shown writes no file") {
  Dir dir;
  {
    RunFiles files(dir.path);
    PresentMonLog log("frame_stages", {});
    log.completed(frame(0, 0), files);
    log.finish(files);
    CHECK(log.rows() == 0);
    files.write_text("summary.json", "{}\n");
    files.commit();
  }
  CHECK(fs::exists(dir.path / "summary.json"));
  CHECK_FALSE(fs::exists(dir.path / "presentmon.csv"));
}

TEST_CASE("presentmon.csv: a pipeline that shows none of its frames writes each once complete, NA for display") {
  Dir dir;
  {
    RunFiles files(dir.path);
    PresentMonLog log("frame_stages", {.sync_interval = 1, .allows_tearing = false, .shown = false});
    log.completed(frame(1, 20), files);
    CHECK(log.rows() == 0);  // frame 0 comes first
    log.completed(frame(0, 0), files);
    CHECK(log.rows() == 2);
    log.completed(frame(3, 60), files);  // frame 2 never completes: 3 waits for it until the end
    CHECK(log.rows() == 2);
    log.finish(files);
    CHECK(log.rows() == 3);
    files.commit();
  }
  const auto rows = lines_of(dir.path / "presentmon.csv");
  REQUIRE(rows.size() == 4);
  for (size_t i = 1; i < rows.size(); ++i) {
    CHECK(cells(rows[i])[9] == "NA");
    CHECK(cells(rows[i])[11] == "NA");
  }
  CHECK(cells(rows[3])[18] == "3");
  // Frame 3's present (63 ms) follows frame 1's (23 ms) in the file: 40 ms between them.
  CHECK(cells(rows[3])[8] == "40.000000000");
}
