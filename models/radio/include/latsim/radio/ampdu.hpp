// What one PPDU carries: the packets aggregated into an A-MPDU for one
// receiver, its size, its airtime and when each MPDU is received.
#pragma once

#include <cstdint>
#include <deque>
#include <vector>

#include "latsim/des/time.hpp"
#include "latsim/radio/mac_params.hpp"
#include "latsim/radio/packet.hpp"
#include "latsim/radio/phy_rate.hpp"

namespace latsim::radio {

/// One PPDU's contents and timing, relative to its start.
struct Ampdu {
  int to = 0;                          ///< receiver (-1: a broadcast)
  std::vector<size_t> positions;       ///< the packets' positions in the sender's queue, in order
  int64_t psdu_bytes = 0;
  des::Time duration;                  ///< airtime of the PPDU
  std::vector<des::Time> received_at;  ///< per MPDU: end of the symbol carrying its last byte
  des::Time response;                  ///< Ack or BlockAck airtime; zero for a broadcast (none)
  bool block_ack = false;              ///< several MPDUs: a BlockAck answers (one MPDU: an Ack)
};

/// Aggregates, in queue order, the packets for the receiver of the queue's
/// first packet while the A-MPDU stays within the MAC's limits (bytes,
/// MPDUs) and the PPDU within `max_duration` (at least the first packet is
/// taken). A VHT or HE PSDU is always an A-MPDU: each MPDU in a subframe
/// with a 4-byte delimiter, padded to 4 bytes except the last. A broadcast
/// (to -1) is one legacy PPDU at 6 Mb/s without a response.
Ampdu aggregate(const std::deque<Packet>& queue, const PhyRate& phy, const MacParams& mac, des::Time max_duration);

}  // namespace latsim::radio
