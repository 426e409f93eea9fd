// A stage timeline: which unit ran which stage of which frame, and when.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "latsim/des/time.hpp"
#include "latsim/results/run_files.hpp"

namespace latsim::results {

/// Stage intervals of a pipeline, written as timeline.csv and as Chrome
/// trace-event JSON (timeline.json, opens in Perfetto / chrome://tracing).
///
/// Entries are kept in memory until stream_to() is given the run's files;
/// from then on each entry goes straight to both files (under temporary names
/// until finish() renames them), so a run's memory does not grow with its length.
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


  /// Accepts at most `max_entries` (0 = no limit); later entries are counted, not kept.
  void set_max_entries(size_t max_entries) { max_entries_ = max_entries; }
  size_t dropped() const { return dropped_; }
  void add(std::string_view stage, int64_t frame, int eye, std::string_view unit, des::Time start, des::Time end);
  /// Entries accepted so far (kept or streamed).
  size_t size() const { return accepted_; }
  /// The entries held in memory (those added before stream_to(), none after).
  const std::vector<Entry>& entries() const { return entries_; }

  /// From now on write every entry to timeline.csv and timeline.json of
  /// `files` (temporary names until finish()); entries held so far go first.
  void stream_to(RunFiles& files);
  /// Completes the streamed files and renames them into place; nothing is
  /// written when no entry was accepted.
  void finish(RunFiles& files);

 private:
  // The two output formats, written one entry at a time.
  class Writer {
   public:
    void open(RunFiles& files);
    void write(const Entry& e) { write(e.stage, e.frame, e.eye, e.unit, e.start, e.end); }
    void write(std::string_view stage, int64_t frame, int eye, std::string_view unit, des::Time start, des::Time end);
    void finish(RunFiles& files);
    bool is_open() const { return csv_.is_open(); }

   private:
    StreamedFile csv_, json_;
    std::vector<std::pair<std::string, int>> tids_;  // thread id per unit, in order of appearance
    bool first_event_ = true;
    std::string buffer_;  // one formatted entry, reused (its size is what is reserved, not what is used)
  };

  std::vector<Entry> entries_;
  size_t max_entries_ = 0;
  size_t dropped_ = 0;
  size_t accepted_ = 0;
  RunFiles* files_ = nullptr;  // set by stream_to()
  Writer stream_;
};

}  // namespace latsim::results
