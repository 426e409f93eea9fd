#include "latsim/radio/bss.hpp"

#include <algorithm>
#include <stdexcept>

namespace latsim::radio {

Bss::Bss(des::Simulator& sim, PhyRate phy, MacParams mac, des::RandomStream stream, const std::string& kind)
    : sim_(sim), phy_(std::move(phy)), mac_(mac), errors_(stream.substream("errors")) {
  if (mac_.slot <= des::Time::zero() || mac_.sifs <= des::Time::zero())
    throw std::invalid_argument("slot and SIFS must be positive");
  if (mac_.max_ampdu_mpdus < 1 || mac_.retry_limit < 0 || mac_.queue_packets < 1)
    throw std::invalid_argument("A-MPDU length, retry limit and queue must allow one packet");
  kind_access_ = sim_.kind(kind + ".access");
  kind_end_ = sim_.kind(kind + ".exchange");
  kind_rx_ = sim_.kind(kind + ".rx");
  kind_beacon_ = sim_.kind(kind + ".beacon");
  station_streams_ = std::make_unique<des::RandomStream>(stream.substream("stations"));
}

int Bss::add_station(const std::string& name, EdcaParams edca) {
  if (edca.aifsn < 1 || edca.cw_min < 0 || edca.cw_max < edca.cw_min)
    throw std::invalid_argument("station " + name + ": AIFSN must be at least 1 and CWmin at most CWmax");
  stations_.push_back(Station{name, Backoff(edca, mac_.slot), station_streams_->substream(name), {}, des::Time::zero()});
  return static_cast<int>(stations_.size()) - 1;
}

void Bss::set_error_rate(double per_mpdu) {
  if (!(per_mpdu >= 0.0 && per_mpdu <= 1.0)) throw std::invalid_argument("the MPDU error rate must be in [0, 1]");
  error_rate_ = per_mpdu;
}

void Bss::send_beacons(int ap, des::Time first, des::Time interval, int64_t bytes, des::Time end) {
  if (interval <= des::Time::zero() || bytes <= 0) throw std::invalid_argument("beacons need an interval and a size");
  if (beacon_station_ < 0) beacon_station_ = add_station(station_name(ap) + ".beacon", EdcaParams{1, 0, 0, {}});
  const des::PeriodicSchedule tbtt(first, des::RationalSeconds{interval.ticks(), des::Time::kTicksPerSecond});
  // Each beacon schedules the next: one pending event at a time.
  auto next = std::make_shared<std::function<void(int64_t)>>();
  *next = [this, tbtt, bytes, end, next](int64_t k) {
    Station& s = stations_[static_cast<size_t>(beacon_station_)];
    enqueue(s, Packet{next_id_++, beacon_station_, -1, bytes, k, sim_.now(), 0});
    const des::Time t = tbtt.at(k + 1);
    if (t < end) sim_.at(t, kind_beacon_, [next, k] { (*next)(k + 1); });
  };
  if (tbtt.at(0) < end) sim_.at(tbtt.at(0), kind_beacon_, [next] { (*next)(0); });
}

int64_t Bss::send(int from, int to, int64_t bytes, int64_t tag) {
  if (from < 0 || from >= stations() || to < 0 || to >= stations() || from == to)
    throw std::invalid_argument("send: no such pair of stations");
  if (bytes <= 0) throw std::invalid_argument("send: a packet has at least one byte");
  const int64_t id = next_id_++;
  enqueue(stations_[static_cast<size_t>(from)], Packet{id, from, to, bytes, tag, sim_.now(), 0});
  return id;
}

void Bss::enqueue(Station& s, Packet p) {
  if (static_cast<int64_t>(s.queue.size()) >= mac_.queue_packets) {
    ++counts_.lost;
    if (lost_) lost_(p, LossReason::queue_full);
    return;
  }
  const bool was_empty = s.queue.empty();
  s.queue.push_back(p);
  if (!was_empty) return;  // it is contending already (or transmitting)
  s.backoff.on_arrival(s.access, sim_.now(), busy_, s.stream);
  schedule_access();
}

void Bss::schedule_access() {
  if (busy_) return;
  des::Time best = des::Time::max();
  for (const Station& s : stations_)
    if (!s.queue.empty()) best = std::min(best, s.backoff.expiry(s.access));
  if (pending_access_.valid()) sim_.cancel(pending_access_);
  pending_access_ = {};
  if (best == des::Time::max()) return;
  pending_access_ = sim_.at(std::max(best, sim_.now()), kind_access_, [this] { on_access(); });
}

void Bss::drop_expired(Station& s) {
  for (size_t i = s.queue.size(); i-- > 0;)
    if (sim_.now() - s.queue[i].enqueued > mac_.queue_max_delay) lose(s, i, LossReason::expired);
}

void Bss::lose(Station& s, size_t position, LossReason why) {
  const Packet p = s.queue[position];
  s.queue.erase(s.queue.begin() + static_cast<std::ptrdiff_t>(position));
  ++counts_.lost;
  if (lost_) lost_(p, why);
}

void Bss::on_access() {
  pending_access_ = {};
  const des::Time now = sim_.now();
  std::vector<int> winners;
  for (size_t i = 0; i < stations_.size(); ++i) {
    Station& s = stations_[i];
    // Due now, or earlier: a collision's end is handled at its last
    // transmitter's timeout, after the instant the others could resume.
    const bool due = !s.queue.empty() && s.backoff.expiry(s.access) <= now;
    // Every counter sees this slot boundary before the medium turns busy.
    s.backoff.count_down(s.access, now);
    if (!due) continue;
    drop_expired(s);
    if (!s.queue.empty()) winners.push_back(static_cast<int>(i));
  }
  if (winners.empty()) {
    schedule_access();
    return;
  }
  busy_ = true;
  if (winners.size() == 1) transmit(winners.front(), now);
  else collide(winners);
}

des::Time Bss::ppdu_limit(const Station& s, des::Time txop_start) const {
  const des::Time limit = s.backoff.params().txop_limit;
  if (limit == des::Time::zero()) return mac_.max_ppdu;
  // The PPDU and its BlockAck must end within the TXOP.
  const des::Time left = txop_start + limit - sim_.now() - mac_.sifs - phy_.control_duration(mac_.framing.block_ack_bytes);
  return std::min(mac_.max_ppdu, left);
}

Bss::Flight Bss::launch(int station, des::Time txop_start, bool collided) {
  Station& s = stations_[static_cast<size_t>(station)];
  Flight f{station, aggregate(s.queue, phy_, mac_, ppdu_limit(s, txop_start)), {}, sim_.now()};
  ++counts_.ppdus;
  for (size_t k = 0; k < f.ampdu.positions.size(); ++k) {
    const Packet& p = s.queue[f.ampdu.positions[k]];
    ++counts_.mpdu_attempts;
    if (p.retries > 0) ++counts_.retransmissions;
    bool ok = !collided;
    if (ok && f.ampdu.to >= 0) {
      if (forced_loss_ && forced_loss_(p)) ok = false;
      else if (error_rate_ > 0.0 && errors_.bernoulli(error_rate_)) ok = false;
    }
    f.received.push_back(ok);
  }
  return f;
}

void Bss::transmit(int station, des::Time txop_start) {
  Station& s = stations_[static_cast<size_t>(station)];
  drop_expired(s);
  if (s.queue.empty()) {
    // Everything left expired during the TXOP: it ends here.
    s.backoff.draw(sim_.now(), s.stream);
    release(sim_.now() + mac_.sifs);
    return;
  }
  Flight f = launch(station, txop_start, false);
  const des::Time t0 = sim_.now();
  for (size_t k = 0; k < f.ampdu.positions.size(); ++k) {
    if (!f.received[k]) continue;
    const Packet p = s.queue[f.ampdu.positions[k]];
    sim_.at(t0 + f.ampdu.received_at[k], kind_rx_, [this, p] {
      ++counts_.delivered;
      if (delivered_) delivered_(p, sim_.now());
    });
  }
  const bool broadcast = f.ampdu.to < 0;
  const bool answered = !broadcast && std::find(f.received.begin(), f.received.end(), true) != f.received.end();
  const des::Time t1 = t0 + f.ampdu.duration;
  des::Time end = t1;
  if (answered) end = t1 + mac_.sifs + f.ampdu.response;
  else if (!broadcast) end = t1 + mac_.sifs + mac_.slot + mac_.response_preamble;
  counts_.busy += f.ampdu.duration + (answered ? f.ampdu.response : des::Time::zero());
  sim_.at(end, kind_end_, [this, f = std::move(f), answered, txop_start] {
    finish(f, answered);
    Station& st = stations_[static_cast<size_t>(f.station)];
    if (answered && may_continue(st, txop_start)) {
      // The TXOP goes on: the next PPDU a SIFS after the response.
      sim_.at(sim_.now() + mac_.sifs, kind_access_, [this, station = f.station, txop_start] {
        transmit(station, txop_start);
      });
      return;
    }
    st.backoff.draw(sim_.now(), st.stream);
    const des::Time t1_end = f.start + f.ampdu.duration;
    if (answered || f.ampdu.to < 0) {
      release(sim_.now() + mac_.sifs);
      return;
    }
    // Unanswered: the sender timed out now; the receiver, who received it in
    // error, waits an EIFS; the others kept the medium reserved for the response.
    const des::Time eifs = mac_.sifs + PhyRate::legacy_duration(mac_.framing.ack_bytes, 6);
    for (size_t i = 0; i < stations_.size(); ++i) {
      if (static_cast<int>(i) == f.station) stations_[i].access = sim_.now() + mac_.sifs;
      else if (static_cast<int>(i) == f.ampdu.to) stations_[i].access = t1_end + mac_.sifs + eifs;
      else stations_[i].access = t1_end + mac_.sifs + f.ampdu.response + mac_.sifs;
    }
    busy_ = false;
    schedule_access();
  });
}

bool Bss::may_continue(const Station& s, des::Time txop_start) const {
  const des::Time limit = s.backoff.params().txop_limit;
  if (limit == des::Time::zero() || s.queue.empty()) return false;
  const int64_t first = mac_.framing.delimiter_bytes + mac_.framing.mpdu_bytes(s.queue.front().bytes);
  const des::Time need = mac_.sifs + phy_.ppdu_duration(first) + mac_.sifs + phy_.control_duration(mac_.framing.ack_bytes);
  return sim_.now() + need <= txop_start + limit;
}

void Bss::finish(const Flight& f, bool answered) {
  Station& s = stations_[static_cast<size_t>(f.station)];
  // Back to front, so that erasing leaves the earlier positions valid.
  for (size_t k = f.ampdu.positions.size(); k-- > 0;) {
    const size_t pos = f.ampdu.positions[k];
    if (f.received[k] || f.ampdu.to < 0) {
      s.queue.erase(s.queue.begin() + static_cast<std::ptrdiff_t>(pos));
      continue;
    }
    if (++s.queue[pos].retries > mac_.retry_limit) lose(s, pos, LossReason::retry_limit);
  }
  if (answered || f.ampdu.to < 0) s.backoff.reset_cw();
  else s.backoff.double_cw();
}

void Bss::collide(const std::vector<int>& stations) {
  ++counts_.collisions;
  std::vector<Flight> flights;
  des::Time busy_end, last_timeout;
  for (int st : stations) {
    flights.push_back(launch(st, sim_.now(), true));
    const des::Time t1 = sim_.now() + flights.back().ampdu.duration;
    busy_end = std::max(busy_end, t1);
    last_timeout = std::max(last_timeout, t1 + mac_.sifs + mac_.slot + mac_.response_preamble);
  }
  counts_.busy += busy_end - sim_.now();
  sim_.at(last_timeout, kind_end_, [this, flights = std::move(flights), busy_end] {
    const des::Time eifs = mac_.sifs + PhyRate::legacy_duration(mac_.framing.ack_bytes, 6);
    // The others received the first PPDU in error: an EIFS after it, and no
    // earlier than SIFS after the medium went quiet.
    const des::Time first_end = flights.front().start + flights.front().ampdu.duration;
    const des::Time others = std::max(first_end + mac_.sifs + eifs, busy_end + mac_.sifs);
    for (Station& s : stations_) s.access = others;
    for (const Flight& f : flights) {
      finish(f, false);
      Station& s = stations_[static_cast<size_t>(f.station)];
      const des::Time timeout = f.start + f.ampdu.duration + mac_.sifs + mac_.slot + mac_.response_preamble;
      s.access = std::max(timeout, busy_end) + mac_.sifs;
      s.backoff.draw(timeout, s.stream);
    }
    busy_ = false;
    schedule_access();
  });
}

void Bss::release(des::Time idle_from) {
  for (Station& s : stations_) s.access = idle_from;
  busy_ = false;
  schedule_access();
}

}  // namespace latsim::radio
