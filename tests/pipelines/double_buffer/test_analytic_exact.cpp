// The analytic figure of double buffering, computed by blocks of tracker
// phases, equals to the last bit the reference that enumerates every phase
// point and frame (analytic_reference.cpp, the first implementation): on every
// shipped double-buffered scenario, and on random configurations that reach
// the bounds of frames and fields.
#include <catch2/catch.hpp>

#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "analytic_reference.hpp"
#include "double_buffer/analytic.hpp"
#include "latsim/run/builder.hpp"
#include "latsim/run/runner.hpp"
#include "run_helpers.hpp"

namespace {

namespace fs = std::filesystem;
using latsim::des::RationalSeconds;
using latsim::des::Time;
using latsim::pipelines::AnalyticInputs;
using latsim::pipelines::AnalyticLatency;
using latsim::pipelines::analytic_double_buffer;
using latsim::pipelines::testing::reference_analytic_double_buffer;

// Every field compared exactly: the mean is the same integer sum over the same count.
void check_same(const std::optional<AnalyticLatency>& got, const std::optional<AnalyticLatency>& want) {
  REQUIRE(got.has_value() == want.has_value());
  if (!want) return;
  CHECK(got->link == want->link);
  CHECK(got->method == want->method);
  CHECK(got->hyperperiod_s == want->hyperperiod_s);
  CHECK(got->frames == want->frames);
  CHECK(got->phase_grid == want->phase_grid);
  CHECK(got->complete == want->complete);
  CHECK(got->min_ms == want->min_ms);
  CHECK(got->mean_ms == want->mean_ms);
  CHECK(got->max_ms == want->max_ms);
}

}  // namespace

TEST_CASE("the analytic figure of every shipped double-buffered scenario equals the reference enumeration",
          "[double_buffer][analytic]") {
  int compared = 0;
  for (const fs::path& file : latsim::testing::shipped_scenarios()) {
    const auto doc = latsim::run::load_scenario(file, {});
    if (doc.resolved()["pipeline"].value("type", "") != "double_buffer") continue;
    latsim::run::Run run;
    latsim::run::build(run, doc, latsim::run::RunOptions{});
    // The pipeline's own figures of its phases (drawn as a run draws them), without simulating.
    run.pipeline->finish(*run.ctx);
    const auto figures = run.recording->book().figures();
    if (!figures.contains("analytic")) continue;
    INFO(file.string());
    const Time render = Time::from_ms(figures["nominal_frame_time_ms"].get<double>());
    const AnalyticInputs in = latsim::pipelines::analytic_inputs(*run.ctx, render);
    const auto want = reference_analytic_double_buffer(in);
    REQUIRE(want);
    check_same(analytic_double_buffer(in), want);
    const auto& a = figures["analytic"];
    CHECK(a["frames"].get<int64_t>() == want->frames);
    CHECK(a["motion_to_photon_ms"]["mean"].get<double>() == want->mean_ms);
    CHECK(a["motion_to_photon_ms"]["min"].get<double>() == want->min_ms);
    CHECK(a["motion_to_photon_ms"]["max"].get<double>() == want->max_ms);
    ++compared;
  }
  // hmd_60hz_direct, the frameless comparison, NTSC stereo, the measured V1, then-and-now's base...
  CHECK(compared >= 4);
}

