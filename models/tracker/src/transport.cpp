#include "latsim/tracker/transport.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

namespace latsim::tracker {

namespace {

void check_order(std::optional<des::Time>& last, des::Time ready_at) {
  if (last && ready_at < *last)
    throw std::logic_error("transport records must be delivered in order of ready time (" + ready_at.str() +
                           " after " + last->str() + ")");
  last = ready_at;
}

}  // namespace

des::RationalSeconds exact_period(des::Time interval) {
  const int64_t g = std::gcd(interval.ticks(), des::Time::kTicksPerSecond);
  return des::RationalSeconds{interval.ticks() / g, des::Time::kTicksPerSecond / g};
}

des::Time Transport::deliver(des::Time ready_at) {
  check_order(last_ready_at_, ready_at);
  const des::Time start = free_at_ ? std::max(ready_at, *free_at_) : ready_at;
  free_at_ = start + occupancy();
  return carry(start).visible;
}

SerialLink::SerialLink(SerialLinkParams params) : params_(params) {
  if (params.record_bytes < 1) throw std::invalid_argument("serial record must be at least one byte");
  if (params.bits_per_byte < 1) throw std::invalid_argument("serial bits per byte must be at least one");
  if (!(params.baud > 0.0) || !std::isfinite(params.baud)) throw std::invalid_argument("baud rate must be positive");
  if (params.buffer_records < 1) throw std::invalid_argument("a serial line buffers at least one record");
  if (params.per_char_interrupt_cost < des::Time::zero())
    throw std::invalid_argument("per-character interrupt cost is negative");
  if (params.host_mode == SerialLinkParams::Poll) {
    if (params.poll_interval <= des::Time::zero()) throw std::invalid_argument("poll interval must be positive");
    polls_ = des::PeriodicSchedule(params.poll_clock.phase.value_or(des::Time::zero()),
                                   des::period_with_rate_error(exact_period(params.poll_interval),
                                                               params.poll_clock.rate_error_ppm));
  }
  character_time_ = arrival_of_character(des::Time::zero(), 1);
  transmit_time_ = arrival_of_character(des::Time::zero(), params.record_bytes);
}

des::Time SerialLink::arrival_of_character(des::Time record_start, int64_t i) const {
  // Character i (1-based) has fully arrived after i * bits_per_byte bit times.
  // At a whole baud rate the instant is the exact one floored to the tick,
  // as periodic times are: 32 bytes at 19200 baud then take no longer than a
  // 60 Hz tracker period, and keep up with it, as they do on the real line.
  const double baud = params_.baud;
  if (baud == std::floor(baud) && baud < 1e15) {
    const __int128 bits = static_cast<__int128>(i) * params_.bits_per_byte;
    return record_start +
           des::Time::ps(static_cast<int64_t>(bits * des::Time::kTicksPerSecond / static_cast<int64_t>(baud)));
  }
  const double bits = static_cast<double>(i) * static_cast<double>(params_.bits_per_byte);
  return record_start + des::Time::from_seconds(bits / baud);
}

Carriage SerialLink::carry(des::Time start) {
  if (last_start_ && start < *last_start_)
    throw std::logic_error("serial records must be carried in order of start (" + start.str() + " after " +
                           last_start_->str() + ")");
  last_start_ = start;
  const des::Time end = arrival_of_character(start, params_.record_bytes);
  if (params_.host_mode == SerialLinkParams::Poll) return Carriage{start, end, polls_.at(polls_.index_at_or_after(end))};
  if (params_.per_char_interrupt_cost == des::Time::zero()) return Carriage{start, end, end};
  // Each character's handler starts when the character is in and the
  // previous handler has returned; a cost above the character time makes
  // handlers back up, and the backlog carries over to the next record.
  des::Time handler_done = handler_free_at_.value_or(start);
  for (int64_t i = 1; i <= params_.record_bytes; ++i)
    handler_done = std::max(arrival_of_character(start, i), handler_done) + params_.per_char_interrupt_cost;
  handler_free_at_ = handler_done;
  return Carriage{start, end, handler_done};
}

UsbHidLink::UsbHidLink(UsbHidParams params, des::RandomStream stream) : params_(params), stream_(stream) {
  if (params_.poll_hz <= 0 || params_.poll_hz > 8000)
    throw std::invalid_argument("a USB poll rate is between 1 and 8000 Hz");
  if (params_.os_delay < des::Time::zero() || params_.os_jitter < des::Time::zero())
    throw std::invalid_argument("operating system delays must not be negative");
  polls_ = des::PeriodicSchedule(params_.poll_clock.phase.value_or(des::Time::zero()),
                                 des::period_with_rate_error(des::RationalSeconds{1, params_.poll_hz},
                                                             params_.poll_clock.rate_error_ppm));
}

Carriage UsbHidLink::carry(des::Time start) {
  if (any_ && start < last_start_)
    throw std::logic_error("USB reports must be carried in order of start (" + start.str() + " after " +
                           last_start_.str() + ")");
  last_start_ = start;
  const int64_t poll = polls_.index_at_or_after(start);
  // One draw per poll: every report a poll carries reaches the application together.
  if (!any_ || poll != last_poll_) {
    des::Time extra;
    if (params_.os_jitter > des::Time::zero()) {
      const double j = static_cast<double>(params_.os_jitter.ticks());
      const double x = params_.os_jitter_shape == UsbHidParams::DelayShape::Uniform ? stream_.uniform(0.0, j)
                                                                                   : stream_.exponential(j);
      extra = des::Time::ps(static_cast<int64_t>(std::llround(x)));
    }
    last_delay_ = params_.os_delay + extra;
    last_poll_ = poll;
    any_ = true;
  }
  const des::Time transfer = polls_.at(poll);
  // The operating system hands reports over in the order they crossed: a
  // short draw never lets a later poll overtake an earlier one.
  last_visible_ = std::max(last_visible_, transfer + last_delay_);
  return Carriage{start, transfer, last_visible_};
}

}  // namespace latsim::tracker
