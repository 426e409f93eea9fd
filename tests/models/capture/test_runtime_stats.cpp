// The runtimes' own statistics read as their tools define them: every OVR
// Metrics Tool export shipped (scenarios/measured/captures/ovr-metrics, real
// exports of a Quest 2 class headset), the two real VrApi lines, and a
// SteamVR frame timing file written from OpenVR's documented fields; each
// as a comparison target (read_runtime_stats) and as a workload (read_capture).
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <numeric>

#include "latsim/capture/capture.hpp"
#include "latsim/capture/runtime_stats.hpp"
#include "temp_file.hpp"

using namespace latsim::capture;
using latsim::capture::test::TempFile;

namespace {

const std::string kDir = LATSIM_SOURCE_DIR "/scenarios/measured/captures/";

double mean(const StatSeries& s) { return std::accumulate(s.values.begin(), s.values.end(), 0.0) / s.values.size(); }

/// Milliseconds read as picoseconds and back: equal to a picosecond.
bool same_ms(const std::vector<double>& got, const std::vector<double>& want) {
  if (got.size() != want.size()) return false;
  for (size_t i = 0; i < got.size(); ++i)
    if (std::fabs(got[i] - want[i]) > 1e-9) return false;
  return true;
}

}  // namespace

TEST_CASE("runtime stats: an OVR Metrics export, counted by hand") {
  // OGMP_1.csv: 106 rows. The first (Time Stamp 888: 888 ms since the tool
  // started, 1 frame counted) and the last (105679, 784 ms after the one
  // before, repeating it) are no second's figures; the 104 between are. Their
  // means, summed by hand from the file: average_frame_rate 67.8365,
  // average_prediction_milliseconds 47.1058, stale_frame_count 6.3173,
  // early_frame_count 65.0769, screen_tear_count 0, app_gpu_time_microseconds
  // 5519.17 (5.51917 ms), timewarp_gpu_time_microseconds 1283.28.
  const RuntimeStats s = read_runtime_stats(kDir + "ovr-metrics/OGMP_1.csv");
  CHECK(s.generation == Generation::ovr_metrics);
  CHECK(s.rows_read == 106);
  CHECK(s.partial_rows == 2);
  REQUIRE(s.find("frame_rate_hz"));
  CHECK(s.find("frame_rate_hz")->values.size() == 104);
  CHECK(s.find("frame_rate_hz")->lines.front() == 3);  // the header is line 1, the partial first row line 2
  CHECK(mean(*s.find("frame_rate_hz")) == Approx(67.8365).margin(1e-4));
  CHECK(mean(*s.find("prediction_ms")) == Approx(47.1058).margin(1e-4));
  CHECK(mean(*s.find("stale_per_s")) == Approx(6.3173).margin(1e-4));
  CHECK(mean(*s.find("early_per_s")) == Approx(65.0769).margin(1e-4));
  CHECK(mean(*s.find("tears_per_s")) == 0.0);
  CHECK(mean(*s.find("app_gpu_ms")) == Approx(5.51917).margin(1e-5));
  CHECK(mean(*s.find("timewarp_gpu_ms")) == Approx(1.28328).margin(1e-5));
  CHECK(mean(*s.find("refresh_hz")) == 72.0);
}

TEST_CASE("runtime stats: every shipped OVR Metrics export reads, at 72 and at 120 Hz") {
  // What the exports' README states and a reading of each file confirms:
  // at 72 Hz the runtime predicts 46.7 to 47.4 ms ahead and shows 66.7 to
  // 69.1 new frames a second; at 120 Hz 32.0 to 32.5 ms and 104 to 108.
  int files = 0;
  for (const auto& e : std::filesystem::recursive_directory_iterator(kDir + "ovr-metrics")) {
    if (e.path().extension() != ".csv") continue;
    INFO(e.path().string());
    const RuntimeStats s = read_runtime_stats(e.path());
    const double hz = mean(*s.find("refresh_hz"));
    const double prd = mean(*s.find("prediction_ms")), fps = mean(*s.find("frame_rate_hz"));
    if (hz == 72.0) {
      CHECK(prd == Approx(47.05).margin(0.35));
      CHECK(fps == Approx(67.9).margin(1.2));
    } else {
      CHECK(hz == 120.0);
      CHECK(prd == Approx(32.25).margin(0.25));
      CHECK(fps == Approx(106.0).margin(2.0));
    }
    ++files;
  }
  CHECK(files == 29);  // 12 at 72 Hz, 17 at 120 Hz
}