namespace {

// A random configuration of the analytic calculation's inputs; the transport
// lives in `links` so that the inputs may point at it.
AnalyticInputs random_inputs(std::mt19937_64& rng, std::vector<std::unique_ptr<latsim::tracker::Transport>>& links) {
  auto pick = [&rng](auto const& options) { return options[std::uniform_int_distribution<size_t>(0, options.size() - 1)(rng)]; };
  auto uniform_ps = [&rng](int64_t lo, int64_t hi) { return Time::ps(std::uniform_int_distribution<int64_t>(lo, hi)(rng)); };
  auto coin = [&rng](double p) { return std::bernoulli_distribution(p)(rng); };
  const std::vector<RationalSeconds> fields{{1, 60}, {1001, 60000}, {1, 72}, {1, 90}, {1, 50}, {1, 144}, {7, 400}};
  const std::vector<RationalSeconds> trackers{{1, 60}, {1001, 60000}, {1, 120}, {1, 240}, {1, 1000}, {1, 30}, {3, 170}};
  AnalyticInputs in;
  in.raster.field_period = pick(fields);
  in.raster.interlaced = coin(0.3);
  in.raster.height_px = std::uniform_int_distribution<int>(2, 40)(rng) * 2;
  in.raster.width_px = std::uniform_int_distribution<int>(1, 20)(rng);
  in.raster.vblank_lines = std::uniform_int_distribution<int>(0, 6)(rng);
  in.raster.hblank_px = std::uniform_int_distribution<int>(0, 8)(rng);
  using Mode = latsim::display::PersistenceParams::Mode;
  in.persistence.mode = pick(std::vector<Mode>{Mode::impulse, Mode::full, Mode::rolling, Mode::global});
  in.persistence.response = uniform_ps(0, 200'000'000);
  in.persistence.lit = uniform_ps(1, 2'000'000'000);
  in.tracker_period = pick(trackers);
  in.tracker_delay = uniform_ps(0, 6'000'000'000);
  in.render_time = coin(0.2) ? Time::zero() : uniform_ps(1, 45'000'000'000);
  in.display_phase = uniform_ps(0, 20'000'000'000);
  in.tracker_phase = uniform_ps(0, 40'000'000'000);
  in.poll_phase = uniform_ps(0, 40'000'000'000);
  in.integrate_tracker = coin(0.5);
  in.integrate_poll = coin(0.5);
  in.max_fields = coin(0.3) ? std::uniform_int_distribution<int64_t>(0, 3000)(rng) : 4'000'000;
  const int kind = std::uniform_int_distribution<int>(0, 2)(rng);
  if (kind == 0) {
    links.push_back(std::make_unique<latsim::tracker::DirectLink>());
  } else {
    latsim::tracker::SerialLinkParams sp;
    sp.record_bytes = 8;
    sp.baud = 115200.0;  // 0.69 ms a record: within every tracker period above
    sp.host_mode = kind == 1 ? latsim::tracker::SerialLinkParams::Poll : latsim::tracker::SerialLinkParams::Interrupt;
    sp.poll_interval = uniform_ps(500'000'000, 31'000'000'000);
    links.push_back(std::make_unique<latsim::tracker::SerialLink>(sp));
  }
  in.transport = links.back().get();
  return in;
}

}  // namespace

TEST_CASE("the analytic figure equals the reference on random configurations, cut off by fields or not",
          "[double_buffer][analytic]") {
  std::mt19937_64 rng(20240611);
  std::vector<std::unique_ptr<latsim::tracker::Transport>> links;
  int truncated = 0, answered = 0;
  for (int n = 0; n < 400; ++n) {
    const AnalyticInputs in = random_inputs(rng, links);
    INFO("case " << n);
    const auto want = reference_analytic_double_buffer(in);
    check_same(analytic_double_buffer(in), want);
    answered += want ? 1 : 0;
    truncated += want && !want->complete ? 1 : 0;
  }
  // Both ends are exercised: answers, and answers cut off by the budget.
  CHECK(answered >= 200);
  CHECK(truncated >= 20);
}

TEST_CASE("the analytic figure equals the reference where the frames run out", "[double_buffer][analytic]") {
  std::vector<std::unique_ptr<latsim::tracker::Transport>> links;
  links.push_back(std::make_unique<latsim::tracker::DirectLink>());
  AnalyticInputs in;
  in.raster.height_px = 4;
  in.raster.vblank_lines = 0;
  in.raster.hblank_px = 0;
  in.transport = links.back().get();
  in.tracker_delay = Time::ms(1);
  in.max_fields = 40'000'000;
  SECTION("fixed phases over a cycle of more frames than the bound") {
    // 59.94 Hz against a tracker period of 2000003/120000000 s (16.667 ms):
    // lcm(1001/60000, 2000003/120000000) = 2000003 fields, one frame each.
    in.raster.field_period = {1001, 60000};
    in.tracker_period = {2'000'003, 120'000'000};
    in.tracker_phase = Time::us(300);
    const auto want = reference_analytic_double_buffer(in);
    REQUIRE(want);
    CHECK_FALSE(want->complete);
    check_same(analytic_double_buffer(in), want);
  }
  SECTION("64 tracker phases against a fixed poll timer, past the bound on all phase points") {
    latsim::tracker::SerialLinkParams sp;
    sp.record_bytes = 8;
    sp.baud = 115200.0;
    // 59.94 Hz against a 16.673 ms poll: lcm(1001/60000, 16673/1000000) s = 50019 fields a phase point.
    sp.poll_interval = Time::us(16'673);
    links.push_back(std::make_unique<latsim::tracker::SerialLink>(sp));
    in.transport = links.back().get();
    in.raster.field_period = {1001, 60000};
    in.tracker_period = {1, 60};
    in.integrate_tracker = true;
    in.poll_phase = Time::us(100);
    const auto want = reference_analytic_double_buffer(in);
    REQUIRE(want);
    CHECK(want->frames == 2'000'000);
    check_same(analytic_double_buffer(in), want);
  }
}
