#include "latsim/measurement/apparent_latency.hpp"
#include "latsim/des/stop_token.hpp"
#include "latsim/units/units.hpp"

#include <algorithm>
#include <array>
#include <deque>
#include <cmath>

namespace latsim::measurement {

namespace {

// Windows whose true motion is slower than this (as the root-mean-square
// speed the fit's curvature implies) leave the shift undetermined.
constexpr double kMinSpeedDegS = 0.1;
constexpr double kCoarseMs = 2.0;  // the grid over the whole range
constexpr double kFineMs = 0.25;   // the grid around the coarse best
constexpr double kFinalMs = 0.02;  // the last parabola's half-width

des::Time shift_time(double shift_ms) { return des::Time::ps(std::llround(shift_ms * 1e9)); }

// Squared angle (rad²) between a shown orientation and the true one
// `shift_ms` before its photon time.
double misfit_one(const ShownSample& s, const tracker::MotionSource& truth, double shift_ms) {
  const double a = tracker::angle_between(s.orientation, truth.pose_at(s.photon - shift_time(shift_ms)).orientation);
  return a * a;
}

double misfit(std::span<const ShownSample> window, const tracker::MotionSource& truth, double shift_ms) {
  double sum = 0.0;
  for (const ShownSample& s : window) sum += misfit_one(s, truth, shift_ms);
  return sum;
}

// Shifts from_ms + k·kCoarseMs, k = 0 … n − 1, covering ±max_shift.
struct CoarseGrid {
  double from_ms;
  int n;
  explicit CoarseGrid(des::Time max_shift) {
    n = 2 * static_cast<int>(std::ceil(max_shift.to_ms() / kCoarseMs)) + 1;
    from_ms = -kCoarseMs * (n - 1) / 2;
  }
  double at(int k) const { return from_ms + kCoarseMs * k; }
};

// The misfit of one sample at every coarse shift.
std::vector<double> coarse_row(const ShownSample& s, const tracker::MotionSource& truth, const CoarseGrid& g) {
  std::vector<double> row(static_cast<size_t>(g.n));
  for (int k = 0; k < g.n; ++k) row[static_cast<size_t>(k)] = misfit_one(s, truth, g.at(k));
  return row;
}

// The vertex offset of the parabola through (−h, l), (0, m), (h, r).
double vertex(double l, double m, double r, double h) { return 0.5 * h * (l - r) / (l - 2.0 * m + r); }

// From the window's misfit on the coarse grid: a 0.25 ms grid around the
// coarse best, the vertex of the parabola through its best and neighbours,
// and the vertex of a parabola ±0.02 ms around that.
std::optional<double> refine(std::span<const ShownSample> window, const tracker::MotionSource& truth,
                             const CoarseGrid& g, const std::vector<double>& coarse) {
  const int c = static_cast<int>(std::min_element(coarse.begin(), coarse.end()) - coarse.begin());
  if (c == 0 || c == g.n - 1) return std::nullopt;
  constexpr int kFineN = 2 * static_cast<int>(kCoarseMs / kFineMs) + 1;
  const double fine_from = g.at(c) - kCoarseMs;
  std::array<double, kFineN> fine{};
  for (int k = 0; k < kFineN; ++k) fine[static_cast<size_t>(k)] = misfit(window, truth, fine_from + kFineMs * k);
  const int f = static_cast<int>(std::min_element(fine.begin(), fine.end()) - fine.begin());
  if (f == 0 || f == kFineN - 1) return std::nullopt;
  const double l = fine[static_cast<size_t>(f - 1)], m = fine[static_cast<size_t>(f)], r = fine[static_cast<size_t>(f + 1)];
  // Near its minimum the misfit is Σ ω_j² (s − s*)², so its curvature is
  // 2 n ω² for a root-mean-square speed ω: too flat, and nothing moves.
  const double curvature = (l - 2.0 * m + r) / (kFineMs * kFineMs);  // rad²/ms²
  const double min_speed_rad_ms = units::deg_to_rad(kMinSpeedDegS) / 1000.0;
  if (!(curvature > 2.0 * static_cast<double>(window.size()) * min_speed_rad_ms * min_speed_rad_ms))
    return std::nullopt;
  const double s1 = fine_from + kFineMs * f + std::clamp(vertex(l, m, r, kFineMs), -kFineMs, kFineMs);
  const double l2 = misfit(window, truth, s1 - kFinalMs), m2 = misfit(window, truth, s1),
               r2 = misfit(window, truth, s1 + kFinalMs);
  if (!(l2 - 2.0 * m2 + r2 > 0.0)) return s1;
  return s1 + std::clamp(vertex(l2, m2, r2, kFinalMs), -kFineMs, kFineMs);
}

}  // namespace

std::optional<double> fit_shift_ms(std::span<const ShownSample> window, const tracker::MotionSource& truth,
                                   des::Time max_shift) {
  if (window.size() < 2) return std::nullopt;
  const CoarseGrid g(max_shift);
  std::vector<double> coarse(static_cast<size_t>(g.n), 0.0);
  for (const ShownSample& s : window) {
    const std::vector<double> row = coarse_row(s, truth, g);
    for (size_t k = 0; k < coarse.size(); ++k) coarse[k] += row[k];
  }
  return refine(window, truth, g, coarse);
}

std::optional<double> start_latency_ms(std::span<const ShownSample> shown, const tracker::MotionSource& truth,
                                       des::Time start, des::Time before, double threshold_deg) {
  const double threshold = units::deg_to_rad(threshold_deg);
  auto photon_before = [](const ShownSample& s, des::Time t) { return s.photon < t; };
  const auto first = std::lower_bound(shown.begin(), shown.end(), start, photon_before);
  if (first == shown.begin()) return std::nullopt;
  const glm::dquat shown_rest = std::prev(first)->orientation;
  auto shown_start = std::find_if(first, shown.end(), [&](const ShownSample& s) {
    return s.photon < before && tracker::angle_between(shown_rest, s.orientation) > threshold;
  });
  if (shown_start == shown.end() || shown_start->photon >= before) return std::nullopt;
  // The truth's own start: the first 10 us step past the threshold, then bisection to 1 ns.
  const glm::dquat true_rest = truth.pose_at(start).orientation;
  auto moved = [&](des::Time t) { return tracker::angle_between(true_rest, truth.pose_at(t).orientation) > threshold; };
  des::Time lo = start, hi = start;
  while (!moved(hi)) {
    lo = hi;
    hi += des::Time::us(10);
    if (hi >= before) return std::nullopt;
  }
  while (hi - lo > des::Time::ns(1)) {
    const des::Time mid = lo + des::Time::ps((hi - lo).ticks() / 2);
    (moved(mid) ? hi : lo) = mid;
  }
  return (shown_start->photon - hi).to_ms();
}

ApparentLatencyResult apparent_latency(std::span<const ShownSample> shown, const tracker::MotionSource& truth,
                                       tracker::MotionPhaseClassifier& phases, const ApparentLatencyParams& p) {
  ApparentLatencyResult result;
  if (shown.empty()) return result;
  const des::Time half = des::Time::ps(p.window.ticks() / 2);
  const des::Time last = shown.back().photon;
  auto photon_before = [](const ShownSample& s, des::Time t) { return s.photon < t; };
  const CoarseGrid grid(p.max_shift);
  std::deque<std::vector<double>> rows;  // coarse misfits of samples cached_from, cached_from + 1, …
  size_t cached_from = 0;
  std::vector<double> coarse(static_cast<size_t>(grid.n));
  for (int64_t k = 0; p.step * k <= last; ++k) {
    des::check_stop();  // a window costs a fit over its samples: microseconds at least
    const des::Time centre = p.step * k;
    const tracker::MotionPhase phase = phases.phase_at(centre);
    const auto begin = std::lower_bound(shown.begin(), shown.end(), centre - half, photon_before);
    const auto end = std::lower_bound(begin, shown.end(), centre + half + des::Time::ps(1), photon_before);
    // Windows overlap: each sample's coarse misfits are computed once and
    // kept while windows still hold it.
    const auto b = static_cast<size_t>(begin - shown.begin()), e = static_cast<size_t>(end - shown.begin());
    while (cached_from < b && !rows.empty()) {
      rows.pop_front();
      ++cached_from;
    }
    if (rows.empty()) cached_from = b;
    while (cached_from + rows.size() < e) rows.push_back(coarse_row(shown[cached_from + rows.size()], truth, grid));
    std::optional<double> shift;
    if (e - b >= 2) {
      std::fill(coarse.begin(), coarse.end(), 0.0);
      for (size_t j = b; j < e; ++j)
        for (size_t k = 0; k < coarse.size(); ++k) coarse[k] += rows[j - cached_from][k];
      shift = refine(std::span(begin, end), truth, grid, coarse);
    }
    if (!shift) {
      // At rest an undetermined shift is expected: nothing moves.
      if (phase != tracker::MotionPhase::Still) ++result.unresolved;
      continue;
    }
    result.windows.push_back(WindowShift{centre, phase, *shift});
  }
  const std::vector<des::Time> all_starts = phases.starts_until(last);
  for (size_t i = 0; i < all_starts.size(); ++i) {
    const des::Time next = i + 1 < all_starts.size() ? all_starts[i + 1] : last;
    if (auto d = start_latency_ms(shown, truth, all_starts[i], next, p.start_threshold_deg)) result.start_ms.push_back(*d);
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
  const std::vector<des::Time>& starts = all_starts;
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