TEST_CASE("runtime stats: both VrApi lines, field by field") {
  // FPS=72/72,Prd=28ms,Tear=0,Early=0,Stale=1,...,TW=2.39ms,App=1.73ms and
  // FPS=16/72,Prd=83ms,Tear=2,Early=2,Stale=56,...,TW=8.91ms,App=11.80ms.
  const RuntimeStats s = read_runtime_stats(kDir + "vrapi/vrapi_stats_lines.txt");
  CHECK(s.generation == Generation::vrapi);
  CHECK(s.rows_read == 2);
  CHECK(s.find("frame_rate_hz")->values == std::vector<double>{72, 16});
  CHECK(s.find("refresh_hz")->values == std::vector<double>{72, 72});
  CHECK(s.find("prediction_ms")->values == std::vector<double>{28, 83});
  CHECK(s.find("tears_per_s")->values == std::vector<double>{0, 2});
  CHECK(s.find("early_per_s")->values == std::vector<double>{0, 2});
  CHECK(s.find("stale_per_s")->values == std::vector<double>{1, 56});
  CHECK(s.find("app_gpu_ms")->values == std::vector<double>{1.73, 11.80});
  CHECK(s.find("timewarp_gpu_ms")->values == std::vector<double>{2.39, 8.91});
}

TEST_CASE("runtime stats: VrApi lines inside a logcat dump, with what logcat writes around them") {
  const TempFile f("logcat.txt",
                   "--------- beginning of main\n"
                   "01-02 12:00:00.000  1234  1234 I SomethingElse: hello\n"
                   "01-02 12:00:01.000  1234  1300 I VrApi   : FPS=72/72,Prd=45ms,Tear=0,Early=0,Stale=0,"
                   "CPU4/GPU=2/3,1171/490MHz,TW=1.25ms,App=4.49ms,LCnt=2(DR72,LM2),GPU%=0.43\n"
                   "01-02 12:00:01.500  1234  1234 I SomethingElse: again\n"
                   "01-02 12:00:02.000  1234  1300 I VrApi   : FPS=71/72,Prd=46ms,Tear=0,Early=1,Stale=1,"
                   "CPU4/GPU=2/3,1171/490MHz,TW=1.30ms,App=4.60ms,LCnt=2(DR72,LM2),GPU%=0.44\n");
  const RuntimeStats s = read_runtime_stats(f.path());
  CHECK(s.rows_read == 2);
  CHECK(s.find("frame_rate_hz")->values == std::vector<double>{72, 71});
  CHECK(s.find("app_gpu_ms")->values == std::vector<double>{4.49, 4.60});
  CHECK(s.find("prediction_ms")->lines == std::vector<int64_t>{3, 5});
}

TEST_CASE("runtime stats: SteamVR frame timing as OpenVR documents Compositor_FrameTiming") {
  // tests/models/capture/data/steamvr_frame_timing.csv (written from openvr.h's
  // fields, see its README): six frames at 90 Hz, frame 3 a vsync late.
  // Application GPU: pre + post submit, 6.5 + 0.3 = 6.8 ms for frame 0 and
  // 13.9 + 0.5 = 14.4 for frame 3; the compositor's 0.9 .. 1.1 ms. Refresh:
  // the shortest step between frames' vsyncs, 1/90 s. One dropped frame over
  // the six frames' span, 5 vsyncs of 1/90 s plus one: 1 / (7/90 s) = 12.857 a second.
  const RuntimeStats s = read_runtime_stats(LATSIM_SOURCE_DIR "/tests/models/capture/data/steamvr_frame_timing.csv");
  CHECK(s.generation == Generation::steamvr);
  CHECK(s.per_frame);
  CHECK(s.rows_read == 6);
  const std::vector<double>& app = s.find("app_gpu_ms")->values;
  REQUIRE(app.size() == 6);
  CHECK(app[0] == Approx(6.8).margin(1e-9));
  CHECK(app[3] == Approx(14.4).margin(1e-9));
  CHECK(s.find("timewarp_gpu_ms")->values[3] == Approx(1.1).margin(1e-9));
  CHECK(s.find("frame_interval_ms")->values[3] == Approx(22.23).margin(1e-9));
  CHECK(mean(*s.find("refresh_hz")) == Approx(90.0).margin(1e-3));
  CHECK(mean(*s.find("stale_per_s")) == Approx(90.0 / 7.0).margin(1e-3));
}

