#include "cell_units.hpp"

#include <array>
#include <charconv>

namespace latsim::capture {

namespace {

bool ends_with(std::string_view s, std::string_view tail) {
  return s.size() >= tail.size() && s.substr(s.size() - tail.size()) == tail;
}

// VrApi's fields that are times in ms (Meta's "VrApi Stats Definition Guide").
constexpr std::array<std::string_view, 5> kVrApiTimes{"Prd", "TW", "App", "GD", "CPU&GPU"};

bool vrapi_time(std::string_view name) {
  for (std::string_view t : kVrApiTimes)
    if (t == name) return true;
  return false;
}

}  // namespace

std::optional<double> parse_number(std::string_view text) {
  double v = 0.0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (ec != std::errc{} || end != text.data() + text.size()) return std::nullopt;
  return v;
}

bool not_available(Generation g, std::string_view cell) {
  return cell.empty() || cell == "NA" || (g == Generation::ovr_metrics && cell == "9999");
}

std::optional<std::string> not_a_duration(Generation g, const std::string& name) {
  if (g == Generation::ovr_metrics && !ends_with(name, "_microseconds") && !ends_with(name, "_milliseconds"))
    return "column \"" + name + "\" of an OVR Metrics export is not a duration (its durations end in _microseconds "
           "or _milliseconds: app_gpu_time_microseconds, timewarp_gpu_time_microseconds, ...)";
  if (g == Generation::vrapi && !vrapi_time(name))
    return "field \"" + name + "\" of a VrApi line is not a duration (the durations: Prd, TW, App, GD, CPU&GPU)";
  return std::nullopt;
}

std::optional<double> cell_ms(Generation g, const std::string& name, std::string_view cell) {
  if (g == Generation::vrapi) {
    if (!ends_with(cell, "ms")) return std::nullopt;
    return parse_number(cell.substr(0, cell.size() - 2));
  }
  const std::optional<double> v = parse_number(cell);
  if (v && g == Generation::ovr_metrics && ends_with(name, "_microseconds")) return *v / 1000.0;
  return v;
}

std::string unit_name(Generation g, const std::string& name) {
  if (g == Generation::vrapi) return "milliseconds written with their unit (1.73ms)";
  if (g == Generation::ovr_metrics && ends_with(name, "_microseconds")) return "microseconds";
  return "milliseconds";
}

}  // namespace latsim::capture
