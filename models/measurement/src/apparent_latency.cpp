#include "latsim/measurement/apparent_latency.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace latsim::measurement {

namespace {

// Windows whose true motion is slower than this (as the root-mean-square
// speed the fit's curvature implies) leave the shift undetermined.
constexpr double kMinSpeedDegS = 0.1;

des::Time shift_time(double shift_ms) { return des::Time::ps(std::llround(shift_ms * 1e9)); }

// Sum of squared angles between each shown orientation and the true one
// `shift_ms` earlier than its photon time, in rad².
double misfit(std::span<const ShownSample> window, const tracker::MotionSource& truth, double shift_ms) {
  const des::Time shift = shift_time(shift_ms);
  double sum = 0.0;
  for (const ShownSample& s : window) {
    const double a = tracker::angle_between(s.orientation, truth.pose_at(s.photon - shift).orientation);
    sum += a * a;
  }
  return sum;
}

struct GridBest {
  int index;
  double value;
};

// The smallest misfit on shifts from + k·step, k = 0 … n − 1.
GridBest grid_minimum(std::span<const ShownSample> window, const tracker::MotionSource& truth, double from_ms,
                      double step_ms, int n, std::vector<double>& values) {
  values.assign(static_cast<size_t>(n), 0.0);
  GridBest best{0, INFINITY};
  for (int k = 0; k < n; ++k) {
    values[static_cast<size_t>(k)] = misfit(window, truth, from_ms + step_ms * k);
    if (values[static_cast<size_t>(k)] < best.value) best = GridBest{k, values[static_cast<size_t>(k)]};
  }
  return best;
}

}  // namespace

std::optional<double> fit_shift_ms(std::span<const ShownSample> window, const tracker::MotionSource& truth,
                                   des::Time max_shift) {
  if (window.size() < 2) return std::nullopt;
  // A coarse grid of 2 ms over the whole range, then 0.05 ms around its best,
  // then the vertex of the parabola through the finest best and its neighbours.
  const double range_ms = max_shift.to_ms();
  constexpr double kCoarseMs = 2.0, kFineMs = 0.05;
  const int coarse_n = 2 * static_cast<int>(std::ceil(range_ms / kCoarseMs)) + 1;
  const double coarse_from = -kCoarseMs * (coarse_n - 1) / 2;
  std::vector<double> values;
  const GridBest coarse = grid_minimum(window, truth, coarse_from, kCoarseMs, coarse_n, values);
  if (coarse.index == 0 || coarse.index == coarse_n - 1) return std::nullopt;
  const int fine_n = 2 * static_cast<int>(kCoarseMs / kFineMs) + 1;
  const double fine_from = coarse_from + kCoarseMs * coarse.index - kCoarseMs;
  const GridBest fine = grid_minimum(window, truth, fine_from, kFineMs, fine_n, values);
  if (fine.index == 0 || fine.index == fine_n - 1) return std::nullopt;
  const double left = values[static_cast<size_t>(fine.index - 1)];
  const double right = values[static_cast<size_t>(fine.index + 1)];
  const double curvature = (left - 2.0 * fine.value + right) / (kFineMs * kFineMs);  // rad²/ms²
  // Near its minimum the misfit is Σ ω_j² (s − s*)², so its curvature is
  // 2 n ω² for a root-mean-square speed ω.
  const double min_speed_rad_ms = kMinSpeedDegS * std::numbers::pi / 180.0 / 1000.0;
  if (!(curvature > 2.0 * static_cast<double>(window.size()) * min_speed_rad_ms * min_speed_rad_ms))
    return std::nullopt;
  const double offset = 0.5 * kFineMs * (left - right) / (left - 2.0 * fine.value + right);
  return fine_from + kFineMs * fine.index + offset;
}

ApparentLatencyResult apparent_latency(std::span<const ShownSample> shown, const tracker::MotionSource& truth,
                                       tracker::MotionPhaseClassifier& phases, const ApparentLatencyParams& p) {
  ApparentLatencyResult result;
  if (shown.empty()) return result;
  const des::Time half = des::Time::ps(p.window.ticks() / 2);
  const des::Time last = shown.back().photon;
  auto photon_before = [](const ShownSample& s, des::Time t) { return s.photon < t; };
  for (int64_t k = 0; p.step * k <= last; ++k) {
    const des::Time centre = p.step * k;
    const tracker::MotionPhase phase = phases.phase_at(centre);
    const auto begin = std::lower_bound(shown.begin(), shown.end(), centre - half, photon_before);
    const auto end = std::lower_bound(begin, shown.end(), centre + half + des::Time::ps(1), photon_before);
    const std::optional<double> shift = fit_shift_ms(std::span(begin, end), truth, p.max_shift);
    if (!shift) {
      // At rest an undetermined shift is expected: nothing moves.
      if (phase != tracker::MotionPhase::Still) ++result.unresolved;
      continue;
    }
    result.windows.push_back(WindowShift{centre, phase, *shift});
  }
  double steady_sum = 0.0;
  int64_t steady_n = 0;
  for (const WindowShift& w : result.windows)
    if (w.phase == tracker::MotionPhase::Steady) {
      steady_sum += w.shift_ms;
      ++steady_n;
    }
  if (steady_n == 0) return result;
  result.steady_ms = steady_sum / static_cast<double>(steady_n);
  const double target = *result.steady_ms + p.catch_up_tolerance_ms;
  const std::vector<des::Time> starts = phases.starts_until(last);
  for (size_t i = 0; i < starts.size(); ++i) {
    const des::Time start = starts[i];
    const des::Time next = i + 1 < starts.size() ? starts[i + 1] : des::Time::max();
    // The movement's windows: from its start while it is in onset or steady motion.
    auto w = std::lower_bound(result.windows.begin(), result.windows.end(), start,
                              [](const WindowShift& a, des::Time t) { return a.centre < t; });
    bool caught = false;
    for (; w != result.windows.end(); ++w) {
      if (w->centre >= next || (w->phase != tracker::MotionPhase::Onset && w->phase != tracker::MotionPhase::Steady))
        break;
      if (w->shift_ms <= target) {
        result.catch_up_ms.push_back((w->centre - start).to_ms());
        caught = true;
        break;
      }
    }
    if (!caught) ++result.never_caught_up;
  }
  return result;
}

}  // namespace latsim::measurement