TEST_CASE("runtime stats as workloads: the GPU times of each kind as a cost, in milliseconds") {
  // OVR Metrics: microseconds / 1000 (the first row's 1099 us: 1.099 ms).
  const Capture ovr = read_capture(kDir + "ovr-metrics/OGMP_1.csv", {{"app_gpu_time_microseconds"}, {}});
  CHECK(ovr.generation == Generation::ovr_metrics);
  CHECK(ovr.columns[0].values.size() == 106);
  CHECK(ovr.columns[0].values.front().to_ms() == Approx(1.099).margin(1e-12));
  // VrApi: App=1.73ms, App=11.80ms.
  const Capture vr = read_capture(kDir + "vrapi/vrapi_stats_lines.txt", {{"App", "TW"}, {}});
  CHECK(vr.generation == Generation::vrapi);
  CHECK(same_ms(vr.column("App").values_ms(), {1.73, 11.80}));
  CHECK(same_ms(vr.column("TW").values_ms(), {2.39, 8.91}));
  // SteamVR: the compositor's GPU time, milliseconds as written.
  const Capture sv = read_capture(LATSIM_SOURCE_DIR "/tests/models/capture/data/steamvr_frame_timing.csv",
                                  {{"m_flCompositorRenderGpuMs"}, {}});
  CHECK(sv.generation == Generation::steamvr);
  CHECK(same_ms(sv.columns[0].values_ms(), {0.9, 1.0, 0.9, 1.1, 1.0, 0.9}));
  // 9999 is "not available": skipped, counted.
  const TempFile na("na.csv", "Time Stamp,app_gpu_time_microseconds\n888,1000\n1888,9999\n2888,2000\n");
  const Capture c = read_capture(na.path(), {{"app_gpu_time_microseconds"}, {}});
  CHECK(same_ms(c.columns[0].values_ms(), {1.0, 2.0}));
  CHECK(c.columns[0].skipped_na == 1);
}

TEST_CASE("runtime stats: a broken row names its file and line") {
  const TempFile bad("bad_ovr.csv",
                     "Time Stamp,average_frame_rate,display_refresh_rate,average_prediction_milliseconds,"
                     "screen_tear_count,early_frame_count,stale_frame_count,app_gpu_time_microseconds,"
                     "timewarp_gpu_time_microseconds\n"
                     "888,1,72,0,0,0,41,1099,1221\n"
                     "1888,74,72,46,0,73,0,1099,1162\n"
                     "2888,73,72,4x8,0,73,0,1106,1163\n");
  CHECK_THROWS_WITH(read_runtime_stats(bad.path()),
                    Catch::Contains(bad.path().string() + ":4:") && Catch::Contains("average_prediction_milliseconds") &&
                        Catch::Contains("'4x8'"));
  const TempFile bad_vr("bad_vrapi.txt", "FPS=72/72,Prd=28ms,Tear=0,Early=0,Stale=1\nFPS=seventy,Prd=28ms,Tear=0,Early=0,Stale=1\n");
  CHECK_THROWS_WITH(read_runtime_stats(bad_vr.path()), Catch::Contains(bad_vr.path().string() + ":2:") && Catch::Contains("FPS"));
  // A duration read from a column that is none.
  CHECK_THROWS_WITH(read_capture(kDir + "ovr-metrics/OGMP_1.csv", {{"average_frame_rate"}, {}}),
                    Catch::Contains("not a duration"));
}
