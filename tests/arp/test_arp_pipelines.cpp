// The ARP pipelines run on the real kernel, tracker, display and recorder:
// rotation latency must not depend on the rendering rate, translation latency must.
#include <catch2/catch.hpp>

#include <fstream>
#include <memory>

#include "latsim/des/run_clocks.hpp"
#include "latsim/des/simulator.hpp"
#include "latsim/display/display.hpp"
#include "latsim/params/shared.hpp"
#include "latsim/pipelines/pipeline.hpp"
#include "latsim/results/frame_recorder.hpp"
#include "latsim/results/image_book.hpp"
#include "latsim/results/latency_recorder.hpp"
#include "latsim/results/run_files.hpp"
#include "latsim/run/builtin_pipelines.hpp"
#include "latsim/run/tracker_host.hpp"
#include "latsim/scenario/params.hpp"
#include "latsim/tracker/motion_source.hpp"
#include "latsim/tracker/tracker.hpp"
#include "latsim/tracker/transport.hpp"

using namespace latsim;

namespace {

/// Everything a pipeline run needs, wired as the runner wires it.
struct Harness {
  explicit Harness(nlohmann::json scenario, std::unique_ptr<tracker::MotionSource> m,
                   tracker::TrackerParams tracking = {})
      : doc(scenario::ScenarioDocument::from_json(std::move(scenario), LATSIM_SOURCE_DIR)),
        motion(std::move(m)),
        tracker(tracking, *motion, des::RandomStream(1, "tracker", 0)),
        host(sim, tracker, link),
        display(sim, display::RasterTiming(display::RasterParams{}), 1, display::ScanoutFidelity::Line),
        recorder(sim, *motion, host, images, display.timing(), results::ProbeSet{}, 0.064, false, false) {
    display.add_listener(&recorder);
  }

  /// Builds the scenario's /pipeline through its registered declaration and runs it.
  nlohmann::json run(des::Time duration) {
    params::SharedParams shared;
    if (doc.json().contains("scene")) {
      shared.scene.emplace();
      scenario::Section scene(doc.root().child("scene"));
      params::bind(scene, *shared.scene);
    }
    if (doc.json().contains("display")) shared.display.hfov_deg = doc.json()["display"].value("hfov_deg", 90.0);
    const std::string type = doc.json()["pipeline"]["type"];
    scenario::Section section(doc.root().child("pipeline"));
    const auto pipeline = run::builtin_pipelines().find(type)->bind(section, shared)();
    pipelines::RunContext ctx{sim,     1,        0,       duration, *motion,         tracker_params,
                              link,    host,     display, shared.display, shared.scene ? &*shared.scene : nullptr,
                              images,  recorder, app_frames, files,   clocks, 0.064,   false,    nullptr,         nullptr};
    pipeline->start(ctx);
    host.start(duration);
    display.start(duration);
    sim.run_until(duration);
    pipeline->finish(ctx);
    app_frames.finish(recorder, duration);
    return recorder.figures();
  }

  scenario::ScenarioDocument doc;
  tracker::TrackerParams tracker_params;
  results::RunFiles files;
  des::RunClocks clocks{1, 0};
  des::Simulator sim;
  std::unique_ptr<tracker::MotionSource> motion;
  tracker::DirectLink link;
  tracker::Tracker tracker;
  run::TrackerHost host;
  display::Display display;
  results::ImageBook images;
  results::LatencyRecorder recorder;
  results::FrameRecorder app_frames;
};

std::unique_ptr<tracker::MotionSource> yaw_and_walk() {
  tracker::WalkParams w;
  w.points_m = {{-6.0, 1.6, 0.5}, {6.0, 1.6, 0.5}};
  w.speed_m_s = 1.0;
  return std::make_unique<tracker::PolylineWalk>(w);
}

std::unique_ptr<tracker::MotionSource> constant_yaw() {
  tracker::Pose start;
  start.position_m = {0.0, 1.6, 0.0};
  return std::make_unique<tracker::ConstantAngularVelocity>(start, glm::dvec3(0.0, 1.0, 0.0), 100.0);
}

struct Latencies {
  des::Distribution::Summary rotation;
  des::Distribution::Summary translation;
};

Latencies run_arp(double rate_hz, std::unique_ptr<tracker::MotionSource> motion) {
  // Both loops start at t = 0, so the first display memory is shown at the same refresh.
  Harness h({{"pipeline", {{"type", "arp"}, {"render_rate_hz", rate_hz}, {"render_time_ms", 4.0}, {"loop_phase_ms", 0.0}}}},
            std::move(motion));
  h.run(des::Time::s(2));
  return {h.recorder.distribution("rotation_latency_ms")->summary(),
          h.recorder.distribution("translation_latency_ms")->summary()};
}

}  // namespace

