// The one call through which a stage reads the head pose: "the pose for
// pixels lit at photon time T". Pose prediction plugs in here.
#pragma once

#include <optional>

#include "latsim/des/time.hpp"
#include "latsim/pipelines/pipeline.hpp"
#include "latsim/tracker/tracker.hpp"

namespace latsim::pipelines::frame_stages {

/// Answers a stage's request for the pose to compute with.
class PoseSampler {
 public:
  explicit PoseSampler(const HostFeed& host) : host_(&host) {}

  /// The sample a stage beginning at `now` uses for pixels expected to be lit
  /// at `photon_target`: the newest one the host can see (no prediction, so
  /// the target is not used yet); nullopt before the first sample arrives.
  std::optional<tracker::TrackerSample> sample(des::Time now, des::Time photon_target) const {
    (void)photon_target;
    return host_->newest_at(now);
  }

 private:
  const HostFeed* host_;
};

}  // namespace latsim::pipelines::frame_stages
