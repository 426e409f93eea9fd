// What region priority rendering writes besides its figures: the table of
// memories (the published gallery experiment's) and pictures of the memories.
#pragma once

#include <array>
#include <string>
#include <vector>

#include <glm/gtc/quaternion.hpp>

#include "arp/frames.hpp"
#include "arp/region_run.hpp"
#include "latsim/renderer/camera.hpp"
#include "latsim/renderer/cube_map.hpp"

namespace latsim::results {
class RunFiles;
}

namespace latsim::pipelines {

/// Per memory and run: average update rate and object segments per update;
/// per run: render load, renderer use and what the seams look like; with a
/// position window (of `window` length), the same per memory over it.
std::string memories_markdown(const std::vector<const RegionRun*>& runs, des::Time duration, des::Time window);
/// The same figures as comma-separated values.
std::string memories_csv(const std::vector<const RegionRun*>& runs, des::Time duration);

/// Writes PNG pictures of what region priority memories show, seen with one head orientation.
class RegionFrames {
 public:
  RegionFrames(const renderer::Camera& camera, const glm::dquat& head, const FrameOptions& options, results::RunFiles& files);
  /// <stem>_memory<i>.png for each memory and <stem>_composite.png.
  void write_memories(const std::string& stem, const RegionRun& run);
  /// <stem>_torn.png / _warped.png and 8x close-ups at the widest tear the torn run shows.
  void write_tear_close_ups(const std::string& stem, const RegionRun& torn, const RegionRun& warped,
                            const arp::ScreenProjection& screen);

 private:
  renderer::Frame composite(const RegionRun& run, std::vector<renderer::CubeMap>* cubes);
  std::array<int, 2> widest_tear(const RegionRun& run, const arp::ScreenProjection& screen) const;

  const renderer::Camera& camera_;
  glm::dquat head_;
  const FrameOptions& options_;
  results::RunFiles& files_;
};

}  // namespace latsim::pipelines