TEST_CASE("ARP rotation latency is identical at 10 Hz and 60 Hz rendering, translation latency is not") {
  const Latencies slow = run_arp(10.0, constant_yaw());
  const Latencies fast = run_arp(60.0, constant_yaw());
  CHECK(slow.rotation.count == fast.rotation.count);
  CHECK(slow.rotation.mean == fast.rotation.mean);
  CHECK(slow.rotation.max == fast.rotation.max);
  CHECK(slow.rotation.p99 == fast.rotation.p99);
  CHECK(slow.rotation.max < 40.0);
  CHECK(slow.translation.mean > fast.translation.mean + 20.0);
}

TEST_CASE("a plain region priority run is one configuration; compare adds the variants asked for") {
  nlohmann::json scenario = {{"scene", {{"type", "gallery"}}},
                             {"display", {{"hfov_deg", 90.0}}},
                             {"pipeline", {{"type", "region_priority"}, {"segmentation", true}, {"warping", false}}}};
  {
    Harness h(scenario, yaw_and_walk());
    const nlohmann::json f = h.run(des::Time::s(6));
    REQUIRE(f["memories"].size() == 4);
    CHECK(f["memories"][0]["update_rate_hz"].get<double>() > 50.0);
    CHECK(f["memories"][3]["update_rate_hz"].get<double>() < f["memories"][0]["update_rate_hz"].get<double>());
    CHECK(f["render_load"].get<double>() > 0.0);
    CHECK(!f.contains("variants"));
    CHECK(!f.contains("stretch_px"));
    CHECK(f["tear_gap_px"]["count"].get<int64_t>() > 0);
    for (const auto& k : h.sim.kind_stats()) CHECK((k.name != "arp.variant_render" || k.events == 0));
  }
  scenario["pipeline"]["compare"] = {"unsegmented", "warped"};
  Harness h(scenario, yaw_and_walk());
  const nlohmann::json f = h.run(des::Time::s(6));
  REQUIRE(f["variants"].size() == 2);
  const nlohmann::json& whole = f["variants"][0];
  const nlohmann::json& warped = f["variants"][1];
  CHECK(whole["segmentation"] == false);
  CHECK(warped["warping"] == true);
  CHECK(whole["memories"][0]["segments"].get<double>() > 3 * f["memories"][0]["segments"].get<double>());
  CHECK(warped["tear_gap_px"]["max"].get<double>() < 1e-3);
  CHECK(warped["tear_gap_px"]["count"].get<int64_t>() > 100);
  CHECK(warped["stretch_px"]["max"].get<double>() > 0.5);
  CHECK(f["tear_gap_px"]["max"].get<double>() > 0.5);
}

namespace {

/// The shipped gallery scenario's /scene, /display and /pipeline, walked along its path.
nlohmann::json gallery(const std::string& file) {
  std::ifstream in(std::string(LATSIM_SOURCE_DIR) + "/scenarios/arp/" + file);
  nlohmann::json j = nlohmann::json::parse(in);
  if (j.contains("include")) {
    nlohmann::json base = gallery(j["include"].get<std::string>());
    base["pipeline"].update(j["pipeline"]);
    return base;
  }
  j["pipeline"]["frame_times_s"] = nlohmann::json::array();
  // The hand derivations below count ticks from t = 0: the update loop starts in
  // phase with the tracker and the display rather than at a drawn phase.
  j["pipeline"]["loop_phase_ms"] = 0.0;
  return {{"scene", j["scene"]}, {"display", j["display"]}, {"pipeline", j["pipeline"]}};
}

std::unique_ptr<tracker::MotionSource> gallery_walk() {
  tracker::WalkParams w;
  w.points_m = {{-8.5, 1.6, -8.5}, {8.5, 1.6, -7.5}, {0.5, 1.6, 8.5}};
  w.speed_m_s = 1.0;
  return std::make_unique<tracker::PolylineWalk>(w);
}

tracker::TrackerParams delayed_2ms() {
  tracker::TrackerParams t;
  t.internal_delay = des::Time::ms(2);
  return t;
}

}  // namespace

