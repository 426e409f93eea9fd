#include "latsim/sweep/cost.hpp"

#include <algorithm>

#include "latsim/display/display.hpp"
#include "latsim/scenario/section.hpp"

namespace latsim::sweep {

double expected_cost(const sections::SharedParams& p) {
  const display::RasterParams& raster = p.display.raster;
  const double fields_per_s = 1.0 / raster.field_period.to_seconds();
  // Scanout events come per active line or pixel; blanking is one wait.
  const double lines = raster.interlaced ? raster.height_px / 2 : raster.height_px;
  const double stride = std::max(1, p.display.pixel_stride);
  double events_per_field = 1.0;
  if (p.display.fidelity == display::ScanoutFidelity::Line) events_per_field = lines;
  if (p.display.fidelity == display::ScanoutFidelity::Pixel) events_per_field = lines * raster.width_px / stride;
  return p.duration_s * fields_per_s * events_per_field * (p.host.stereo ? 2.0 : 1.0);
}

double expected_cost(const scenario::ScenarioDocument& doc) {
  sections::SharedParams p;
  scenario::Section root(doc.root());
  sections::bind(root, p);
  return expected_cost(p);
}

std::vector<size_t> longest_first(std::vector<size_t> indices, const std::vector<double>& cost_of_index) {
  std::stable_sort(indices.begin(), indices.end(),
                   [&](size_t a, size_t b) { return cost_of_index[a] > cost_of_index[b]; });
  return indices;
}

}  // namespace latsim::sweep
