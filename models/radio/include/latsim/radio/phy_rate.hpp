// The Wi-Fi physical layer's timing: data rate from MCS, channel width and
// spatial streams, and the airtime of a PPDU (preamble plus OFDM symbols),
// for 802.11ac (VHT) and 802.11ax (HE) single-user PPDUs, and the legacy
// OFDM PPDUs that carry control responses (Ack, BlockAck).
#pragma once

#include <cstdint>
#include <string>

#include "latsim/des/time.hpp"

namespace latsim::radio {

/// Which amendment's PPDU format carries the data.
enum class Standard { vht, he };

/// How the data PPDUs are sent (a fixed rate: no rate adaptation).
struct PhyParams {
  Standard standard = Standard::vht;
  int mcs = 9;                   ///< VHT 0-9, HE 0-11
  int channel_width_mhz = 80;    ///< 20, 40, 80 or 160
  int spatial_streams = 2;       ///< 1-8
  /// Guard interval: VHT 800 or 400 ns; HE 800, 1600 or 3200 ns.
  int guard_interval_ns = 800;
  /// Control responses (Ack, BlockAck) at this legacy OFDM rate: 6, 9, 12,
  /// 18, 24, 36, 48 or 54 Mb/s (the highest basic rate not above the data
  /// frame's non-HT reference rate; 24 Mb/s when the basic rates are the
  /// mandatory 6, 12 and 24).
  int control_rate_mbps = 24;
};

/// Data rate and PPDU airtime of one PHY configuration, exact in picoseconds.
///
/// Data bits per OFDM symbol N_DBPS = N_SD · N_BPSCS · N_SS · R (data
/// subcarriers, coded bits per subcarrier, streams, code rate); a VHT
/// combination where that is not a whole number is not defined by the
/// standard (e.g. 20 MHz MCS 9 on one stream) and is refused, HE rounds it
/// down. A PSDU of
/// L bytes takes ceil((16 + 8 L + 6 N_ES) / N_DBPS) symbols after the
/// preamble (16 service bits, 6 tail bits per BCC encoder, N_ES encoders).
class PhyRate {
 public:
  /// Throws std::invalid_argument naming the parameter for an undefined combination.
  explicit PhyRate(PhyParams params);

  const PhyParams& params() const { return p_; }
  /// Data bits per OFDM symbol.
  int64_t bits_per_symbol() const { return n_dbps_; }
  /// One OFDM data symbol (VHT: 3.2 µs + GI; HE: 12.8 µs + GI).
  des::Time symbol() const { return symbol_; }
  /// PHY data rate in bit/s (N_DBPS / symbol).
  double data_rate_bps() const;
  /// Preamble and PHY headers before the first data symbol.
  des::Time preamble() const { return preamble_; }
  /// Airtime of a data PPDU carrying `psdu_bytes`.
  des::Time ppdu_duration(int64_t psdu_bytes) const;
  /// From the PPDU's start to the end of the symbol that carries its first
  /// `bytes` bytes: when a receiver has an MPDU ending there.
  des::Time bytes_received_after(int64_t bytes) const;
  /// Airtime of a legacy (802.11a OFDM) PPDU of `bytes` at `rate_mbps`:
  /// 20 µs of preamble and SIGNAL, then 4 µs symbols of 4 · rate bits
  /// carrying 16 service bits, the bytes and 6 tail bits.
  static des::Time legacy_duration(int64_t bytes, int rate_mbps);
  /// The control response rate's airtime for `bytes` (Ack: 14, BlockAck: 32).
  des::Time control_duration(int64_t bytes) const { return legacy_duration(bytes, p_.control_rate_mbps); }
  /// One line for messages: "VHT MCS 9, 80 MHz, 2 streams, 866.7 Mb/s".
  std::string describe() const;

 private:
  int64_t data_symbols(int64_t bytes) const;

  PhyParams p_;
  int64_t n_dbps_ = 0;
  int n_es_ = 1;
  des::Time symbol_;
  des::Time preamble_;
};

}  // namespace latsim::radio
