// Playing a capture column back as a sequence of durations.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "latsim/des/random.hpp"
#include "latsim/des/time.hpp"

namespace latsim::capture {

/// How a column's values are played back, and what-if changes to them.
struct ReplayParams {
  enum class Order { in_order, bootstrap };
  enum class AtEnd { wrap, stop };
  Order order = Order::in_order;
  AtEnd at_end = AtEnd::wrap;  ///< in order: after the last value, the first again, or no more values
  int64_t block_length = 32;   ///< bootstrap: consecutive values drawn together
  double scale = 1.0;          ///< each value × scale + offset_ms
  double offset_ms = 0.0;
  std::optional<double> max_ms;  ///< values (after scale and offset) above this are clipped to it
};

/// Plays back a column of durations: in order (wrapping or stopping at the
/// end) or as a circular moving-block bootstrap (Künsch 1989; circular after
/// Politis & Romano 1992): blocks of block_length consecutive values, each
/// starting at a uniformly drawn index and wrapping past the end, so every
/// value is equally likely and the autocorrelation within a block is the
/// capture's. Each value becomes value × scale + offset_ms (to the
/// picosecond), clipped to max_ms when given. The values are shared, the
/// position is this object's: copy it for a new run.
class Replay {
 public:
  /// Throws std::invalid_argument for no values, a scale below 0, a
  /// block_length outside [1, values], or a transformed value below zero.
  Replay(std::shared_ptr<const std::vector<des::Time>> values, const ReplayParams& params);

  /// The next duration; draws from `stream` (bootstrap only, once a block).
  /// In order with at_end stop, once exhausted() it returns the last value again.
  des::Time next(des::RandomStream& stream);
  /// In order with at_end stop: every value has been played.
  bool exhausted() const { return exhausted_; }
  /// The mean of the transformed values (what a frame costs on average).
  des::Time mean() const { return mean_; }
  /// Values played so far.
  int64_t played() const { return played_; }
  /// Times the in-order replay went back to the first value.
  int64_t wraps() const { return wraps_; }
  /// Values clipped to max_ms (counted once per value of the column).
  int64_t clipped_values() const { return clipped_; }
  const ReplayParams& params() const { return params_; }
  size_t size() const { return values_->size(); }

 private:
  des::Time scaled(des::Time v) const;       // × scale + offset
  des::Time transformed(des::Time v) const;  // scaled, then clipped

  std::shared_ptr<const std::vector<des::Time>> values_;
  ReplayParams params_;
  des::Time mean_;
  std::optional<des::Time> max_;
  int64_t clipped_ = 0;
  size_t next_ = 0;        // index of the next value
  int64_t block_left_ = 0;  // bootstrap: values left in the current block
  int64_t played_ = 0;
  int64_t wraps_ = 0;
  bool exhausted_ = false;
};

}  // namespace latsim::capture
