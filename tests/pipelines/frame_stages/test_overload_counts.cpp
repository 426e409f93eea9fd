// A time-warped 144 Hz overload (scenarios/modern/timewarp_overload_144hz.json)
// reports one set of missed, late and re-warped counts that add up, refresh
// by refresh, and `latsim run` prints them all (docs/figures.md, "Counts: one
// name, one meaning").
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "latsim/run/runner.hpp"
#include "latsim/scenario/config.hpp"

using namespace latsim;
using Json = nlohmann::json;

namespace {

Json run_shipped(const std::vector<std::string>& overrides) {
  const auto doc = run::load_scenario(LATSIM_SOURCE_DIR "/scenarios/modern/timewarp_overload_144hz.json", overrides);
  return run::run_scenario(doc, run::RunOptions{});
}

int64_t count(const Json& f, const char* name) { return f.at(name).get<int64_t>(); }

}  // namespace

TEST_CASE("a time-warped 144 Hz overload: missed, late and re-warped refreshes add up", "[overload][frame_stages]") {
  const Json s = run_shipped({"/duration_s=2"});
  const Json& f = s.at("figures");
  // 144 Hz for 2 s: 288 retraces.
  CHECK(count(f, "fields") == 288);
  // Every refresh is one of: before the first frame, skipped by the
  // compositor, a frame's first showing, or a re-warp (the last warp begun
  // may be for a refresh after the run's end: one more).
  const int64_t accounted = count(f, "refreshes_without_image") + count(f, "refreshes_without_warp") +
                            count(f, "frames_shown") + count(f, "frames_rewarped");
  CHECK(accounted >= count(f, "fields"));
  CHECK(accounted <= count(f, "fields") + 1);
  // No half rate here: every re-warp is a missed application frame.
  CHECK(count(f, "frames_synthesised") == 0);
  CHECK(count(f, "frames_rewarped") == count(f, "frames_missed") + count(f, "frames_synthesised"));
  // The GPU is preempted every 0.5 ms slice, and the warp starts late enough
  // ahead of its retrace for it: no warp ends late, none is skipped, and the
  // display shows a new (warped) image at every refresh.
  CHECK(count(f, "warps_late") == 0);
  CHECK(count(f, "refreshes_without_warp") == 0);
  CHECK(count(f, "missed_refreshes") == count(f, "warps_late"));
  // One warp per refresh once the first frame is in: the shown and re-warped ones.
  CHECK(count(f, "warps") == count(f, "frames_shown") + count(f, "frames_rewarped"));
  // By hand: the GPU gives 1 ms to the warp at each of 144 refreshes a
  // second, leaving (1 - 0.144) s a second for 10.417 ms frames: at most
  // 0.856 / 0.010417 = 82.2 frames a second. The CPU's 5.5 ms a frame and
  // two frames in flight keep the GPU fed, so it is nearly reached.
  const double app_hz = f.at("application_frame_rate_hz").get<double>();
  CHECK(app_hz <= 0.856 / 0.010417 + 0.5);  // + a frame in flight at either end of 2 s
  CHECK(app_hz >= 0.856 / 0.010417 - 2.0);
  // Each application frame is shown (the display is the faster), but the one
  // still in flight at the end; the others of the 288 - 3 refreshes with an
  // image re-warp: (144 - 82.2) x 2 = 124 missed, give or take the ends.
  CHECK(count(f, "frames_shown") >= count(f, "frames_rendered") - 1);
  CHECK(count(f, "frames_shown") <= count(f, "frames_rendered"));
  CHECK(count(f, "frames_missed") == Approx((144 - 0.856 / 0.010417) * 2).margin(5));
  // `latsim run` prints them together, in the registry's headline order.
  const std::vector<std::string> headline = s.at("headline").get<std::vector<std::string>>();
  const std::vector<std::string> printed{"rotation_latency_ms", "application_frame_rate_hz", "frames_missed",
                                         "warps_late", "motion_to_photon_ms", "frames_shown", "frames_rewarped",
                                         "frames_synthesised", "missed_refreshes", "refreshes_without_warp"};
  CHECK(headline == printed);
}

TEST_CASE("a warp without preemption ends late and the next skips refreshes: the counts still add up",
          "[overload][frame_stages]") {
  // The same overload on a GPU that runs each 10.417 ms stage to its end: a
  // warp ready during it waits, ends after its retrace (warps_late, and that
  // refresh shows nothing new: missed_refreshes), and the next warp aims
  // past the refreshes it can no longer meet (refreshes_without_warp).
  const Json s = run_shipped({"/duration_s=2", R"(/pipeline/processors=[{"name": "cpu"}, {"name": "gpu"}])"});
  const Json& f = s.at("figures");
  CHECK(count(f, "warps_late") > 0);
  CHECK(count(f, "refreshes_without_warp") > 0);
  CHECK(count(f, "missed_refreshes") == count(f, "warps_late"));
  const int64_t accounted = count(f, "refreshes_without_image") + count(f, "refreshes_without_warp") +
                            count(f, "frames_shown") + count(f, "frames_rewarped");
  CHECK(accounted >= count(f, "fields"));
  CHECK(accounted <= count(f, "fields") + 1);
  CHECK(count(f, "warps") == count(f, "frames_shown") + count(f, "frames_rewarped"));
  CHECK(count(f, "frames_rewarped") == count(f, "frames_missed") + count(f, "frames_synthesised"));
  // By hand: a warp waits for the stage it shares the GPU with, so the GPU
  // makes at most one frame and one warp per 10.417 + 1 ms: at most 87.6 warps a
  // second, each showing a new frame, and at least 144 - 87.6 = 56.4 refreshes
  // a second get no warp.
  CHECK(count(f, "warps") <= static_cast<int64_t>(2 / 0.011417) + 1);
  CHECK(count(f, "refreshes_without_warp") >= static_cast<int64_t>((144 - 1 / 0.011417) * 2) - 2);
}
