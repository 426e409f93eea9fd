// A Wi-Fi basic service set as a packet-level process: stations (an access
// point and its clients) on one channel, each contending for it with EDCA,
// sending aggregated MPDUs and retransmitting what was lost.
#pragma once

#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "latsim/des/random.hpp"
#include "latsim/des/simulator.hpp"
#include "latsim/radio/ampdu.hpp"
#include "latsim/radio/edca.hpp"
#include "latsim/radio/mac_params.hpp"
#include "latsim/radio/packet.hpp"
#include "latsim/radio/phy_rate.hpp"

namespace latsim::radio {

/// What the channel did over a run.
struct LinkCounts {
  int64_t ppdus = 0;            ///< PPDUs sent (a collision counts each)
  int64_t collisions = 0;       ///< accesses where two or more stations transmitted at once
  int64_t mpdu_attempts = 0;    ///< MPDU transmissions, first ones and retries
  int64_t retransmissions = 0;  ///< MPDU transmissions after the first
  int64_t delivered = 0;
  int64_t lost = 0;
  des::Time busy;               ///< airtime of PPDUs and responses (overlaps counted once)
};

/// Every station shares one channel: one transmission at a time, or a
/// collision when two backoffs expire at the same slot boundary (both fail).
///
/// A station's queue is first in, first out; when it wins the channel it
/// sends one A-MPDU to the receiver of its oldest packet (ampdu.hpp) and, with
/// a TXOP limit, more after a SIFS while they fit. Each MPDU is lost with the
/// link's error rate (or when the forced-loss rule says so) and retransmitted
/// in a later A-MPDU until the retry limit; an A-MPDU none of whose MPDUs
/// arrive, or that collided, goes unanswered and doubles its sender's
/// contention window. The receiver has each MPDU at the end of the symbol
/// carrying its last byte. After a busy medium every station waits SIFS;
/// a transmitter whose response did not come waits for its timeout, and the
/// stations that received a collision an EIFS.
class Bss {
 public:
  /// `kind` prefixes the event kinds ("radio" -> "radio.access", ...).
  Bss(des::Simulator& sim, PhyRate phy, MacParams mac, des::RandomStream stream, const std::string& kind = "radio");
  Bss(const Bss&) = delete;
  Bss& operator=(const Bss&) = delete;

  /// Adds a station contending with `edca`; returns its index (0, 1, ...).
  int add_station(const std::string& name, EdcaParams edca);
  /// The access point (station `ap`) sends a beacon of `bytes` (its whole
  /// frame) every `interval` from `first`, at the highest priority (AIFSN 1,
  /// no backoff), as one 6 Mb/s PPDU; until `end`.
  void send_beacons(int ap, des::Time first, des::Time interval, int64_t bytes, des::Time end);
  /// Queues a packet of `bytes` now at station `from` for station `to`;
  /// returns its id. A full queue drops it at once (on_lost).
  int64_t send(int from, int to, int64_t bytes, int64_t tag);

  /// Each MPDU transmission is lost with this probability (independently).
  void set_error_rate(double per_mpdu);
  /// Called for every MPDU transmission before the error rate: true loses it.
  void set_forced_loss(std::function<bool(const Packet&)> rule) { forced_loss_ = std::move(rule); }
  /// A packet reached its receiver at the given instant (an event at that instant).
  void on_delivered(std::function<void(const Packet&, des::Time)> fn) { delivered_ = std::move(fn); }
  void on_lost(std::function<void(const Packet&, LossReason)> fn) { lost_ = std::move(fn); }

  const PhyRate& phy() const { return phy_; }
  const MacParams& mac() const { return mac_; }
  const LinkCounts& counts() const { return counts_; }
  int stations() const { return static_cast<int>(stations_.size()); }
  const std::string& station_name(int i) const { return stations_.at(static_cast<size_t>(i)).name; }
  /// Packets waiting (or in flight) at station i.
  size_t queued(int i) const { return stations_.at(static_cast<size_t>(i)).queue.size(); }

 private:
  struct Station {
    std::string name;
    Backoff backoff;
    des::RandomStream stream;
    std::deque<Packet> queue;
    des::Time access;  ///< the medium counts as idle for it from here
  };
  /// One PPDU in the air and what became of its MPDUs.
  struct Flight {
    int station = 0;
    Ampdu ampdu;
    std::vector<bool> received;
    des::Time start;
  };

  void enqueue(Station& s, Packet p);
  void schedule_access();
  void on_access();
  des::Time ppdu_limit(const Station& s, des::Time txop_start) const;
  Flight launch(int station, des::Time txop_start, bool collided);
  void transmit(int station, des::Time txop_start);
  void collide(const std::vector<int>& stations);
  void finish(const Flight& f, bool answered);
  bool may_continue(const Station& s, des::Time txop_start) const;
  void release(des::Time idle_from);
  void drop_expired(Station& s);
  void lose(Station& s, size_t position, LossReason why);

  des::Simulator& sim_;
  PhyRate phy_;
  MacParams mac_;
  des::RandomStream errors_;
  double error_rate_ = 0.0;
  std::deque<Station> stations_;
  int beacon_station_ = -1;
  bool busy_ = false;
  des::EventId pending_access_;
  des::KindId kind_access_ = 0, kind_end_ = 0, kind_rx_ = 0, kind_beacon_ = 0;
  int64_t next_id_ = 0;
  LinkCounts counts_;
  std::function<bool(const Packet&)> forced_loss_;
  std::function<void(const Packet&, des::Time)> delivered_;
  std::function<void(const Packet&, LossReason)> lost_;
  std::unique_ptr<des::RandomStream> station_streams_;  ///< parent of each station's own stream
};

}  // namespace latsim::radio
