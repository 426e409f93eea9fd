// A stage timeline: which unit ran which stage of which frame, and when.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "latsim/des/time.hpp"
#include "latsim/results/run_files.hpp"

namespace latsim::results {

/// Stage intervals of a pipeline, written as timeline.csv and as Chrome
/// trace-event JSON (timeline.json, opens in Perfetto / chrome://tracing).
///
/// Intervals of one unit that overlap (frames in flight, a warp preempting a
/// stage) go to separate lanes of the unit, so that the intervals of one
/// lane (one track of the JSON, one row of a Gantt chart) are disjoint: an
/// interval takes the first lane whose intervals all end by its start.
/// Besides intervals, the JSON holds counter tracks (add_counter) and flow
/// arrows from a pose sample to the first photon of an image (add_flow).
///
/// Entries are kept in memory until stream_to() is given the run's files;
/// from then on each entry goes straight to both files (under temporary names
/// until finish() renames them), so a run's memory does not grow with its length.
class Timeline {
 public:
  enum class Kind { interval, counter, flow };
  struct Entry {
    std::string stage;  ///< e.g. "SEND", "EDIT", "TRANSFORM", "RENDER", "COPY"; a counter's name
    int64_t frame;      ///< a flow's id
    int eye;            ///< -1 when the stage covers both eyes
    std::string unit;   ///< e.g. "GP3", "R1", "ring", "FB0"; a flow's origin unit
    des::Time start;
    des::Time end;      ///< a counter's: its time again; a flow's: its arrival
    Kind kind = Kind::interval;
    double value = 0;   ///< a counter's value
    std::string to_unit;  ///< a flow's arrival unit
  };


  /// Accepts at most `max_entries` (0 = no limit); later entries are counted, not kept.
  void set_max_entries(size_t max_entries) { max_entries_ = max_entries; }
  size_t dropped() const { return dropped_; }
  void add(std::string_view stage, int64_t frame, int eye, std::string_view unit, des::Time start, des::Time end);
  /// A sample of counter `name` (a counter track of the JSON only).
  void add_counter(std::string_view name, des::Time at, double value);
  /// A pose-to-photon arrow (JSON only) from a zero-length SAMPLE mark on
  /// `from_unit` at `from` (the pose's measurement) to a zero-length PHOTON
  /// mark on `to_unit` at `to` (its image's first photon); `id` names the
  /// arrow and must be unique in the run.
  void add_flow(int64_t id, std::string_view from_unit, des::Time from, std::string_view to_unit, des::Time to);
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
    void write(const Entry& e);
    void write(std::string_view stage, int64_t frame, int eye, std::string_view unit, des::Time start, des::Time end);
    void write_counter(std::string_view name, des::Time at, double value);
    void write_flow(int64_t id, std::string_view from_unit, des::Time from, std::string_view to_unit, des::Time to);
    void finish(RunFiles& files);
    bool is_open() const { return csv_.is_open(); }

   private:
    // One track of the JSON: a lane of a unit, and the latest end of its intervals.
    struct Track {
      std::string unit;
      int lane;
      int tid;
      des::Time max_end;
    };
    // The track an interval [start, end] of `unit` goes to (opened, and
    // named in the JSON, when no lane of the unit is free by `start`).
    const Track& track_for(std::string_view unit, des::Time start, des::Time end, char*& p);
    void separator(char*& p);

    StreamedFile csv_, json_;
    std::vector<Track> tracks_;  // in order of appearance
    std::vector<std::string> units_;  // in order of appearance: the JSON's sort order
    int counters_tid_ = 0;
    bool first_event_ = true;
    std::string buffer_;  // one formatted entry, reused (its size is what is reserved, not what is used)
  };

  // Counts an entry, or the one the limit drops (false).
  bool accept();
  // The files' writer, opened on first use; nullptr while entries are held.
  Writer* stream();

  std::vector<Entry> entries_;
  size_t max_entries_ = 0;
  size_t dropped_ = 0;
  size_t accepted_ = 0;
  RunFiles* files_ = nullptr;  // set by stream_to()
  Writer stream_;
};

}  // namespace latsim::results
