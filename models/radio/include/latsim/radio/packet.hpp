// What the radio link carries: packets handed to a station's MAC, and why one
// may never arrive.
#pragma once

#include <cstdint>
#include <string_view>

#include "latsim/des/time.hpp"

namespace latsim::radio {

/// One packet (an IP datagram) queued at a station for another station.
struct Packet {
  int64_t id = -1;      ///< the link's number, in order of sending
  int from = 0;         ///< station index
  int to = 0;           ///< station index; -1: broadcast (a beacon)
  int64_t bytes = 0;    ///< the datagram (what LLC/SNAP carries)
  int64_t tag = 0;      ///< the sender's own label (a frame and slice, a pose report)
  des::Time enqueued;   ///< when it was handed to the MAC
  int retries = 0;      ///< transmissions after the first so far
};

/// Why a packet was discarded before it arrived.
enum class LossReason {
  queue_full,   ///< its station's queue was full when it was sent
  expired,      ///< it waited longer than the queue's maximum delay
  retry_limit,  ///< its last allowed transmission failed
};

/// "queue_full", "expired", "retry_limit".
std::string_view loss_reason_name(LossReason r);

}  // namespace latsim::radio
