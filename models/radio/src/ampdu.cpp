#include "latsim/radio/ampdu.hpp"

#include <stdexcept>

namespace latsim::radio {

std::string_view loss_reason_name(LossReason r) {
  switch (r) {
    case LossReason::queue_full: return "queue_full";
    case LossReason::expired: return "expired";
    case LossReason::retry_limit: return "retry_limit";
  }
  return "unknown";
}

namespace {

int64_t padded(int64_t bytes) { return (bytes + 3) / 4 * 4; }

}  // namespace

Ampdu aggregate(const std::deque<Packet>& queue, const PhyRate& phy, const MacParams& mac, des::Time max_duration) {
  if (queue.empty()) throw std::logic_error("aggregate: nothing queued");
  Ampdu a;
  a.to = queue.front().to;
  if (a.to < 0) {
    // A broadcast management frame (a beacon): the whole frame at the lowest rate, unanswered.
    a.positions.push_back(0);
    a.psdu_bytes = queue.front().bytes;
    a.duration = PhyRate::legacy_duration(a.psdu_bytes, 6);
    a.received_at.push_back(a.duration);
    return a;
  }
  const Framing& f = mac.framing;
  // Bytes up to the end of the last MPDU taken (no padding after it).
  int64_t closed = 0;
  for (size_t i = 0; i < queue.size() && static_cast<int>(a.positions.size()) < mac.max_ampdu_mpdus; ++i) {
    const Packet& p = queue[i];
    if (p.to != a.to) continue;
    const int64_t start = padded(closed);
    const int64_t end = start + f.delimiter_bytes + f.mpdu_bytes(p.bytes);
    if (!a.positions.empty() && (end > mac.max_ampdu_bytes || phy.ppdu_duration(end) > max_duration)) break;
    a.positions.push_back(i);
    a.received_at.push_back(phy.bytes_received_after(end));
    closed = end;
  }
  a.psdu_bytes = closed;
  a.duration = phy.ppdu_duration(closed);
  a.block_ack = a.positions.size() > 1;
  a.response = phy.control_duration(a.block_ack ? f.block_ack_bytes : f.ack_bytes);
  return a;
}

}  // namespace latsim::radio
