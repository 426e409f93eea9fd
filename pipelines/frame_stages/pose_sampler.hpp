// The one call through which a stage reads the head pose: "the pose for
// pixels lit at photon time T", predicted there by the host.
#pragma once

#include <optional>

#include "latsim/des/time.hpp"
#include "latsim/pipelines/pipeline.hpp"
#include "latsim/tracker/host_feed.hpp"
#include "latsim/tracker/host_prediction.hpp"

namespace latsim::pipelines::frame_stages {

/// Answers a stage's request for the pose to compute with.
class PoseSampler {
 public:
  explicit PoseSampler(const tracker::HostFeed& host) : host_(&host) {}

  /// The pose a stage beginning at `now` uses for pixels expected to be lit
  /// at `photon_target`: from the newest sample the host can see, predicted
  /// to that instant when the host predicts; nullopt before the first sample.
  std::optional<tracker::PosePrediction> pose(des::Time now, des::Time photon_target) const {
    return host_->pose_for(now, photon_target);
  }

 private:
  const tracker::HostFeed* host_;
};

}  // namespace latsim::pipelines::frame_stages
