// Carrying tracker records to the host application: links and the host's mailbox.
#pragma once

#include <cstdint>
#include <deque>
#include <optional>
#include <string>

#include "latsim/des/time.hpp"
#include "latsim/tracker/tracker.hpp"

namespace latsim::tracker {

/// A link from the tracker to the host application: given when a record
/// starts leaving the tracker, says when the application can see it. Links
/// keep state (a busy line, a busy interrupt handler), so records must be
/// passed in order of non-decreasing ready time.
class Transport {
 public:
  virtual ~Transport() = default;
  /// When the host application can see the record; throws std::logic_error
  /// if ready_at is earlier than the previous call's.
  virtual des::Time deliver(des::Time ready_at) = 0;
  virtual std::string name() const = 0;
};

/// An ideal link: the application sees each record the instant it is ready.
class DirectLink final : public Transport {
 public:
  des::Time deliver(des::Time ready_at) override;
  std::string name() const override { return "direct"; }

 private:
  std::optional<des::Time> last_ready_at_;
};

/// Settings of SerialLink.
struct SerialLinkParams {
  enum HostMode { Poll, Interrupt };

  int64_t record_bytes = 32;
  /// Bits on the wire per byte: start + 8 data + stop = 10.
  int64_t bits_per_byte = 10;
  double baud = 19200.0;
  HostMode host_mode = Poll;
  /// Poll mode: the kernel looks at the port every poll_interval, first at poll_phase.
  des::Time poll_interval = des::Time::ms(30);
  des::Time poll_phase;
  /// Interrupt mode: handler time per received character.
  des::Time per_char_interrupt_cost;
};

/// An asynchronous serial line. A record takes record_bytes * bits_per_byte /
/// baud seconds to transmit and cannot start before the previous record has
/// finished (records queue on the line). In poll mode the application sees a
/// record at the first kernel poll at or after its last character arrived;
/// in interrupt mode every character raises an interrupt whose handler takes
/// per_char_interrupt_cost (handlers run one at a time), and the record is
/// visible when the handler of its last character returns.
class SerialLink final : public Transport {
 public:
  explicit SerialLink(SerialLinkParams params);
  des::Time deliver(des::Time ready_at) override;
  std::string name() const override { return "serial"; }
  /// Wire time of one character and of one record (rounded to the tick; the
  /// rounding never accumulates because arrival times come from an index).
  des::Time character_time() const { return character_time_; }
  des::Time transmit_time() const { return transmit_time_; }
  const SerialLinkParams& params() const { return params_; }

 private:
  des::Time arrival_of_character(des::Time record_start, int64_t i) const;

  SerialLinkParams params_;
  des::Time character_time_;
  des::Time transmit_time_;
  des::PeriodicSchedule polls_;
  std::optional<des::Time> line_free_at_;
  std::optional<des::Time> handler_free_at_;
  std::optional<des::Time> last_ready_at_;
};

/// The host's view of arrived samples. Records are posted with the time the
/// application can see them; a read at time t returns the newest sample (the
/// highest index) visible by then, so a poll that finds several records
/// yields the newest, and a read with nothing new returns the last sample
/// again. Samples that can never be returned again are dropped, keeping
/// memory bounded by the records still in flight.
class SampleMailbox {
 public:
  /// Posts a sample that becomes visible at `at` (may be in the future of
  /// earlier reads; posts need not be in time order).
  void deliver(const TrackerSample& sample, des::Time at);
  /// The newest sample visible at time t, if any; changes nothing.
  std::optional<TrackerSample> newest_at(des::Time t) const;
  /// newest_at(now), then forgets everything older than it: the caller
  /// promises not to read before `now` again.
  std::optional<TrackerSample> read(des::Time now);
  /// Samples that became visible but were superseded before any read
  /// returned them (records a poll swallowed), counted by read().
  int64_t skipped_count() const { return skipped_; }
  /// Entries currently held (for tests of the memory bound).
  size_t held() const { return entries_.size(); }

 private:
  struct Entry {
    des::Time visible_at;
    TrackerSample sample;
  };
  // Sorted by visible_at with strictly increasing sample index: an entry that
  // is not newer than one visible no later than it could never be returned.
  std::deque<Entry> entries_;
  int64_t last_read_index_ = 0;
  bool any_read_ = false;
  int64_t skipped_ = 0;
};

}  // namespace latsim::tracker
