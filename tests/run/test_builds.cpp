// One run lifecycle: a scenario is parsed, bound and built once per run.
// Validation, the event estimate and the run itself use that one build,
// wherever a run starts: latsim run and the Python module (PreparedRun),
// latsim validate, a sweep's checks and its resolved defaults.
#include <catch2/catch.hpp>

#include <stdexcept>

#include "latsim/run/builder.hpp"
#include "latsim/run/prepared_run.hpp"
#include "latsim/tracker/transport.hpp"
#include "latsim/run/runner.hpp"
#include "run_helpers.hpp"

using namespace latsim;

namespace {

scenario::ScenarioDocument doc_of(const nlohmann::json& s) {
  return scenario::ScenarioDocument::from_json(s, LATSIM_SOURCE_DIR "/scenarios");
}

// Builds made while `f` runs.
template <class F>
uint64_t builds_during(F&& f) {
  const uint64_t before = run::builds_made();
  f();
  return run::builds_made() - before;
}

}  // namespace

TEST_CASE("a prepared run validates, estimates and runs from one build", "[run][builds]") {
  const auto doc = doc_of(testing::base_scenario());
  CHECK(builds_during([&] {
          run::PreparedRun prepared(doc, run::RunOptions{});
          CHECK(prepared.warnings().empty());
          // 2 s of a 60 Hz tracker, 60 Hz retraces and one render per refresh.
          CHECK(prepared.estimate().events == Approx(3 * 120.0));
          const nlohmann::json summary = prepared.run();
          CHECK(summary.at("events").get<int64_t>() > 0);
          CHECK_THROWS_AS(prepared.run(), std::logic_error);
        }) == 1);
}

TEST_CASE("every way into a run builds it once", "[run][builds]") {
  const auto doc = doc_of(testing::base_scenario());
  CHECK(builds_during([&] { (void)run::run_scenario(doc, run::RunOptions{}); }) == 1);
  CHECK(builds_during([&] { (void)run::validate_scenario(doc); }) == 1);
  CHECK(builds_during([&] { (void)run::estimate_scenario_events(doc); }) == 1);
  CHECK(builds_during([&] { (void)run::resolve_defaults(testing::base_scenario(), LATSIM_SOURCE_DIR "/scenarios"); }) ==
        1);
}

TEST_CASE("bad input is refused by the one build, before anything runs", "[run][builds]") {
  nlohmann::json s = testing::base_scenario();
  s["display"]["refresh_hz"] = -60;
  const auto doc = doc_of(s);
  CHECK(builds_during([&] {
          CHECK_THROWS_AS(run::PreparedRun(doc, run::RunOptions{}), scenario::ScenarioError);
        }) == 0);
}

TEST_CASE("a run's drawn phases are read from its clocks; the document stays as read", "[run][builds][clocks]") {
  nlohmann::json s = testing::base_scenario();
  s["tracker"].erase("phase_ms");
  s["display"].erase("phase_ms");
  const auto doc = doc_of(s);
  run::PreparedRun prepared(doc, run::RunOptions{});
  const nlohmann::json resolved = prepared.resolved();
  const double period_ms = 1000.0 / 60.0;  // both clocks tick at 60 Hz: a phase is drawn within one period
  for (const char* clock : {"/tracker/phase_ms", "/display/phase_ms"}) {
    INFO(clock);
    const nlohmann::json::json_pointer p(clock);
    REQUIRE(resolved.contains(p));
    CHECK(resolved[p].get<double>() >= 0.0);
    CHECK(resolved[p].get<double>() < period_ms);
    // None was given, and the run writes none back into the document it read.
    CHECK_FALSE(doc.resolved().contains(p));
  }
  // summary.json's scenario holds the same phases.
  const nlohmann::json summary = prepared.run();
  for (const char* clock : {"/tracker/phase_ms", "/display/phase_ms"}) {
    const nlohmann::json::json_pointer p(clock);
    CHECK(summary.at("scenario")[p] == resolved[p]);
  }
}

TEST_CASE("a clock's phase is decided once, by the run's clocks, and never written back", "[run][builds][clocks]") {
  // The polled serial HMD with no phase keys: the tracker's, the kernel's
  // poll timer's and the display's phases are drawn per replication.
  nlohmann::json s = testing::base_scenario();
  s["tracker"].erase("phase_ms");
  s["display"].erase("phase_ms");
  s["transport"] = {{"type", "serial"}, {"record_bytes", 32}, {"baud", 19200}, {"host", "poll"}, {"poll_interval_ms", 7}};
  const auto doc = doc_of(s);
  for (uint64_t replication : {0u, 1u, 2u}) {
    run::RunOptions options;
    options.replication = replication;
    run::Run run;
    run::build(run, doc, options);
    // The bound scenario is what the file and the defaults make it: no phase.
    CHECK_FALSE(run.shared().tracker.clock.phase.has_value());
    CHECK_FALSE(run.shared().display.clock.phase.has_value());
    CHECK_FALSE(run.shared().transport.serial.poll_clock.phase.has_value());
    // Each model runs on the phase its clock drew: report 0 of the tracker,
    // field 0 of the display and the poll timer all start at that phase.
    const des::Clock& tracker = *run.clocks->find("tracker");
    const des::Clock& display = *run.clocks->find("display");
    const des::Clock& poll = *run.clocks->find("poll");
    CHECK(tracker.drawn);
    CHECK(run.tracker->nominal_time(0) == tracker.phase);
    CHECK(run.display->timing().field_start(0) == display.phase);
    const auto* serial = dynamic_cast<const tracker::SerialLink*>(run.transport.get());
    REQUIRE(serial != nullptr);
    CHECK(serial->params().poll_clock.phase == poll.phase);
    // A drawn phase lies within one period (7 ms poll, 1/60 s tracker and display).
    CHECK(poll.phase < des::Time::ms(7));
    CHECK(tracker.phase.to_seconds() < 1.0 / 60.0);
    CHECK(display.phase.to_seconds() < 1.0 / 60.0);
  }
}
