// presentmon.csv read back with the capture reader reproduces the run's
// frame costs exactly: the GPU stage's cost varies, and its k-th cost is
// drawn again here, independently of the pipeline, as the k-th draw of the
// stage's random stream (the only stage that varies draws from it, frame by
// frame in order on the one GPU).
#include <catch2/catch.hpp>

#include <filesystem>
#include <string>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include "latsim/capture/capture.hpp"
#include "latsim/des/random.hpp"
#include "latsim/renderer/render_cost.hpp"
#include "latsim/run/runner.hpp"
#include "latsim/scenario/config.hpp"

namespace {

using latsim::des::Time;
namespace fs = std::filesystem;

nlohmann::json varying_gpu_scenario() {
  return nlohmann::json::parse(R"({
    "duration_s": 1, "seed": 11,
    "motion": {"type": "constant", "axis": [0, 1, 0], "rate_deg_s": 60, "position_m": [0, 1.6, 0]},
    "tracker": {"rate_hz": 1000, "internal_delay_ms": 0},
    "transport": {"type": "direct"},
    "display": {"refresh_hz": 62.5, "width_px": 640, "height_px": 480, "vblank_lines": 0, "hblank_px": 0,
                "hfov_deg": 90, "scanout": "line"},
    "pipeline": {
      "type": "frame_stages",
      "processors": [{"name": "cpu"}, {"name": "gpu"}],
      "stages": [
        {"name": "I", "on": "cpu", "start": "retrace", "samples_pose": true, "cost": {"fixed_ms": 1}},
        {"name": "S", "on": "cpu", "cost": {"fixed_ms": 5}},
        {"name": "G", "on": "gpu", "cost": {"fixed_ms": 9, "variation": "uniform", "variation_fraction": 0.3}}
      ]
    }
  })");
}

}  // namespace

TEST_CASE("presentmon.csv read back with the capture reader gives each frame's drawn GPU and CPU cost exactly") {
  const fs::path dir = fs::temp_directory_path() / ("latsim_presentmon_roundtrip_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  const auto doc = latsim::scenario::ScenarioDocument::from_json(varying_gpu_scenario(), LATSIM_SOURCE_DIR "/scenarios");
  latsim::run::RunOptions options;
  options.out_dir = dir;
  latsim::run::run_scenario(doc, options);

  const latsim::capture::Capture cap =
      latsim::capture::read_capture(dir / "presentmon.csv", {{"MsGPUBusy", "MsCPUBusy", "FrameId"}, {}});
  fs::remove_all(dir);
  CHECK(cap.generation == latsim::capture::Generation::current);
  CHECK(cap.application == "frame_stages");
  const auto& gpu = cap.column("MsGPUBusy").values;
  const auto& cpu = cap.column("MsCPUBusy").values;
  const auto& ids = cap.column("FrameId").values;
  // 62.5 frames a second, less the last one or two still on their way to the display.
  REQUIRE(gpu.size() >= 55);
  REQUIRE(ids.size() == gpu.size());

  // The k-th G, drawn again: 9 ms times 1 + U(-0.3, 0.3) from stream "frame_stages" of seed 11.
  latsim::des::RandomStream stream(11, "frame_stages", 0);
  latsim::renderer::RenderCost g({.fixed_ms = 9, .variation = latsim::renderer::RenderCost::Variation::Uniform,
                                        .variation_fraction = 0.3},
                                       0, 0);
  for (size_t k = 0; k < gpu.size(); ++k) {
    // FrameId read as milliseconds: frame k is k ms.
    REQUIRE(ids[k] == Time::ms(static_cast<int64_t>(k)));
    const Time drawn = g.frame_time(stream);
    INFO("frame " << k);
    CHECK(gpu[k].ticks() == drawn.ticks());
    CHECK(cpu[k] == Time::ms(6));  // I + S, fixed
  }
}
