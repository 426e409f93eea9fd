#include "sweep_cost.hpp"

#include <algorithm>
#include <charconv>
#include <string>

namespace latsim::app {

namespace {

using Json = nlohmann::json;

double number_or(const Json& object, const char* key, double fallback) {
  if (!object.is_object() || !object.contains(key)) return fallback;
  const Json& v = object[key];
  if (v.is_number()) return v.get<double>();
  if (v.is_boolean()) return v.get<bool>() ? 1.0 : 0.0;
  if (!v.is_string()) return fallback;
  // Exact rational frequencies are written "num/den".
  const std::string text = v.get<std::string>();
  double num = 0, den = 1;
  const auto slash = text.find('/');
  const auto r1 = std::from_chars(text.data(), text.data() + (slash == std::string::npos ? text.size() : slash), num);
  if (r1.ec != std::errc{}) return fallback;
  if (slash != std::string::npos && std::from_chars(text.data() + slash + 1, text.data() + text.size(), den).ec != std::errc{})
    return fallback;
  return den != 0 ? num / den : fallback;
}

}  // namespace

double expected_cost(const Json& resolved) {
  // Defaults as docs/scenario-reference.md gives them, for a scenario read without them.
  const double duration_s = number_or(resolved, "duration_s", 10.0);
  if (!resolved.is_object() || !resolved.contains("display")) return duration_s;
  const Json& display = resolved["display"];
  const double fields_per_s = number_or(display, "refresh_hz", 60.0);
  const bool interlaced = number_or(display, "interlaced", 0.0) != 0.0;
  // Scanout events come per active line or pixel; blanking is one wait.
  const double lines = number_or(display, "height_px", 480.0) / (interlaced ? 2.0 : 1.0);
  const double line_px = number_or(display, "width_px", 640.0);
  const double stride = std::max(1.0, number_or(display, "pixel_stride", 1.0));
  const std::string scanout = display.value("scanout", std::string("field"));
  double events_per_field = 1.0;
  if (scanout == "line") events_per_field = lines;
  if (scanout == "pixel") events_per_field = lines * line_px / stride;
  const bool stereo = resolved.contains("host") && number_or(resolved["host"], "stereo", 0.0) != 0.0;
  return duration_s * fields_per_s * events_per_field * (stereo ? 2.0 : 1.0);
}

std::vector<size_t> longest_first(std::vector<size_t> indices, const std::vector<double>& cost_of_index) {
  std::stable_sort(indices.begin(), indices.end(),
                   [&](size_t a, size_t b) { return cost_of_index[a] > cost_of_index[b]; });
  return indices;
}

}  // namespace latsim::app
