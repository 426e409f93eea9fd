#include <algorithm>

#include "frame_stages/pacing_runtimes.hpp"

namespace latsim::pipelines::frame_stages {

void RuntimeThrottle::frame(bool late, bool early) {
  recent_.push_back(late);
  if (static_cast<int>(recent_.size()) > p_.window) recent_.pop_front();
  if (level_ < p_.max_level && std::count(recent_.begin(), recent_.end(), true) >= p_.late_threshold) {
    ++level_;
    ++raised_;
    recent_.clear();
    early_run_ = 0;
    return;
  }
  early_run_ = early && !late ? early_run_ + 1 : 0;
  if (level_ > 0 && early_run_ >= p_.early_frames) {
    --level_;
    recent_.clear();
    early_run_ = 0;
  }
}

}  // namespace latsim::pipelines::frame_stages
