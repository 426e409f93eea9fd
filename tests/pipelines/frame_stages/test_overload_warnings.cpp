// Overload behind a compositor is said, in the application's own terms: the
// display shows a (re-warped) image at every refresh, so missed_refreshes
// and frame_rate_hz stay healthy while the application falls behind.
#include <catch2/catch.hpp>

#include <string>

#include <nlohmann/json.hpp>

#include "latsim/run/runner.hpp"
#include "latsim/scenario/config.hpp"

using namespace latsim;
using Json = nlohmann::json;

namespace {

// 144 Hz, one 0.5 ms CPU stage started at each retrace, a GPU stage of
// `gpu_ms`, and a 1 ms rotation warp per refresh on the same GPU.
Json warped_144hz(double gpu_ms, double slice_ms) {
  Json gpu = {{"name", "gpu"}};
  if (slice_ms > 0) gpu["preemption_slice_ms"] = slice_ms;
  return {
      {"duration_s", 2},
      {"seed", 1},
      {"motion", {{"type", "constant"}, {"rate_deg_s", 60}}},
      {"tracker", {{"rate_hz", 1000}, {"internal_delay_ms", 0}}},
      {"transport", {{"type", "direct"}}},
      {"display", {{"refresh_hz", 144}, {"width_px", 640}, {"height_px", 480}, {"vblank_lines", 0},
                   {"hblank_px", 0}, {"scanout", "field"}}},
      {"pipeline",
       {{"type", "frame_stages"},
        {"max_frames_in_flight", 2},
        {"processors", Json::array({{{"name", "cpu"}}, gpu})},
        {"stages", Json::array({{{"name", "C"}, {"on", "cpu"}, {"start", "retrace"}, {"samples_pose", true},
                                 {"cost", {{"fixed_ms", 0.5}}}},
                                {{"name", "G"}, {"on", "gpu"}, {"cost", {{"fixed_ms", gpu_ms}}}}})},
        {"timewarp",
         {{"mode", "rotation"},
          {"asynchronous", true},
          {"stages", Json::array({{{"name", "W"}, {"on", "gpu"}, {"start", "late"}, {"samples_pose", true},
                                   {"cost", {{"fixed_ms", 1}}}}})}}}}}};
}

Json run_warped(const Json& scenario) {
  const auto doc = scenario::ScenarioDocument::from_json(scenario, LATSIM_SOURCE_DIR "/scenarios/modern");
  return run::run_scenario(doc, run::RunOptions{});
}

bool has_warning(const Json& summary, const std::string& part) {
  for (const Json& w : summary["warnings"])
    if (w.get<std::string>().find(part) != std::string::npos) return true;
  return false;
}

}  // namespace

TEST_CASE("an application slower than the display behind a compositor is warned of", "[overload][frame_stages]") {
  // The GPU gives 1 ms to the warp at each of 144 refreshes a second, so at
  // most 1 - 0.144 = 0.856 s a second is left for 9 ms frames: at most
  // 0.856 / 0.009 = 95.1 frames a second, and at least 144 - 95.1 = 48.9
  // refreshes a second re-warp an image already shown (frames_missed).
  const Json s = run_warped(warped_144hz(9.0, 0.5));
  const Json& f = s["figures"];
  const double app_hz = f["application_frame_rate_hz"].get<double>();
  CHECK(app_hz <= (1 - 0.144) / 0.009 + 0.5);  // + a frame in flight at either end of 2 s
  CHECK(app_hz > 80);
  CHECK(f["frames_missed"].get<int64_t>() >= static_cast<int64_t>((144 - (1 - 0.144) / 0.009) * 2) - 2);
  // What the display counts looks healthy: a warped image at every refresh.
  CHECK(f["missed_refreshes"].get<int64_t>() == 0);
  CHECK(has_warning(s, "frames_missed"));
  CHECK(has_warning(s, "application_frame_rate_hz"));
  CHECK_FALSE(has_warning(s, "warps_late"));
}

TEST_CASE("warps that wait for an unpreemptible GPU stage are warned of, naming the processor", "[overload][frame_stages]") {
  // Without a preemption slice a warp that becomes ready while the 9 ms
  // stage runs waits for it: with the stage covering 9 of every ~10.5 ms of
  // GPU time, most warps due within a refresh (6.94 ms) end after it.
  const Json s = run_warped(warped_144hz(9.0, 0.0));
  CHECK(s["figures"]["warps_late"].get<int64_t>() > 0);
  CHECK(has_warning(s, "warps_late"));
  CHECK(has_warning(s, "processor \"gpu\" runs the warp without preemption_slice_ms"));
}

TEST_CASE("an application that keeps up behind a compositor gets no overload warning", "[overload][frame_stages]") {
  // 0.5 + 3 ms of work and a 1 ms warp fit in a 6.94 ms refresh.
  const Json s = run_warped(warped_144hz(3.0, 0.5));
  CHECK(s["figures"]["frames_missed"].get<int64_t>() == 0);
  CHECK(s["figures"]["warps_late"].get<int64_t>() == 0);
  CHECK(s["warnings"].empty());
}
