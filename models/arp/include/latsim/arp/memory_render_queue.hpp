// Renderers as a resource for display-memory updates: a queue ordered by
// memory (fastest first) and request time, a fixed number of renderers taking
// from its head, and presentation of finished images in request order per
// memory and never before the images they were drawn against.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <set>
#include <vector>

#include "latsim/des/simulator.hpp"
#include "latsim/stats/stats.hpp"

namespace latsim::arp {

/// Schedules display-memory renders on `renderers` renderers and decides when
/// each finished image may be presented.
///
/// Order: a free renderer takes the waiting request of the fastest memory;
/// among equals, the one waiting longest. A request that an image of a
/// faster memory must be presented with (see below) is served at that
/// memory's priority (priority inheritance), so a slow memory that a group
/// waits for cannot hold the fast memory's images back behind its own newer
/// requests.
///
/// Overload policy: a memory has at most one request waiting. A new request
/// for a memory whose previous request has not started yet replaces it and
/// keeps its place in the queue and the older one's presentation ties
/// (below): the older one is skipped (counted, never
/// drawn), since drawing a position the user has already left is wasted
/// work. A request for a memory being drawn is served like any other (by
/// another renderer, if one is free); its image is presented after the one
/// in progress. Overload thus
/// lowers update rates, slowest memories first, and shows as queueing time.
///
/// Presentation: an image is presented when its render has finished, every
/// earlier request of its memory is presented or skipped, and every image it
/// names in `present_after` (the newest request of those memories at the time
/// of the request, or a later one) is presented at the same instant or
/// earlier. Images that name each other (an object moving between two
/// memories) are presented together, so nothing is ever shown twice or missing.
class MemoryRenderQueue {
 public:
  /// One display-memory update asked for.
  struct Update {
    int memory = 0;
    des::Time cost;                ///< how long a renderer takes for it
    std::vector<int> present_after;  ///< memories whose newest request must be shown no later
  };
  /// What becomes of requests: (memory, request id), or for a presentation
  /// the batch of requests presented at the same instant, in request order.
  struct Listener {
    std::function<void(int, int64_t)> started;
    std::function<void(int, int64_t)> finished;
    std::function<void(const std::vector<std::pair<int, int64_t>>&)> presented;
    std::function<void(int, int64_t)> skipped;
  };

  /// `kind` names the render-completion events; renderers >= 1, memory_count >= 1.
  MemoryRenderQueue(des::Simulator& sim, des::KindId kind, int renderers, int memory_count, Listener listener);
  MemoryRenderQueue(const MemoryRenderQueue&) = delete;  // pending events refer to this object
  MemoryRenderQueue& operator=(const MemoryRenderQueue&) = delete;

  /// Requests updates decided at the same instant; returns their ids (increasing
  /// in the order given). A memory may appear at most once per call.
  std::vector<int64_t> request(const std::vector<Update>& updates);

  /// The id the next request will get.
  int64_t next_id() const { return next_id_; }
  int renderers() const { return renderers_; }
  int memory_count() const { return static_cast<int>(memories_.size()); }
  /// Request (of the first request a started one replaced) to start of every
  /// render started so far, in milliseconds.
  const stats::Distribution& queue_ms() const { return queue_ms_; }
  int64_t skipped(int memory) const { return memories_.at(static_cast<size_t>(memory)).skipped; }
  int64_t finished(int memory) const { return memories_.at(static_cast<size_t>(memory)).finished; }
  /// Renderer time spent up to now, renders in progress included.
  des::Time busy_time() const;
  /// busy_time over (renderers x elapsed), 0 when no time has elapsed.
  double utilisation(des::Time elapsed) const;
  /// Requests not yet presented or skipped (waiting, rendering or finished).
  size_t unresolved() const { return jobs_.size(); }

 private:
  enum class State { waiting, rendering, finished };
  struct Job {
    int memory = 0;
    des::Time cost;
    des::Time queued;  // when its memory's waiting request was first made
    des::Time started;
    State state = State::waiting;
    std::vector<std::pair<int, int64_t>> after;  // (memory, request id) shown no later
  };
  struct Memory {
    int64_t waiting = -1;     // its request not started yet, if any
    int64_t presented = -1;   // newest request presented
    int64_t newest = -1;      // newest request made
    int64_t skipped = 0;
    int64_t finished = 0;
  };

  void dispatch();
  std::vector<int> inherited_priorities() const;
  void finish(int64_t id);
  void present_ready();
  bool presentable(int64_t id, const std::set<int64_t>& candidates) const;

  des::Simulator& sim_;
  des::KindId kind_;
  int renderers_;
  int idle_;
  Listener listener_;
  std::vector<Memory> memories_;
  std::map<int64_t, Job> jobs_;  // unresolved requests by id
  int64_t next_id_ = 0;
  des::Time busy_done_;                                 // renderer time of finished renders
  stats::Distribution queue_ms_;
};

}  // namespace latsim::arp
