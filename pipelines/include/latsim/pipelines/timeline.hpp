// A stage timeline: which unit ran which stage of which frame, and when.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "latsim/des/time.hpp"

namespace latsim::pipelines {

/// Stage intervals of a pipeline, written as timeline.csv and as Chrome
/// trace-event JSON (timeline.json, opens in Perfetto / chrome://tracing).
class Timeline {
 public:
  struct Entry {
    std::string stage;  ///< e.g. "SEND", "EDIT", "TRANSFORM", "RENDER", "COPY"
    int64_t frame;
    int eye;            ///< -1 when the stage covers both eyes
    std::string unit;   ///< e.g. "GP3", "R1", "ring", "FB0"
    des::Time start;
    des::Time end;
  };

  /// Keeps at most `max_entries` (0 = no limit); later entries are counted, not kept.
  void set_max_entries(size_t max_entries) { max_entries_ = max_entries; }
  size_t dropped() const { return dropped_; }
  void add(std::string stage, int64_t frame, int eye, std::string unit, des::Time start, des::Time end);
  const std::vector<Entry>& entries() const { return entries_; }
  /// Hash of all entries in order (for fingerprint tests).
  uint64_t fingerprint() const;
  /// timeline.csv: one row per interval.
  std::string csv() const;
  /// timeline.json: Chrome trace events.
  std::string trace_json() const;

 private:
  std::vector<Entry> entries_;
  size_t max_entries_ = 0;
  size_t dropped_ = 0;
};

}  // namespace latsim::pipelines
