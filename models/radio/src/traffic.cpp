#include "latsim/radio/traffic.hpp"

#include <stdexcept>

namespace latsim::radio {

TrafficSource::TrafficSource(des::Simulator& sim, Bss& bss, TrafficParams params, des::RandomStream stream)
    : sim_(sim), bss_(bss), p_(params), stream_(std::move(stream)) {
  if (!(p_.rate_bps > 0.0) || p_.packet_bytes <= 0) throw std::invalid_argument("traffic needs a rate and a packet size");
  kind_ = sim_.kind("radio.traffic");
  gap_s_ = 8.0 * static_cast<double>(p_.packet_bytes) / p_.rate_bps;
}

void TrafficSource::start(des::Time start, des::Time end) {
  start_ = start;
  end_ = end;
  next_ = p_.arrivals == TrafficParams::Arrivals::poisson ? start + des::Time::from_seconds(stream_.exponential(gap_s_))
                                                          : start;
  if (next_ < end_) sim_.at(next_, kind_, [this] { arrive(); });
}

void TrafficSource::arrive() {
  bss_.send(p_.from, p_.to, p_.packet_bytes, sent_);
  ++sent_;
  if (p_.arrivals == TrafficParams::Arrivals::poisson)
    next_ = sim_.now() + des::Time::from_seconds(stream_.exponential(gap_s_));
  else
    next_ = start_ + des::Time::from_seconds(gap_s_ * static_cast<double>(sent_));
  if (next_ < end_) sim_.at(next_, kind_, [this] { arrive(); });
}

}  // namespace latsim::radio
