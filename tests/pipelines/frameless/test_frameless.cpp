// Frameless rendering and double buffering on one pixel budget.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <vector>

#include "frames_helpers.hpp"
#include "frameless/frameless_order.hpp"
#include "latsim/units/units.hpp"

namespace units = latsim::units;

namespace des = latsim::des;
namespace pipelines = latsim::pipelines;
namespace scenario = latsim::scenario;
using namespace latsim::frames_test;

namespace {

constexpr double kCycleMs = 200.0;        // 5 full images per second of budget
constexpr double kRefreshMs = 1000.0 / 60.0;
constexpr double kTrackerPeriodMs = 1.0;  // the small scenario's 1000 Hz tracker

nlohmann::json turning(const char* strategy) {
  nlohmann::json s = small_scenario();
  s["duration_s"] = 2;
  s["motion"] = {{"type", "constant"}, {"axis", {0, 1, 0}}, {"rate_deg_s", 30}};
  s["pipeline"] = frameless(strategy);
  return s;
}

// A head that looks ahead until 0.5 s, then faces 90 degrees to the left
// within a millisecond (a cut), and stays there.
std::filesystem::path write_cut_trace(const std::filesystem::path& dir) {
  std::filesystem::create_directories(dir);
  const auto file = dir / "cut.csv";
  std::ofstream out(file);
  const double c = std::cos(units::kPi / 4.0);
  out << "t_s,px,py,pz,qw,qx,qy,qz\n"
      << "0,0,0,0,1,0,0,0\n0.499,0,0,0,1,0,0,0\n"
      << "0.5,0,0,0," << c << ",0," << c << ",0\n3,0,0,0," << c << ",0," << c << ",0\n";
  return file;
}

double capture_error(const nlohmann::json& summary, size_t i) {
  return fig(summary, "frames").at(i).at("image_error").get<double>();
}

}  // namespace

TEST_CASE("the permutation table updates every pixel exactly once per cycle", "[frameless]") {
  for (int32_t n : {1, 7, 64 * 48}) {
    const pipelines::FramelessOrder order(n, des::RandomStream(5, "frameless"));
    for (int64_t cycle = 0; cycle < 3; ++cycle) {
      std::vector<int> seen(static_cast<size_t>(n), 0);
      for (int64_t k = cycle * n; k < (cycle + 1) * n; ++k) ++seen[static_cast<size_t>(order.pixel_of(k))];
      INFO("n = " << n << ", cycle " << cycle);
      CHECK(std::all_of(seen.begin(), seen.end(), [](int v) { return v == 1; }));
    }
  }
  // Randomised, yet reproducible from the stream.
  const pipelines::FramelessOrder a(1000, des::RandomStream(5, "frameless"));
  const pipelines::FramelessOrder b(1000, des::RandomStream(5, "frameless"));
  const pipelines::FramelessOrder c(1000, des::RandomStream(6, "frameless"));
  int same_ab = 0, same_ac = 0, identity = 0;
  for (int k = 0; k < 1000; ++k) {
    same_ab += a.pixel_of(k) == b.pixel_of(k);
    same_ac += a.pixel_of(k) == c.pixel_of(k);
    identity += a.pixel_of(k) == k;
  }
  CHECK(same_ab == 1000);
  CHECK(same_ac < 50);
  CHECK(identity < 50);
}

TEST_CASE("with a still head frameless converges to the truth after one cycle", "[frameless]") {
  nlohmann::json s = small_scenario();
  s["pipeline"] = frameless("frameless");
  capture(s, {{"at_s", {0.1, 0.25}}, {"threads", 2}});
  const auto summary = run(s);
  // Half a cycle in, some pixels have not been computed yet (background).
  CHECK(capture_error(summary, 0) > 0.0);
  // One cycle computes as many pixels as the screen has; all are lit, so each
  // was computed exactly once, from the true pose.
  CHECK(capture_error(summary, 1) == 0.0);
}

TEST_CASE("frameless pixel ages lie within one cycle plus a refresh", "[frameless]") {
  const auto summary = run(turning("frameless"));
  const auto& age = fig(summary, "pixel_age_ms");
  CHECK(age["count"].get<int64_t>() > 100000);
  CHECK(age["min"].get<double>() >= 0.0);
  CHECK(age["max"].get<double>() <= kCycleMs + 2 * kRefreshMs + kTrackerPeriodMs);
  // Ages spread evenly over the cycle: the mean is near half of it.
  CHECK(age["mean"].get<double>() == Approx(kCycleMs / 2 + kRefreshMs).margin(15.0));
  CHECK(fig(summary, "motion_to_photon_ms")["count"] == age["count"]);
  CHECK(fig(summary, "registration_error_arcmin")["mean"].get<double>() > 0.0);
  // About a twelfth of the screen changes at each refresh, never a pixel twice.
  const auto& updated = fig(summary, "updated_fraction");
  const double per_refresh = std::ceil(64.0 * 48.0 * 5.0 / 60.0) / (64.0 * 48.0);
  CHECK(updated["max"].get<double>() <= per_refresh);
  CHECK(updated["p50"].get<double>() == Approx(1.0 / 12.0).margin(0.002));
  CHECK(fig(summary, "frameless")["fallbacks"] == 0);
}

