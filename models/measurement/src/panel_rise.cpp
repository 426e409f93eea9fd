#include "latsim/measurement/panel_rise.hpp"

#include <algorithm>
#include <cmath>

namespace latsim::measurement {

double PanelRise::fraction(des::Time since) const {
  const double r = response.to_seconds();
  if (curve == Curve::step || r <= 0.0) return 1.0;
  if (since <= des::Time::zero()) return 0.0;
  const double t = since.to_seconds();
  if (curve == Curve::linear) return std::min(1.0, t / r);
  return 1.0 - std::exp(-t * std::log(9.0) / r);
}

}  // namespace latsim::measurement
