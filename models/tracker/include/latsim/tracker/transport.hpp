// Carrying tracker records to the host application: links and the host's mailbox.
#pragma once

#include <cstdint>
#include <deque>
#include <optional>
#include <string>

#include "latsim/des/clock.hpp"
#include "latsim/des/random.hpp"
#include "latsim/des/time.hpp"
#include "latsim/tracker/tracker.hpp"

namespace latsim::tracker {

/// A whole number of picoseconds as an exact rational number of seconds.
des::RationalSeconds exact_period(des::Time interval);

/// When one record crossed a link: it started to leave the tracker, its last
/// character arrived at the host, and the host application could see it.
struct Carriage {
  des::Time start;
  des::Time end;
  des::Time visible;
};

/// A link from the tracker to the host application. A record occupies the
/// link for occupancy() from its start; records that find the link busy wait
/// in a buffer of buffer_records() (the caller keeps that queue: see
/// run::TrackerHost). Links keep state (a busy interrupt handler), so
/// records must be carried in order of start.
class Transport {
 public:
  virtual ~Transport() = default;
  /// The record that starts leaving at `start`, the link being free then.
  virtual Carriage carry(des::Time start) = 0;
  /// How long one record holds the link (zero: records never wait).
  virtual des::Time occupancy() const { return des::Time::zero(); }
  /// Records that may wait behind the one on the link; a newer one arriving
  /// at a full buffer pushes the oldest waiting record out (drop-oldest).
  virtual int64_t buffer_records() const { return 1; }
  virtual std::string name() const = 0;

  /// With an unbounded buffer: when the host application can see a record
  /// ready at `ready_at`. Throws std::logic_error if ready_at is earlier than
  /// the previous call's.
  des::Time deliver(des::Time ready_at);

 private:
  std::optional<des::Time> last_ready_at_;
  std::optional<des::Time> free_at_;
};

/// An ideal link: the application sees each record the instant it is ready.
class DirectLink final : public Transport {
 public:
  Carriage carry(des::Time start) override { return Carriage{start, start, start}; }
  std::string name() const override { return "direct"; }
};

/// Settings of SerialLink.
struct SerialLinkParams {
  enum HostMode { Poll, Interrupt };

  int64_t record_bytes = 32;
  /// Bits on the wire per byte: start + 8 data + stop = 10.
  int64_t bits_per_byte = 10;
  double baud = 19200.0;
  /// Records that may wait for the line behind the one being sent; when a
  /// newer record arrives to a full buffer the oldest waiting one is dropped.
  int64_t buffer_records = 8;
  HostMode host_mode = Poll;
  /// Poll mode: the kernel looks at the port every poll_interval (nominal),
  /// first at the poll clock's phase (none: 0; a run draws one), the
  /// interval corrected by the clock's rate error.
  des::Time poll_interval = des::Time::ms(30);
  des::ClockSettings poll_clock;
  /// Interrupt mode: handler time per received character.
  des::Time per_char_interrupt_cost;
};

/// An asynchronous serial line. A record takes record_bytes * bits_per_byte /
/// baud seconds to transmit. In poll mode the application sees a record at
/// the first kernel poll at or after its last character arrived; in
/// interrupt mode every character raises an interrupt whose handler takes
/// per_char_interrupt_cost (handlers run one at a time), and the record is
/// visible when the handler of its last character returns.
class SerialLink final : public Transport {
 public:
  explicit SerialLink(SerialLinkParams params);
  Carriage carry(des::Time start) override;
  des::Time occupancy() const override { return transmit_time_; }
  int64_t buffer_records() const override { return params_.buffer_records; }
  std::string name() const override { return "serial"; }
  /// Wire time of one character and of one record (rounded to the tick; the
  /// rounding never accumulates because arrival times come from an index).
  des::Time character_time() const { return character_time_; }
  des::Time transmit_time() const { return transmit_time_; }
  /// Interrupt mode: handler time for one record's characters.
  des::Time handler_time() const { return params_.per_char_interrupt_cost * params_.record_bytes; }
  const SerialLinkParams& params() const { return params_; }

 private:
  des::Time arrival_of_character(des::Time record_start, int64_t i) const;

  SerialLinkParams params_;
  des::Time character_time_;
  des::Time transmit_time_;
  des::PeriodicSchedule polls_;
  std::optional<des::Time> handler_free_at_;
  std::optional<des::Time> last_start_;
};

/// Settings of UsbHidLink.
struct UsbHidParams {
  enum class DelayShape { Uniform, Exponential };
  /// The host controller polls the device's interrupt endpoint this often
  /// (bInterval: 125, 250, 500 or 1000 Hz for today's trackers).
  int64_t poll_hz = 1000;
  des::ClockSettings poll_clock;  ///< the host controller's frame clock
  /// From the transfer to the application: a fixed part, plus a random part
  /// drawn once per poll, uniform on [0, os_jitter] or exponential of mean os_jitter.
  des::Time os_delay;
  des::Time os_jitter;
  DelayShape os_jitter_shape = DelayShape::Uniform;
};

/// A USB HID device polled by the host: a report ready at t crosses at the
/// first poll at or after t (a report waits in the device's endpoint; a newer
/// one found by the same poll wins, as the host reads the newest), then the
/// operating system hands it to the application os_delay plus a random part
/// later, the same for everything one poll carries. With the poll phase
/// unrelated to the reports, the wait for the poll is uniform on one poll
/// interval P: the added latency has mean P/2 + os_delay + E[jitter] and is at
/// most P + os_delay + the jitter's bound (a jitter above P can hold a poll's
/// reports behind an earlier poll's: reports are handed over in order).
class UsbHidLink final : public Transport {
 public:
  /// Throws std::invalid_argument for a poll rate outside (0, 8000] Hz or a
  /// negative delay.
  UsbHidLink(UsbHidParams params, des::RandomStream stream);
  Carriage carry(des::Time start) override;
  std::string name() const override { return "usb_hid"; }
  const UsbHidParams& params() const { return params_; }

 private:
  UsbHidParams params_;
  des::RandomStream stream_;
  des::PeriodicSchedule polls_;
  int64_t last_poll_ = 0;
  des::Time last_start_;
  des::Time last_delay_;
  des::Time last_visible_;
  bool any_ = false;
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
