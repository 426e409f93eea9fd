// Other traffic on the channel: a station sending packets of a fixed size
// at random (Poisson) or regular instants, the load the headset's stream
// shares the channel with.
#pragma once

#include <cstdint>

#include "latsim/des/random.hpp"
#include "latsim/des/simulator.hpp"
#include "latsim/radio/bss.hpp"

namespace latsim::radio {

/// One flow of background packets.
struct TrafficParams {
  enum class Arrivals { poisson, constant };
  int from = 0;
  int to = 0;
  double rate_bps = 0.0;       ///< offered load (IP datagrams)
  int64_t packet_bytes = 1500;
  Arrivals arrivals = Arrivals::poisson;
};

/// Sends a flow's packets into a Bss from `start` until `end`: exponential
/// gaps of mean packet_bits / rate (Poisson), or exactly that gap
/// (constant, the n-th packet at start + n · gap, from its index).
class TrafficSource {
 public:
  TrafficSource(des::Simulator& sim, Bss& bss, TrafficParams params, des::RandomStream stream);
  TrafficSource(const TrafficSource&) = delete;
  TrafficSource& operator=(const TrafficSource&) = delete;

  void start(des::Time start, des::Time end);
  int64_t sent() const { return sent_; }

 private:
  void arrive();

  des::Simulator& sim_;
  Bss& bss_;
  TrafficParams p_;
  des::RandomStream stream_;
  des::KindId kind_ = 0;
  des::Time start_, end_;
  double gap_s_ = 0.0;
  int64_t sent_ = 0;
  des::Time next_;
};

}  // namespace latsim::radio
