#include "present_replay/present_path.hpp"

namespace latsim::pipelines::present_replay {

void PresentPath::presented(int64_t frame) { waiting_.push_back(Waiting{frame, std::nullopt}); }

bool PresentPath::ready(int64_t frame, des::Time t) {
  for (auto it = waiting_.begin(); it != waiting_.end(); ++it) {
    if (it->frame != frame) continue;
    it->ready = t;
    if (spec_.show != PresentPathSpec::Show::immediate) return false;
    waiting_.erase(it);
    return true;
  }
  return false;
}

PresentPath::Retrace PresentPath::retrace(des::Time t) {
  Retrace r;
  // The compositor's frame of the last refresh reaches the screen now.
  if (composing_) {
    r.show = composing_;
    composing_.reset();
  }
  if (on_screen_) ++refreshes_shown_;
  auto is_ready = [t](const Waiting& w) { return w.ready && *w.ready <= t; };
  std::optional<int64_t> take;
  switch (spec_.show) {
    case PresentPathSpec::Show::immediate: break;
    case PresentPathSpec::Show::queued:
      // The frame on screen keeps it for sync_interval refreshes; then the oldest ready one flips in.
      if (!waiting_.empty() && is_ready(waiting_.front()) && (!on_screen_ || refreshes_shown_ >= spec_.sync_interval)) {
        take = waiting_.front().frame;
        waiting_.pop_front();
      }
      break;
    case PresentPathSpec::Show::newest: {
      // GPU work is done in present order: the ready frames are the oldest ones.
      size_t n = 0;
      while (n < waiting_.size() && is_ready(waiting_[n])) ++n;
      if (n == 0) break;
      for (size_t i = 0; i + 1 < n; ++i) r.discarded.push_back(waiting_[i].frame);
      take = waiting_[n - 1].frame;
      waiting_.erase(waiting_.begin(), waiting_.begin() + static_cast<std::ptrdiff_t>(n));
      break;
    }
  }
  if (!take) return r;
  r.taken.push_back(*take);
  on_screen_ = true;
  refreshes_shown_ = 0;
  if (spec_.composed) composing_ = take;
  else r.show = take;
  return r;
}

}  // namespace latsim::pipelines::present_replay
