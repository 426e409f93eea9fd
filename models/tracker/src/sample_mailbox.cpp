#include <algorithm>

#include "latsim/tracker/transport.hpp"

namespace latsim::tracker {

void SampleMailbox::deliver(const TrackerSample& sample, des::Time at) {
  const auto index = sample.index;
  // Older than what the application already has: it can never be returned.
  if (any_read_ && index <= last_read_index_) {
    ++skipped_;
    return;
  }
  const bool superseded = std::any_of(entries_.begin(), entries_.end(), [&](const Entry& e) {
    return e.visible_at <= at && e.sample.index >= index;
  });
  if (superseded) {
    ++skipped_;
    return;
  }
  // Entries visible no earlier than this one and not newer are now dead.
  const auto dead = std::remove_if(entries_.begin(), entries_.end(), [&](const Entry& e) {
    return e.visible_at >= at && e.sample.index <= index;
  });
  skipped_ += static_cast<int64_t>(std::distance(dead, entries_.end()));
  entries_.erase(dead, entries_.end());

  const auto pos = std::upper_bound(entries_.begin(), entries_.end(), at,
                                    [](des::Time t, const Entry& e) { return t < e.visible_at; });
  entries_.insert(pos, Entry{at, sample});
}

std::optional<TrackerSample> SampleMailbox::newest_at(des::Time t) const {
  // Indices increase along the deque, so the last visible entry is the newest.
  const auto after = std::upper_bound(entries_.begin(), entries_.end(), t,
                                      [](des::Time v, const Entry& e) { return v < e.visible_at; });
  if (after == entries_.begin()) return std::nullopt;
  return std::prev(after)->sample;
}

std::optional<TrackerSample> SampleMailbox::read(des::Time now) {
  const auto after = std::upper_bound(entries_.begin(), entries_.end(), now,
                                      [](des::Time v, const Entry& e) { return v < e.visible_at; });
  if (after == entries_.begin()) return std::nullopt;
  const auto newest = std::prev(after);
  for (auto it = entries_.begin(); it != newest; ++it)
    if (!any_read_ || it->sample.index > last_read_index_) ++skipped_;
  const TrackerSample result = newest->sample;
  entries_.erase(entries_.begin(), newest);  // keep the newest: a later read may reuse it
  last_read_index_ = result.index;
  any_read_ = true;
  return result;
}

}  // namespace latsim::tracker
