// The ARP pipelines run on the real kernel, tracker, display and recorder:
// rotation latency must not depend on the rendering rate, translation latency must.
#include <catch2/catch.hpp>

#include <memory>

#include "latsim/des/simulator.hpp"
#include "latsim/display/display.hpp"
#include "latsim/pipelines/latency_recorder.hpp"
#include "latsim/pipelines/run_files.hpp"
#include "latsim/pipelines/tracker_host.hpp"
#include "latsim/scenario/params.hpp"
#include "latsim/tracker/motion_source.hpp"
#include "latsim/tracker/tracker.hpp"
#include "latsim/tracker/transport.hpp"

using namespace latsim;

namespace {

/// Everything a pipeline run needs, wired as the runner wires it.
struct Harness {
  explicit Harness(nlohmann::json scenario, std::unique_ptr<tracker::MotionSource> m)
      : doc(scenario::ScenarioDocument::from_json(std::move(scenario), LATSIM_SOURCE_DIR)),
        motion(std::move(m)),
        tracker(tracker::TrackerParams{}, *motion, des::RandomStream(1, "tracker", 0)),
        host(sim, tracker, link),
        display(sim, display::RasterTiming(display::RasterParams{}), 1, display::ScanoutFidelity::Line),
        recorder(sim, *motion, host, display.timing(), pipelines::ProbeSet{}, 0.064, false, false) {
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
    const auto pipeline = pipelines::builtin_pipelines().find(type)->bind(section, shared)();
    pipelines::RunContext ctx{sim,     1,        0,       duration, *motion,         tracker_params,
                              link,    host,     display, shared.display, shared.scene ? &*shared.scene : nullptr,
                              recorder, files,   0.064,   false,    nullptr,         nullptr};
    pipeline->start(ctx);
    host.start(duration);
    display.start(duration);
    sim.run_until(duration);
    pipeline->finish(ctx);
    return recorder.figures();
  }

  scenario::ScenarioDocument doc;
  tracker::TrackerParams tracker_params;
  pipelines::RunFiles files;
  des::Simulator sim;
  std::unique_ptr<tracker::MotionSource> motion;
  tracker::DirectLink link;
  tracker::Tracker tracker;
  pipelines::TrackerHost host;
  display::Display display;
  pipelines::LatencyRecorder recorder;
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
  Harness h({{"pipeline", {{"type", "arp"}, {"render_rate_hz", rate_hz}, {"render_time_ms", 4.0}}}}, std::move(motion));
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

TEST_CASE("region priority pipeline reports memories, render load and tears on a walk") {
  nlohmann::json scenario = {{"scene", {{"type", "gallery"}}},
                             {"display", {{"hfov_deg", 90.0}}},
                             {"pipeline", {{"type", "region_priority"}, {"segmentation", true}, {"warping", false}}}};
  Harness h(scenario, yaw_and_walk());
  const nlohmann::json f = h.run(des::Time::s(6));
  REQUIRE(f["memories"].size() == 4);
  CHECK(f["memories"][0]["update_rate_hz"].get<double>() > 50.0);
  CHECK(f["memories"][3]["update_rate_hz"].get<double>() < f["memories"][0]["update_rate_hz"].get<double>());
  CHECK(f["render_load"].get<double>() > 0.0);
  REQUIRE(f["variants"].size() == 3);
  for (const auto& v : f["variants"]) {
    if (v["segmentation"] && v["warping"]) CHECK(v["tear_gap_max_px"].get<double>() < 1e-3);
    if (v["segmentation"] && !v["warping"]) CHECK(v["tear_gap_max_px"].get<double>() > 0.5);
  }
  CHECK(h.recorder.distribution("tear_gap_px") != nullptr);
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
