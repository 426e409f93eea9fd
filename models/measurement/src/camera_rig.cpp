#include "latsim/measurement/camera_rig.hpp"

#include "latsim/des/stop_token.hpp"

#include <algorithm>
#include <cmath>

namespace latsim::measurement {

namespace {

// The angle equal to `a` modulo 360 degrees nearest to `near`.
double unwrap_near(double a, double near) { return a + 360.0 * std::round((near - a) / 360.0); }

// A reading per frame, unwrapped from frame to frame; frames the camera saw
// no light in keep the previous reading (the first ones the first reading).
struct Readings {
  std::vector<double> value;
  std::vector<bool> lit;  ///< the frame caught light (else it holds the previous value)
};

std::optional<Readings> readings(const FilmedSignal& signal, const des::PeriodicSchedule& camera, int64_t first,
                                 int64_t n, des::Time exposure, des::Time row_offset) {
  std::vector<std::optional<double>> seen(static_cast<size_t>(n));
  uint64_t steps = 0;
  for (int64_t k = 0; k < n; ++k) {
    des::check_stop_every(steps, 1024);
    const des::Time open = camera.at(first + k) + row_offset;
    seen[static_cast<size_t>(k)] = signal.seen(open, open + exposure);
  }
  const auto lit = std::find_if(seen.begin(), seen.end(), [](const auto& v) { return v.has_value(); });
  if (lit == seen.end()) return std::nullopt;
  Readings out{std::vector<double>(static_cast<size_t>(n)), std::vector<bool>(static_cast<size_t>(n))};
  double last = **lit;
  for (size_t k = 0; k < out.value.size(); ++k) {
    if (seen[k]) last = unwrap_near(*seen[k], last);
    out.value[k] = last;
    out.lit[k] = seen[k].has_value();
  }
  return out;
}

// Whether both readings stayed within `tol` over frames [k − n, k].
bool steady(const std::vector<double>& a, const std::vector<double>& b, int64_t k, int64_t n, double tol) {
  if (k < n) return false;
  auto within = [&](const std::vector<double>& v) {
    const auto from = v.begin() + (k - n), to = v.begin() + k + 1;
    const auto [lo, hi] = std::minmax_element(from, to);
    return *hi - *lo <= tol;
  };
  return within(a) && within(b);
}

// Least-squares shift (ms) of display readings d onto object readings r over
// the frames in [a, b] that caught the display lit, frame k at time
// `t_ms[k]`; frames `frame_ms` apart.
std::optional<double> trajectory_shift_ms(const std::vector<double>& r, const Readings& d,
                                          const std::vector<double>& t_ms, int64_t a, int64_t b, double frame_ms,
                                          double max_shift_ms) {
  const auto n = static_cast<int64_t>(r.size());
  auto object_at = [&](double t) {
    const double f = std::clamp((t - t_ms[0]) / frame_ms, 0.0, static_cast<double>(n - 1));
    const auto i = std::min<int64_t>(static_cast<int64_t>(f), n - 2 < 0 ? 0 : n - 2);
    const double u = f - static_cast<double>(i);
    return n == 1 ? r[0] : r[static_cast<size_t>(i)] * (1.0 - u) + r[static_cast<size_t>(i + 1)] * u;
  };
  auto misfit = [&](double s) {
    double sum = 0.0;
    for (int64_t k = a; k <= b; ++k) {
      if (!d.lit[static_cast<size_t>(k)]) continue;
      const double e = d.value[static_cast<size_t>(k)] - object_at(t_ms[static_cast<size_t>(k)] - s);
      sum += e * e;
    }
    return sum;
  };
  auto grid = [&](double from, double step, int count, std::vector<double>& v) {
    v.assign(static_cast<size_t>(count), 0.0);
    int best = 0;
    for (int i = 0; i < count; ++i) {
      v[static_cast<size_t>(i)] = misfit(from + step * i);
      if (v[static_cast<size_t>(i)] < v[static_cast<size_t>(best)]) best = i;
    }
    return best;
  };
  const double coarse = std::min(2.0, frame_ms / 4.0);
  const int coarse_n = 2 * static_cast<int>(std::ceil(max_shift_ms / coarse)) + 1;
  const double coarse_from = -coarse * (coarse_n - 1) / 2;
  std::vector<double> v;
  const int c = grid(coarse_from, coarse, coarse_n, v);
  if (c == 0 || c == coarse_n - 1) return std::nullopt;
  constexpr int kFine = 20;
  const double fine = coarse / kFine;
  const double fine_from = coarse_from + coarse * (c - 1);
  const int f = grid(fine_from, fine, 2 * kFine + 1, v);
  if (f == 0 || f == 2 * kFine) return std::nullopt;
  const double left = v[static_cast<size_t>(f - 1)], mid = v[static_cast<size_t>(f)], right = v[static_cast<size_t>(f + 1)];
  const double bend = left - 2.0 * mid + right;
  const double offset = bend > 0.0 ? 0.5 * fine * (left - right) / bend : 0.0;
  return fine_from + fine * f + offset;
}

}  // namespace

std::optional<double> ObjectSignal::seen(des::Time open, des::Time close) const {
  if (close <= open) return angle_deg_(open);
  constexpr int kPoints = 8;
  const int64_t span = (close - open).ticks();
  const double first = angle_deg_(open + des::Time::ps(span / (2 * kPoints)));
  double sum = 0.0;
  for (int i = 0; i < kPoints; ++i) {
    const des::Time t = open + des::Time::ps(span / (2 * kPoints) + span * i / kPoints);
    sum += unwrap_near(angle_deg_(t), first);
  }
  return sum / kPoints;
}

std::optional<double> DisplaySignal::seen(des::Time open, des::Time close) const {
  // First interval that ends at or after the shutter opens.
  auto it = std::lower_bound(lit_.begin(), lit_.end(), open, [](const LitAngle& l, des::Time t) { return l.off < t; });
  if (close <= open) {
    for (; it != lit_.end() && it->on <= open; ++it)
      if (open < it->off || it->on == open) return it->angle_deg;
    return std::nullopt;
  }
  double weighted = 0.0, weight = 0.0, flashes = 0.0;
  int flash_count = 0;
  std::optional<double> first;
  for (; it != lit_.end() && it->on < close; ++it) {
    const double a = first ? unwrap_near(it->angle_deg, *first) : it->angle_deg;
    const double old = unwrap_near(it->from_deg, a);
    if (!first) first = a;
    if (it->off == it->on) {
      if (it->on >= open) {
        flashes += old + (a - old) * rise_.fraction(it->on - it->written);
        ++flash_count;
      }
      continue;
    }
    const des::Time from = std::max(open, it->on), to = std::min(close, it->off);
    if (to > from) {
      const double w = (to - from).to_seconds();
      weighted += w * mean_over(*it, a, old, from, to);
      weight += w;
    }
  }
  if (weight > 0.0) return weighted / weight;
  if (flash_count > 0) return flashes / flash_count;
  return std::nullopt;
}

double DisplaySignal::mean_over(const LitAngle& l, double angle, double from_angle, des::Time from, des::Time to) const {
  if (rise_.curve == PanelRise::Curve::step || rise_.response <= des::Time::zero() || from_angle == angle) return angle;
  // The midpoint rule over 16 points: the transition is smooth and the
  // camera's reading a mean, so a few hundredths of a degree at most.
  constexpr int kPoints = 16;
  const int64_t span = (to - from).ticks();
  double sum = 0.0;
  for (int i = 0; i < kPoints; ++i) {
    const des::Time t = from + des::Time::ps(span / (2 * kPoints) + span * i / kPoints);
    sum += rise_.fraction(t - l.written);
  }
  return from_angle + (angle - from_angle) * sum / kPoints;
}

des::Time CameraRigParams::object_offset() const {
  return shutter == Shutter::rolling ? des::Time::from_seconds(readout.to_seconds() * object_row) : des::Time::zero();
}

des::Time CameraRigParams::display_offset() const {
  return shutter == Shutter::rolling ? des::Time::from_seconds(readout.to_seconds() * display_row) : des::Time::zero();
}

RigResult film(const FilmedSignal& object, const FilmedSignal& display, const des::PeriodicSchedule& camera,
               des::Time exposure, des::Time end, const CameraRigParams& p) {
  RigResult result;
  const double frame_ms = camera.period().to_seconds() * 1e3;
  result.resolution_ms = frame_ms / 2.0;
  const int64_t first = camera.index_at_or_after(des::Time::zero());
  const int64_t last = camera.index_at_or_before(end - exposure);
  const int64_t n = last - first + 1;
  if (n < 2) return result;
  result.frames = n;
  const auto object_readings = readings(object, camera, first, n, exposure, p.object_offset());
  const auto d = readings(display, camera, first, n, exposure, p.display_offset());
  if (!object_readings || !d) return result;
  const std::vector<double>* r = &object_readings->value;
  std::vector<double> t_ms(static_cast<size_t>(n));
  for (int64_t k = 0; k < n; ++k) t_ms[static_cast<size_t>(k)] = camera.at(first + k).to_ms();
  const auto rest_frames = static_cast<int64_t>(std::ceil(p.rest.to_ms() / frame_ms));
  const auto shift_frames = static_cast<int64_t>(std::ceil(p.max_shift.to_ms() / frame_ms));
  const double display_threshold = p.display_threshold_deg.value_or(p.threshold_deg);
  const double tol = p.rest_tolerance_deg.value_or(std::min(p.threshold_deg, display_threshold) / 10.0);
  enum class State { Settling, Rest, Moving } state = State::Settling;
  double rest_r = 0.0, rest_d = 0.0;
  int64_t start = -1, shown = -1;
  uint64_t steps = 0;
  for (int64_t k = 0; k < n; ++k) {
    des::check_stop_every(steps, 1024);
    const double rk = (*r)[static_cast<size_t>(k)], dk = d->value[static_cast<size_t>(k)];
    if (state == State::Rest && std::abs(rk - rest_r) > p.threshold_deg) {
      state = State::Moving;
      start = k;
      shown = -1;
    }
    if (state == State::Moving && shown < 0 && std::abs(dk - rest_d) > display_threshold) shown = k;
    if (state == State::Rest || !steady(*r, d->value, k, rest_frames, tol)) continue;
    if (state == State::Moving && shown >= 0) {
      result.frame_counting_ms.push_back(static_cast<double>(shown - start) * frame_ms);
      const std::optional<double> s = trajectory_shift_ms(*r, *d, t_ms, std::max<int64_t>(0, start - shift_frames), k,
                                                          frame_ms, p.max_shift.to_ms());
      if (s) result.shift_ms.push_back(*s);
    }
    state = State::Rest;
    rest_r = rk;
    rest_d = dk;
  }
  return result;
}

std::vector<LitAngle> lit_angles(std::span<const ShownSample> shown, const glm::dquat& reference,
                                 const glm::dvec3& axis) {
  std::vector<LitAngle> out;
  out.reserve(shown.size());
  double last = 0.0;
  for (const ShownSample& s : shown) {
    const des::Time on = s.photon - des::Time::ps(s.lit.ticks() / 2);
    const double before = out.empty() ? twist_deg(reference, s.orientation, axis) : last;
    last = unwrap_near(twist_deg(reference, s.orientation, axis), last);
    out.push_back(LitAngle{on, on + s.lit, last, s.written, before});
  }
  return out;
}

}  // namespace latsim::measurement

namespace latsim::measurement {

std::vector<LitAngle> motion_flags(std::span<const LitAngle> lit, double threshold_deg, int behind) {
  std::vector<LitAngle> out;
  out.reserve(lit.size());
  double previous_flag = 0.0;
  const auto b = static_cast<size_t>(std::max(0, behind));
  for (size_t i = 0; i < lit.size(); ++i) {
    const bool moved = i > b && std::abs(lit[i - b].angle_deg - lit[i - b - 1].angle_deg) > threshold_deg;
    const double flag = moved ? 1.0 : 0.0;
    out.push_back(LitAngle{lit[i].on, lit[i].off, flag, lit[i].written, previous_flag});
    previous_flag = flag;
  }
  return out;
}

double calibrated_flag_threshold(std::span<const LitAngle> lit, des::Time until, double factor) {
  double largest = 0.0;
  for (size_t i = 1; i < lit.size() && lit[i].on < until; ++i)
    largest = std::max(largest, std::abs(lit[i].angle_deg - lit[i - 1].angle_deg));
  return factor * largest;
}

}  // namespace latsim::measurement
