// Every PresentMon capture shipped (scenarios/measured/captures: the gold
// cases 0 to 3 of PresentMon, each in its three column generations) replayed
// process by process on a display at the capture's own refresh rate and by
// its own present mode: the run's frame intervals match the capture's (KS
// distance at most 0.1), and dwm.exe's frames are flipped when the capture
// says they were.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "latsim/capture/comparison.hpp"
#include "latsim/capture/presentmon.hpp"
#include "latsim/run/runner.hpp"
#include "latsim/scenario/config.hpp"

namespace {

namespace fs = std::filesystem;
using latsim::capture::PresentMonFrame;
using latsim::capture::PresentMonProcess;

const std::string kDir = LATSIM_SOURCE_DIR "/scenarios/measured/captures/";

/// A temporary directory for one run, removed afterwards.
struct TempDir {
  fs::path path = fs::temp_directory_path() / ("latsim-replay-" + std::to_string(::getpid()));
  ~TempDir() { fs::remove_all(path); }
};

/// The capture's refresh rate to the millihertz (a scenario gives at most 6 decimals).
double capture_hz(const std::string& file) {
  return std::round(1e6 / *latsim::capture::refresh_period_ms(kDir + file)) / 1000.0;
}

/// The process replayed once through (at_end stop) on a display refreshing at the capture's rate.
PresentMonProcess replay(const std::string& file, const std::string& application, int64_t process_id, double refresh_hz,
                         const fs::path& out) {
  const nlohmann::json scenario{
      {"duration_s", 600},
      {"motion", {{"type", "constant"}, {"axis", {0, 1, 0}}, {"rate_deg_s", 60}, {"position_m", {0, 1.6, 0}}}},
      {"tracker", {{"rate_hz", 1000}, {"internal_delay_ms", 0}}},
      {"transport", {{"type", "direct"}}},
      {"display", {{"refresh_hz", refresh_hz}, {"width_px", 64}, {"height_px", 48}, {"hfov_deg", 90}}},
      {"pipeline",
       {{"type", "present_replay"},
        {"at_end", "stop"},
        {"capture", {{"file", kDir + file}, {"application", application}, {"process_id", process_id}}}}}};
  fs::remove_all(out);
  latsim::run::RunOptions options;
  options.out_dir = out;
  latsim::run::run_scenario(latsim::scenario::ScenarioDocument::from_json(scenario, kDir), options);
  return latsim::capture::read_presentmon(out / "presentmon.csv", {});
}

/// The frames a replay plays: those with CPU busy, CPU wait and GPU busy.
std::vector<const PresentMonFrame*> replayed(const PresentMonProcess& p) {
  std::vector<const PresentMonFrame*> out;
  for (const PresentMonFrame& f : p.frames)
    if (f.cpu_busy_ms && f.in_present_ms && f.gpu_busy_ms) out.push_back(&f);
  return out;
}

}  // namespace

TEST_CASE("replay: every shipped capture's processes keep their frame intervals on their own display and mode") {
  // The interval into a frame is the time in Present of the frame before
  // plus its own CPU busy time (PresentMon's CPU start is the previous
  // Present's return), so a replay that blocks where the capture's runtime
  // blocked, and nowhere else, gives back the capture's intervals. The first
  // replayed frame's interval reaches to a Present before the capture (or
  // before the replay's start) and is left out on both sides; the rest are
  // frame for frame the same quantity.
  TempDir tmp;
  int processes = 0;
  for (const char* file : {"test_case_0.csv", "test_case_0_v1.csv", "test_case_0_v2.csv", "test_case_1.csv",
                           "test_case_1_v1.csv", "test_case_1_v2.csv", "test_case_2.csv", "test_case_2_v1.csv",
                           "test_case_2_v2.csv", "test_case_3.csv", "test_case_3_v1.csv", "test_case_3_v2.csv"}) {
    const double refresh_hz = capture_hz(file);
    for (const auto& proc : latsim::capture::presentmon_processes(kDir + file)) {
      if (proc.frames < 5) continue;
      INFO(file << " " << proc.application << " " << proc.process_id);
      const PresentMonProcess cap = latsim::capture::read_presentmon(kDir + file, {proc.application, proc.process_id});
      const PresentMonProcess run = replay(file, proc.application, proc.process_id, refresh_hz, tmp.path);
      const auto played = replayed(cap);
      REQUIRE(run.frames.size() == played.size());
      std::vector<double> capture_ms, run_ms;
      for (size_t j = 1; j < played.size(); ++j) {
        if (played[j]->between_presents_ms) capture_ms.push_back(*played[j]->between_presents_ms);
        if (run.frames[j].between_presents_ms) run_ms.push_back(*run.frames[j].between_presents_ms);
      }
      const auto ks = latsim::capture::ks_distance(capture_ms, run_ms);
      REQUIRE(ks);
      CHECK(*ks <= 0.1);
      ++processes;
    }
  }
  CHECK(processes == 57);  // 4 cases x 3 generations: their processes of 5 frames or more
}

TEST_CASE("replay: dwm.exe's frames are flipped at the retraces the capture saw") {
  // dwm.exe presents on a Legacy Flip swap chain with sync interval 1: a
  // frame is flipped at the first retrace after its GPU work, behind the
  // frames queued before it. With the display at the capture's measured
  // refresh rate and the first displayed frame aligned to a retrace, the
  // replay's present-to-flip times follow the capture's within the drift of
  // the period's last digits and the capture's own timing jitter (a few tens
  // of microseconds); a frame the model flips a refresh early or late would
  // be a whole period (16.7 ms) off. Case 0: 197 frames over 3.4 s.
  TempDir tmp;
  const std::string file = "test_case_0.csv";
  const double refresh_hz = capture_hz(file);
  const PresentMonProcess cap = latsim::capture::read_presentmon(kDir + file, {"dwm.exe", 1268});
  const PresentMonProcess run = replay(file, "dwm.exe", 1268, refresh_hz, tmp.path);
  REQUIRE(run.frames.size() == cap.frames.size());
  int within_1ms = 0, displayed = 0;
  for (size_t j = 0; j < cap.frames.size(); ++j) {
    if (!cap.frames[j].until_displayed_ms || !run.frames[j].until_scanout_ms) continue;
    ++displayed;
    if (std::fabs(*cap.frames[j].until_displayed_ms - *run.frames[j].until_scanout_ms) < 1.0) ++within_1ms;
  }
  CHECK(displayed == 197);
  CHECK(within_1ms >= 190);
}
