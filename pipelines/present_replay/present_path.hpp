// How a presented frame reaches the screen on a Windows desktop, as the
// present modes PresentMon names behave: a flip queue paced by the sync
// interval, the newest frame at each refresh, or a flip at once (tearing),
// directly or through the desktop compositor (docs/measured.md, "Replay").
#pragma once

#include <cstdint>
#include <deque>
#include <optional>
#include <vector>

#include "latsim/des/time.hpp"

namespace latsim::pipelines::present_replay {

/// The rules of one present path.
struct PresentPathSpec {
  enum class Show {
    queued,     ///< in present order, each on screen for at least sync_interval refreshes (a flip queue with vsync)
    newest,     ///< at each refresh the newest ready frame; older ready ones are discarded (sync interval 0
                ///< without tearing, or a copy into the compositor's surface)
    immediate,  ///< as soon as its GPU work is done, mid-scan (sync interval 0 with tearing allowed)
  };
  Show show = Show::queued;
  int sync_interval = 1;       ///< queued: refreshes a frame stays on screen at least
  bool composed = false;       ///< the desktop compositor shows the frame it takes at a refresh one refresh later
  int max_frame_latency = 3;   ///< frames presented and not yet taken; a Present beyond waits (DXGI's default: 3)
};

/// The present path's state: frames presented, ready, taken at refreshes,
/// discarded. Pure bookkeeping: the pipeline calls it at the events.
class PresentPath {
 public:
  explicit PresentPath(PresentPathSpec spec) : spec_(spec) {}

  /// Frame `frame` was presented (its GPU work may still run).
  void presented(int64_t frame);
  /// Its GPU work ended at `t`. Immediate: it is taken now (returns true).
  bool ready(int64_t frame, des::Time t);
  /// What a retrace does.
  struct Retrace {
    std::optional<int64_t> show;     ///< the frame scanned out from this retrace on
    std::vector<int64_t> taken;      ///< frames taken at this retrace (composed: shown at the next)
    std::vector<int64_t> discarded;  ///< frames passed over for a newer one: never displayed
  };
  /// At a retrace at `t`: which frame goes on screen, which are taken or passed over.
  Retrace retrace(des::Time t);
  /// Whether more frames are presented and not yet taken than max_frame_latency
  /// allows: the Present of the newest waits until one is.
  bool blocks() const { return static_cast<int>(waiting_.size()) > spec_.max_frame_latency; }
  const PresentPathSpec& spec() const { return spec_; }
  /// Frames presented and not yet taken nor passed over.
  int waiting() const { return static_cast<int>(waiting_.size()); }

 private:
  struct Waiting {
    int64_t frame = -1;
    std::optional<des::Time> ready;
  };

  PresentPathSpec spec_;
  std::deque<Waiting> waiting_;          ///< presented, not yet taken nor discarded
  std::optional<int64_t> composing_;     ///< composed: taken at the last retrace, shown at this one
  bool on_screen_ = false;
  int refreshes_shown_ = 0;              ///< refreshes the frame on screen (or last taken) has had
};

}  // namespace latsim::pipelines::present_replay
