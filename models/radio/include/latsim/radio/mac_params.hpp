// The MAC's timing, framing and limits of one basic service set.
#pragma once

#include <cstdint>

#include "latsim/des/time.hpp"

namespace latsim::radio {

/// Bytes a packet takes on the air, and the responses' sizes.
struct Framing {
  /// MAC header of a QoS data frame: frame control 2, duration 2, three
  /// addresses 18, sequence control 2, QoS control 2.
  int64_t mac_header_bytes = 26;
  int64_t llc_snap_bytes = 8;    ///< LLC/SNAP encapsulation of the packet
  int64_t fcs_bytes = 4;
  int64_t delimiter_bytes = 4;   ///< MPDU delimiter of an A-MPDU subframe
  int64_t ack_bytes = 14;
  int64_t block_ack_bytes = 32;  ///< compressed BlockAck with a 64-bit bitmap

  /// An MPDU carrying a packet of `packet_bytes` (the IP datagram).
  int64_t mpdu_bytes(int64_t packet_bytes) const { return packet_bytes + llc_snap_bytes + mac_header_bytes + fcs_bytes; }
};

/// Channel access timing and the limits of aggregation, retries and queues.
struct MacParams {
  des::Time slot = des::Time::us(9);   ///< aSlotTime (OFDM, 5 and 6 GHz)
  des::Time sifs = des::Time::us(16);  ///< aSIFSTime (5 and 6 GHz)
  int64_t max_ampdu_bytes = 65535;     ///< the recipient's maximum A-MPDU length
  int max_ampdu_mpdus = 64;            ///< block-ack window: MPDUs in one A-MPDU at most
  des::Time max_ppdu = des::Time::us(5484);  ///< aPPDUMaxTime (VHT and HE)
  int retry_limit = 7;                 ///< retransmissions of an MPDU before it is discarded
  int64_t queue_packets = 500;         ///< per station: a packet arriving at a full queue is dropped
  des::Time queue_max_delay = des::Time::ms(500);  ///< a packet waiting longer is discarded
  /// A lost or unanswered PPDU: its transmitter waits SIFS + slot + the
  /// response's PHY preamble (20 µs) for the response before it may count
  /// again; the others, who received it in error, wait an EIFS (SIFS + an
  /// Ack at 6 Mb/s, 60 µs, more than SIFS).
  des::Time response_preamble = des::Time::us(20);
  Framing framing;
};

}  // namespace latsim::radio
