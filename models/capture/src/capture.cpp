#include "latsim/capture/capture.hpp"

#include <algorithm>
#include <cctype>


namespace latsim::capture {

namespace {

bool has(const std::vector<std::string>& header, const char* name) {
  return std::find(header.begin(), header.end(), name) != header.end();
}

}  // namespace

const char* generation_name(Generation g) {
  switch (g) {
    case Generation::current: return "current";
    case Generation::v1: return "v1";
    case Generation::v2: return "v2";
    case Generation::ovr_metrics: return "ovr_metrics";
    case Generation::vrapi: return "vrapi";
    case Generation::steamvr: return "steamvr";
    case Generation::generic: return "generic";
  }
  return "generic";
}

Generation detect_generation(const std::vector<std::string>& header) {
  if (has(header, "MsBetweenPresents") || has(header, "MsCPUBusy")) return Generation::current;
  if (has(header, "TimeInSeconds") || has(header, "msBetweenPresents")) return Generation::v1;
  if (has(header, "CPUBusy") || has(header, "CPUStartQPC")) return Generation::v2;
  if (has(header, "average_frame_rate") || has(header, "app_gpu_time_microseconds")) return Generation::ovr_metrics;
  if (has(header, "m_nFrameIndex") || has(header, "m_flClientFrameIntervalMs")) return Generation::steamvr;
  return Generation::generic;
}

bool is_presentmon(Generation g) { return g == Generation::current || g == Generation::v1 || g == Generation::v2; }

bool is_display_column(const std::string& name) {
  std::string lower(name);
  std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return std::tolower(c); });
  return lower.find("display") != std::string::npos;
}

des::Time CaptureColumn::min() const {
  if (values.empty()) throw std::out_of_range("column " + name + " has no values");
  return *std::min_element(values.begin(), values.end());
}

des::Time CaptureColumn::max() const {
  if (values.empty()) throw std::out_of_range("column " + name + " has no values");
  return *std::max_element(values.begin(), values.end());
}

std::vector<double> CaptureColumn::values_ms() const {
  std::vector<double> ms;
  ms.reserve(values.size());
  for (des::Time v : values) ms.push_back(v.to_ms());
  return ms;
}

des::Time CaptureColumn::mean() const {
  if (values.empty()) throw std::out_of_range("column " + name + " has no values");
  // Summed as 128-bit integers: a million values of a second each do not overflow.
  __int128 sum = 0;
  for (des::Time v : values) sum += v.ticks();
  const auto n = static_cast<__int128>(values.size());
  const __int128 half = sum >= 0 ? n / 2 : -(n / 2);
  return des::Time::ps(static_cast<int64_t>((sum + half) / n));
}

const CaptureColumn& Capture::column(const std::string& name) const {
  for (const CaptureColumn& c : columns)
    if (c.name == name) return c;
  throw std::out_of_range("no column " + name + " was read from " + source.string());
}

}  // namespace latsim::capture
