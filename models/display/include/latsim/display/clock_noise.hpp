// Short-term instability of the display's oscillator: white jitter on each
// retrace and a rate that wanders as a random walk.
#pragma once

#include <cstdint>
#include <vector>

#include "latsim/des/random.hpp"
#include "latsim/des/time.hpp"

namespace latsim::display {

/// How unsteady the display clock is (both zero: a steady clock).
struct ClockNoiseParams {
  des::Time jitter_rms;               ///< standard deviation of each retrace about its clock time
  double wander_ppm_per_sqrt_s = 0.0; ///< the rate's random walk: its deviation grows as this x sqrt(seconds)
};

/// Offsets of the retraces of fields 0 .. fields-1 from a steady clock,
/// drawn once, field by field, from one random stream:
///
///   D(k) = W(k) + J(k),  W(0) = 0,  W(k+1) = W(k) + r(k) x 1e-6 x T,
///   r(0) = 0,  r(k) = r(k-1) + wander x sqrt(T) x N(0, 1)  (ppm),
///   J(k) = jitter_rms x N(0, 1), cut at ±min(4 jitter_rms, slack / 4),
///
/// T the field period in seconds. r is reflected at ±r_max = slack / (4 T)
/// (in ppm), so that, with the cut jitter, a field never starts before the
/// last pixel of the previous one was lit (|D(k+1) - D(k)| < slack, the blank
/// time after the field's last pixel). Field 0 keeps the clock's phase
/// (D(0) = 0); fields before it are not moved; fields past the table go on
/// at the last rate, without jitter. Offsets are whole ticks.
class ClockNoise {
 public:
  /// Throws std::invalid_argument for a negative jitter or wander, or a slack
  /// below 8 ticks.
  ClockNoise(ClockNoiseParams params, des::RationalSeconds period, des::Time slack, int64_t fields,
             des::RandomStream stream);

  const ClockNoiseParams& params() const { return params_; }
  /// Offset of field k's retrace from the steady clock.
  des::Time offset(int64_t field) const;
  /// The largest rate deviation the wander reaches, in ppm.
  double max_rate_ppm() const { return max_rate_ppm_; }
  /// The bound of each retrace's jitter.
  des::Time jitter_bound() const { return jitter_bound_; }

 private:
  ClockNoiseParams params_;
  double period_s_ = 0.0;
  double max_rate_ppm_ = 0.0;
  des::Time jitter_bound_;
  std::vector<int64_t> offsets_;  // ticks, index = field
  double last_wander_ps_ = 0.0;   // W of the last field of the table
  double last_rate_ppm_ = 0.0;    // r of the last field of the table
};

}  // namespace latsim::display
