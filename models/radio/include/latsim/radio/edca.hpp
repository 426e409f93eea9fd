// Contention for the medium: an EDCA function's parameters and its backoff
// counter, counted down in idle slots after its AIFS (IEEE 802.11-2020
// 10.23.2).
#pragma once

#include <cstdint>
#include <string_view>

#include "latsim/des/random.hpp"
#include "latsim/des/time.hpp"

namespace latsim::radio {

/// One access category's EDCA parameters.
struct EdcaParams {
  int aifsn = 3;         ///< slots after SIFS before the backoff may count (AIFS = SIFS + AIFSN · slot)
  int cw_min = 15;       ///< contention window after a success
  int cw_max = 1023;     ///< the window doubles (2 (CW + 1) - 1) up to this after a failure
  des::Time txop_limit;  ///< zero: one PPDU (and its response) per access

  /// The default EDCA parameter set for an OFDM PHY (802.11-2020 Table 9-155):
  /// "BK", "BE", "VI" or "VO"; throws std::invalid_argument otherwise.
  static EdcaParams for_category(std::string_view ac);
};

/// The backoff counter of one EDCA function.
///
/// The counter is decremented at every slot boundary at which the medium has
/// been idle since the function's AIFS ended, the first at the end of AIFS
/// itself; at a boundary where it is already zero the function transmits.
/// `start` is the earliest boundary from which it counts; the boundaries
/// are `counting_start(access) + k · slot`, where `access` is the instant
/// the medium counts as idle from (SIFS after the last busy instant, or
/// later after a failed reception or a missing response).
class Backoff {
 public:
  Backoff(EdcaParams params, des::Time slot) : p_(params), slot_(slot), cw_(params.cw_min) {}

  const EdcaParams& params() const { return p_; }
  int cw() const { return cw_; }
  int slots() const { return slots_; }
  des::Time start() const { return start_; }
  /// The instant counting may begin: AIFS after `access`, or `start` if later.
  des::Time counting_start(des::Time access) const;
  /// When the function transmits if the medium stays idle: its counting
  /// start plus its remaining slots.
  des::Time expiry(des::Time access) const { return counting_start(access) + slot_ * slots_; }
  /// Applies the slot boundaries at or before `now` (the medium idle up to
  /// now since `access`): each decrements the counter, to zero at most.
  void count_down(des::Time access, des::Time now);
  /// A frame arrived at an empty queue with the counter at zero: with the
  /// medium idle it may go at the next boundary after `now`; with it busy a
  /// new backoff is drawn (10.23.2.2 a).
  void on_arrival(des::Time access, des::Time now, bool medium_busy, des::RandomStream& stream);
  /// Draws a new counter uniform on [0, CW], counting from `now`.
  void draw(des::Time now, des::RandomStream& stream);
  /// After a success: CW back to its minimum.
  void reset_cw() { cw_ = p_.cw_min; }
  /// After a failure: CW doubles, up to its maximum.
  void double_cw();

 private:
  EdcaParams p_;
  des::Time slot_;
  int cw_;
  int slots_ = 0;
  des::Time start_;
};

}  // namespace latsim::radio