TEST_CASE("gallery: segmentation lowers memory 0's segments per update and the render load") {
  nlohmann::json scenario = gallery("gallery.json");
  scenario["pipeline"]["compare"] = {"unsegmented"};
  Harness h(scenario, gallery_walk(), delayed_2ms());
  const nlohmann::json f = h.run(des::Time::s(34));
  const nlohmann::json& whole = f["variants"][0];
  // The published experiment: far fewer object segments at the fastest rate.
  CHECK(f["memories"][0]["segments"].get<double>() * 3 < whole["memories"][0]["segments"].get<double>());
  CHECK(f["render_load"].get<double>() < whole["render_load"].get<double>());
  CHECK(f["renderer_utilisation"].get<double>() < whole["renderer_utilisation"].get<double>());
  for (int m = 0; m + 1 < 4; ++m) {
    CHECK(f["memories"][m]["update_rate_hz"].get<double>() > f["memories"][m + 1]["update_rate_hz"].get<double>());
  }
  CHECK(f["renders_skipped"].get<int64_t>() == 0);
  // Memory 0 is redrawn at every tick k (t = k/60 s) from sample k-1 (2 ms tracker
  // delay), shown from the retrace at (k+1)/60 s; its first active line is lit 22
  // blank lines of 502 later: 2/60 s + 22/502 x 1/60 s.
  const double memory0_ms = 1000.0 * (2.0 / 60.0 + 22.0 / 502.0 / 60.0);
  const auto& t0 = f["translation_latency_memory0_ms"];
  CHECK(t0["min"].get<double>() == Approx(memory0_ms).epsilon(1e-9));
  CHECK(t0["max"].get<double>() == Approx(memory0_ms).epsilon(1e-9));
  // Slower memories show older positions.
  CHECK(f["translation_latency_memory3_ms"]["mean"].get<double>() > memory0_ms + 10.0);
}

TEST_CASE("gallery with doubled render costs queues and updates less often instead of overlapping") {
  Harness plain(gallery("gallery.json"), gallery_walk(), delayed_2ms());
  const nlohmann::json f = plain.run(des::Time::s(34));
  Harness over(gallery("gallery_overload.json"), gallery_walk(), delayed_2ms());
  const nlohmann::json g = over.run(des::Time::s(34));
  CHECK(g["render_queue_ms"]["mean"].get<double>() > 2 * f["render_queue_ms"]["mean"].get<double>());
  CHECK(g["renders_skipped"].get<int64_t>() > 0);
  CHECK(g["renderer_utilisation"].get<double>() > f["renderer_utilisation"].get<double>());
  for (int m = 2; m < 4; ++m) {
    CHECK(g["memories"][m]["update_rate_hz"].get<double>() < f["memories"][m]["update_rate_hz"].get<double>());
  }
  CHECK(!over.recorder.warnings().empty());
}

TEST_CASE("priority pipeline with a still user renders once") {
  nlohmann::json scenario = {{"scene", {{"type", "room"}}}, {"pipeline", {{"type", "priority"}}}};
  tracker::Pose still;
  still.position_m = {0.0, 1.6, 0.0};
  Harness h(scenario, std::make_unique<tracker::StillMotion>(still));
  const nlohmann::json f = h.run(des::Time::s(3));
  int64_t renders = 0;
  for (const auto& m : f["memories"]) renders += m["renders"].get<int64_t>();
  CHECK(renders == static_cast<int64_t>(f["memories"].size()));  // the first drawing of each memory, then nothing
}
