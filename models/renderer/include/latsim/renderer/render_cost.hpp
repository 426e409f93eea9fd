// How long a generic renderer takes for one frame.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "latsim/capture/capture.hpp"
#include "latsim/capture/replay.hpp"
#include "latsim/des/random.hpp"
#include "latsim/des/time.hpp"

namespace latsim::renderer {

/// A measured cost: one column of a capture, played back frame by frame.
struct TraceCost {
  std::shared_ptr<const capture::Capture> capture;  ///< holds the one column played
  capture::ReplayParams replay;
  std::string label;  ///< where it was asked for (the scenario's JSON pointer), for messages and summaries
};

/// Frame time = fixed + per primitive x primitives + per covered pixel x
/// covered pixels, optionally varied by a random factor per frame (normal
/// factors may be correlated from frame to frame); or, with a trace, the
/// values of a capture column in turn (nominal: their mean).
class RenderCost {
 public:
  enum class Variation { None, Uniform, Normal };
  struct Params {
    double fixed_ms = 0.0;
    double per_primitive_us = 0.0;
    double per_pixel_ns = 0.0;
    Variation variation = Variation::None;
    double variation_fraction = 0.0;  ///< uniform: +-fraction; normal: stddev as a fraction
    /// normal: frames over which a frame's factor still correlates with the
    /// next ones, falling to 1/e (a first-order autoregression); 0: independent
    double variation_correlation_frames = 0.0;
    std::shared_ptr<const TraceCost> trace;  ///< set: the cost is measured and the terms above are unused
  };

  RenderCost() = default;
  RenderCost(Params params, int64_t primitives, int64_t covered_pixels);
  /// The cost of drawing `triangles` triangles covering a `coverage` fraction
  /// of a width x height display, for each of `eyes` eyes per frame (both
  /// eyes are rendered per frame in stereo).
  static RenderCost for_scene(const Params& params, int64_t triangles, double coverage, int width_px, int height_px,
                              int eyes);

  /// Duration of the next frame; draws from `stream` only when variation is
  /// on or a trace is bootstrapped. A trace moves on by one value a call.
  des::Time frame_time(des::RandomStream& stream);
  /// The model's frame time; a trace's mean value (after scale, offset and clipping).
  des::Time nominal_frame_time() const { return nominal_; }
  bool varies() const {
    return replay_ || (params_.variation != Variation::None && params_.variation_fraction > 0);
  }
  /// A trace played in order that must stop at its end has no value left.
  bool exhausted() const { return replay_ && replay_->exhausted(); }
  /// The trace, if the cost is measured (with its replay's position).
  const TraceCost* trace() const { return params_.trace.get(); }
  const capture::Replay* replay() const { return replay_ ? &*replay_ : nullptr; }

 private:
  Params params_;
  des::Time nominal_;
  std::optional<capture::Replay> replay_;  // a copy of the cost starts from the position it had
  double correlated_ = 0.0;  // the last correlated normal deviate (unit variance)
  bool correlated_drawn_ = false;
};

}  // namespace latsim::renderer
