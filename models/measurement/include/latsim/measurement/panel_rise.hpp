// How a panel's pixel goes from its old value to its new one, as a camera
// filming it sees it: at once, along a line (OLED) or along an exponential
// (an LCD's liquid crystal settling, specified by its grey-to-grey time).
#pragma once

#include "latsim/des/time.hpp"

namespace latsim::measurement {

/// The transition of a written pixel.
struct PanelRise {
  enum class Curve {
    step,         ///< the new value at once (the lit interval already waits for the response)
    linear,       ///< from 0 to 1 over `response` (OLED)
    exponential,  ///< 1 - exp(-t / tau), 10 % to 90 % in `response` (LCD grey to grey): tau = response / ln 9
  };
  Curve curve = Curve::step;
  des::Time response;

  /// How far a pixel written `since` ago has gone from its old value to its new one, in [0, 1].
  double fraction(des::Time since) const;
};

}  // namespace latsim::measurement
