#include "latsim/renderer/render_cost.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace latsim::renderer {

RenderCost::RenderCost(Params params, int64_t primitives, int64_t covered_pixels) : params_(std::move(params)) {
  if (const TraceCost* t = params_.trace.get()) {
    // The replay shares the column's values with the capture that holds them.
    const std::shared_ptr<const std::vector<des::Time>> values(t->capture, &t->capture->columns.front().values);
    replay_.emplace(values, t->replay);
    nominal_ = replay_->mean();
    return;
  }
  const double ms = params_.fixed_ms + params_.per_primitive_us * 1e-3 * static_cast<double>(primitives) +
                    params_.per_pixel_ns * 1e-6 * static_cast<double>(covered_pixels);
  nominal_ = des::Time::from_ms(ms);
}

RenderCost RenderCost::for_scene(const Params& params, int64_t triangles, double coverage, int width_px, int height_px,
                                 int eyes) {
  const int64_t pixels = static_cast<int64_t>(coverage * width_px * height_px) * eyes;
  return RenderCost(params, triangles * eyes, pixels);
}

des::Time RenderCost::frame_time(des::RandomStream& stream) {
  if (replay_) return replay_->next(stream);
  if (!varies()) return nominal_;
  double factor = 1.0;
  if (params_.variation == Variation::Uniform)
    factor = 1.0 + stream.uniform(-params_.variation_fraction, params_.variation_fraction);
  else if (params_.variation_correlation_frames <= 0.0)
    factor = 1.0 + stream.normal(0.0, params_.variation_fraction);
  else {
    // x_j = r x_(j-1) + sqrt(1 - r^2) z_j keeps unit variance, the first x the
    // stationary one, and correlates frames k apart by r^k = exp(-k / N).
    const double r = std::exp(-1.0 / params_.variation_correlation_frames);
    const double z = stream.normal(0.0, 1.0);
    correlated_ = correlated_drawn_ ? r * correlated_ + std::sqrt(1.0 - r * r) * z : z;
    correlated_drawn_ = true;
    factor = 1.0 + params_.variation_fraction * correlated_;
  }
  factor = std::max(factor, 0.0);
  return des::Time::from_seconds(nominal_.to_seconds() * factor);
}

}  // namespace latsim::renderer
