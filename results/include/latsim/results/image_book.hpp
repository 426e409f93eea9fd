// The images of a run: every image a pipeline registers, looked up by the
// id it presents to the display, until it can no longer be shown.
#pragma once

#include <cstdint>
#include <map>

#include "latsim/results/image_record.hpp"

namespace latsim::results {

/// Images by id, in registration order. Pipelines add an image before they
/// present it; the recorders look it up for every span that shows it and
/// note when it is first shown.
class ImageBook {
 public:
  struct Held {
    ImageRecord record;
    bool shown = false;  ///< lit at least once
  };

  /// Registers an image and returns the id to present to the display.
  int64_t add(const ImageRecord& record) {
    const int64_t id = next_id_++;
    images_.emplace(id, Held{record, false});
    return id;
  }
  /// The image with `id`, nullptr when there is none (never registered, or pruned).
  const ImageRecord* find(int64_t id) const {
    const auto it = images_.find(id);
    return it == images_.end() ? nullptr : &it->second.record;
  }
  /// The same with its shown flag; consecutive lookups of one id cost a compare.
  Held* held(int64_t id) {
    if (last_held_ != nullptr && last_id_ == id) return last_held_;
    const auto it = images_.find(id);
    if (it == images_.end()) return nullptr;
    last_id_ = id;
    return last_held_ = &it->second;
  }
  /// Forgets the images below `below_id` (they will not be shown again).
  void prune(int64_t below_id) {
    while (!images_.empty() && images_.begin()->first < below_id) images_.erase(images_.begin());
    last_held_ = nullptr;
  }
  /// Images registered so far.
  int64_t registered() const { return next_id_; }

 private:
  std::map<int64_t, Held> images_;
  int64_t last_id_ = -1;
  Held* last_held_ = nullptr;  // images_[last_id_], or nullptr
  int64_t next_id_ = 0;
};

}  // namespace latsim::results
