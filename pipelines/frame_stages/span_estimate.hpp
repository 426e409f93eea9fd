// Late scheduling's estimate of how long a span of stages will take.
#pragma once

#include <deque>

#include "latsim/des/time.hpp"

namespace latsim::pipelines::frame_stages {

/// The longest of a span's nominal length and its last `window` measured
/// lengths: late scheduling starts the span that long before its deadline, so
/// a span that once ran long is given that much room again for a while.
class SpanEstimate {
 public:
  SpanEstimate(des::Time nominal, int window) : nominal_(nominal), window_(window) {}

  des::Time estimate() const {
    des::Time e = nominal_;
    for (des::Time m : recent_) e = m > e ? m : e;
    return e;
  }
  void add(des::Time measured) {
    if (window_ <= 0) return;
    recent_.push_back(measured);
    if (static_cast<int>(recent_.size()) > window_) recent_.pop_front();
  }

 private:
  des::Time nominal_;
  int window_;
  std::deque<des::Time> recent_;
};

}  // namespace latsim::pipelines::frame_stages