TEST_CASE("double-buffered pixel ages lie between one and two image times plus refreshes", "[frameless]") {
  const auto summary = run(turning("double_buffer"));
  const auto& age = fig(summary, "pixel_age_ms");
  CHECK(age["count"].get<int64_t>() > 100000);
  CHECK(age["min"].get<double>() >= kCycleMs);
  CHECK(age["max"].get<double>() <= 2 * kCycleMs + 2 * kRefreshMs + kTrackerPeriodMs);
  CHECK(fig(summary, "frameless")["images_rendered"].get<int64_t>() >= 9);
  // A whole new image or nothing at each refresh, about one refresh in twelve.
  const auto& updated = fig(summary, "updated_fraction");
  CHECK(updated["max"].get<double>() == 1.0);
  CHECK(updated["p50"].get<double>() == 0.0);
  CHECK(updated["mean"].get<double>() == Approx(1.0 / 12.0).margin(0.02));
}

TEST_CASE("frameless shows younger pixels and a smaller error than double buffering", "[frameless]") {
  nlohmann::json fl = turning("frameless"), db = turning("double_buffer");
  capture(fl, {{"at_s", {1.0, 1.5}}, {"threads", 2}});
  capture(db, fl["frames"]);
  const auto a = run(fl), b = run(db);
  CHECK(fig(a, "pixel_age_ms")["mean"].get<double>() < fig(b, "pixel_age_ms")["mean"].get<double>());
  CHECK(fig(a, "frames_mean_image_error").get<double>() < fig(b, "frames_mean_image_error").get<double>());
}

TEST_CASE("a cut makes frameless fall back as configured", "[frameless]") {
  const auto dir = fresh_dir("cut");
  nlohmann::json s = small_scenario();
  s["duration_s"] = 0.8;
  s["tracker"] = {{"rate_hz", 60}};
  s["motion"] = {{"type", "trace"}, {"file", write_cut_trace(dir).string()}, {"loop", false}};
  s["pipeline"] = frameless("frameless");
  capture(s, {{"at_s", {0.55, 0.75}}, {"threads", 2}});

  s["pipeline"]["fallback"] = {{"kind", "none"}};
  const auto none = run(s);
  CHECK(fig(none, "frameless")["fallbacks"] == 0);

  s["pipeline"]["fallback"] = {{"kind", "low_resolution"}, {"trigger_deg", 30}, {"block_px", 4}};
  const auto low = run(s);
  CHECK(fig(low, "frameless")["fallbacks"] == 1);
  // 50 ms after the cut the coarse pass has covered the screen.
  CHECK(capture_error(low, 0) < 0.5 * capture_error(none, 0));
  // Block updates change many pixels per unit of budget.
  CHECK(fig(low, "updated_fraction")["max"].get<double>() > 0.2);

  s["pipeline"]["fallback"] = {{"kind", "double_buffer"}, {"trigger_deg", 30}};
  const auto held = run(s);
  CHECK(fig(held, "frameless")["fallbacks"] == 1);
  // The old picture stays up while one whole image renders from the new pose,
  // then it replaces every pixel at once.
  CHECK(capture_error(held, 0) > capture_error(low, 0));
  CHECK(capture_error(held, 1) == 0.0);
  CHECK(fig(held, "updated_fraction")["max"].get<double>() == 1.0);
  std::filesystem::remove_all(dir);
}

TEST_CASE("the frameless scenarios run and tell the two strategies apart", "[frameless][scenario]") {
  for (const char* name : {"side_by_side", "double_buffered"}) {
    auto doc = scenario::ScenarioDocument::load(LATSIM_SOURCE_DIR "/scenarios/frameless/" + std::string(name) + ".json",
                                                {"/duration_s=1", "/frames/enabled=false"});
    const auto summary = latsim::run::run_scenario(doc, latsim::run::RunOptions{});
    const double mean = fig(summary, "pixel_age_ms")["mean"].get<double>();
    INFO(name << ": mean pixel age " << mean);
    if (std::string(name) == "side_by_side") CHECK((mean > 100.0 && mean < 140.0));
    else CHECK((mean > 280.0 && mean < 340.0));
  }
}
