#include "latsim/tracker/predictor.hpp"

#include <array>
#include <utility>

#include "latsim/tracker/extrapolating_predictor.hpp"
#include "latsim/tracker/fusion_predictor.hpp"
#include "latsim/tracker/kalman_predictor.hpp"

namespace latsim::tracker {

namespace {

constexpr std::array<std::pair<PredictorKind, std::string_view>, 5> kNames{{
    {PredictorKind::None, "none"},
    {PredictorKind::ConstantVelocity, "constant_velocity"},
    {PredictorKind::ConstantAcceleration, "constant_acceleration"},
    {PredictorKind::Kalman, "kalman"},
    {PredictorKind::Fusion, "fusion"},
}};

}  // namespace

Pose extrapolate(const MotionEstimate& estimate, des::Time target) {
  const double h = (target - estimate.at).to_seconds();
  const glm::dvec3 turn = estimate.angular_velocity_rad_s * h + estimate.angular_acceleration_rad_s2 * (0.5 * h * h);
  Pose p;
  p.orientation = glm::normalize(quat_from_rotation_vector(turn) * estimate.pose.orientation);
  p.position_m = estimate.pose.position_m + estimate.velocity_m_s * h + estimate.acceleration_m_s2 * (0.5 * h * h);
  return p;
}

std::string_view predictor_name(PredictorKind kind) {
  for (const auto& [k, name] : kNames)
    if (k == kind) return name;
  return "none";
}

std::optional<PredictorKind> predictor_kind(std::string_view name) {
  for (const auto& [k, n] : kNames)
    if (n == name) return k;
  return std::nullopt;
}

std::unique_ptr<Predictor> make_predictor(const PredictorParams& params) {
  switch (params.kind) {
    case PredictorKind::None: return std::make_unique<ExtrapolatingPredictor>(0);
    case PredictorKind::ConstantVelocity: return std::make_unique<ExtrapolatingPredictor>(1);
    case PredictorKind::ConstantAcceleration: return std::make_unique<ExtrapolatingPredictor>(2);
    case PredictorKind::Kalman: return std::make_unique<KalmanPredictor>(params.kalman);
    case PredictorKind::Fusion: return std::make_unique<FusionPredictor>();
  }
  return std::make_unique<ExtrapolatingPredictor>(0);
}

}  // namespace latsim::tracker
