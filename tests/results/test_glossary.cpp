// The glossary's figures belong to the recorder: documented once, computed
// once, and never reported by a pipeline under the same name.
#include <catch2/catch.hpp>

#include <fstream>
#include <iterator>
#include <string>

#include "latsim/des/simulator.hpp"
#include "latsim/display/raster_timing.hpp"
#include "latsim/results/glossary.hpp"
#include "latsim/results/image_book.hpp"
#include "latsim/results/latency_recorder.hpp"
#include "latsim/tracker/host_feed.hpp"
#include "latsim/tracker/motion_phase.hpp"
#include "latsim/tracker/motion_source.hpp"

using namespace latsim;

namespace {

/// A host that never sees a sample.
class NoSamples final : public tracker::HostFeed {
 public:
  std::optional<tracker::TrackerSample> newest_at(des::Time) const override { return std::nullopt; }
  des::Time received_at(const tracker::TrackerSample& s) const override { return s.ready_at; }
  void on_delivery(std::function<void(const tracker::TrackerSample&, des::Time)>) override {}
  tracker::PredictionBasis basis_of(const tracker::TrackerSample& s) const override { return tracker::hold_basis(s); }
  bool predicts() const override { return false; }
};

struct Recorder {
  des::Simulator sim;
  tracker::StillMotion motion{tracker::Pose{}};
  NoSamples host;
  display::RasterTiming timing{display::RasterParams{}};
  results::ImageBook images;
  results::LatencyRecorder recorder{sim, motion, host, images, timing, results::ProbeSet{}, 0.064, false, false};
};

}  // namespace

TEST_CASE("every glossary figure is defined in docs/figures.md", "[glossary]") {
  std::ifstream in(LATSIM_SOURCE_DIR "/docs/figures.md");
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  REQUIRE_FALSE(text.empty());
  for (const auto& entry : results::glossary()) {
    INFO(entry.name);
    CHECK(text.find("\n### " + std::string(entry.name) + "\n") != std::string::npos);
    CHECK_FALSE(entry.definition.empty());
  }
}

TEST_CASE("a pipeline cannot report under a glossary name, nor set a figure twice", "[glossary]") {
  Recorder r;
  results::LatencyRecorder& rec = r.recorder;
  CHECK_THROWS_AS(rec.add("motion_to_photon_ms", 1.0), std::logic_error);
  CHECK_THROWS_AS(rec.set("render_latency_fields", 2.99), std::logic_error);
  CHECK_THROWS_AS(rec.publish("render_latency_fields", stats::Distribution{}), std::logic_error);
  CHECK_THROWS_AS(rec.set("frame_rate_hz", 60.0), std::logic_error);
  CHECK_THROWS_AS(rec.set("missed_refreshes.total", int64_t{1}), std::logic_error);
  CHECK_THROWS_AS(rec.count("images_shown"), std::logic_error);
  // A variant under its own name is welcome, once.
  rec.publish("transform_to_copy_end_fields", stats::Distribution{});
  rec.set("frames_rendered", int64_t{3});
  CHECK_THROWS_AS(rec.set("frames_rendered", int64_t{4}), std::logic_error);
  rec.add("tear_gap_px", 0.5);
  CHECK_THROWS_AS(rec.set("tear_gap_px", 1.0), std::logic_error);
  CHECK(results::is_glossary_figure("rotation_latency_ms"));
  CHECK_FALSE(results::is_glossary_figure("translation_latency_memory0_ms"));
}

TEST_CASE("the motion-phase parts of split figures are the recorder's", "[glossary]") {
  Recorder r;
  CHECK(results::is_glossary_figure("prediction_error_deg"));
  CHECK(results::is_glossary_figure("registration_error_arcmin_onset"));
  CHECK(results::is_glossary_figure("prediction_error_deg_still.mean"));
  CHECK_FALSE(results::is_glossary_figure("prediction_error_deg_early"));
  CHECK_FALSE(results::is_glossary_figure("registration_error_arcmin_onsets"));
  CHECK_FALSE(results::is_glossary_figure("prediction_error_mm_steady"));
  CHECK_THROWS_AS(r.recorder.add("registration_error_arcmin_steady", 1.0), std::logic_error);
  CHECK_THROWS_AS(r.recorder.add("prediction_horizon_ms", 1.0), std::logic_error);
  // The suffixes are the classifier's own phase names, in its order.
  const auto phases = results::motion_phase_suffixes();
  REQUIRE(phases.size() == 4);
  for (size_t i = 0; i < phases.size(); ++i) CHECK(tracker::phase_name(static_cast<tracker::MotionPhase>(i)) == phases[i]);
}
